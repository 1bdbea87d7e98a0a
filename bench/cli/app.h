// The `ocpbench` command-line program: subcommands register themselves on one CLI11 app. Only
// the command files include CLI11 (its global objects cost seconds per translation unit).
#pragma once

#include <string>
#include <vector>

#include "core/integrator.h"
#include "core/option_value.h"

namespace CLI {
class App;
}  // namespace CLI

namespace ocpb {

/// Exit codes of `ocpbench`.
enum ExitCode : int {
  kExitOk = 0,             ///< everything ran and every case succeeded
  kExitSomeFailed = 1,     ///< everything ran; some solves ended with a failure status
  kExitBadInput = 2,       ///< invalid input (one-line message on stderr); nothing was run
  kExitInternalError = 3,  ///< an unexpected error
  /// `merge` and `status`: cases of the suite are missing (or duplicated, or records of other
  /// cases are there); what was found was merged and its summary says it is partial.
  kExitIncomplete = 4,
};

/// `ocpbench list problems|solvers|transcriptions` and `ocpbench describe problem|solver|
/// transcription NAME` (every option with its default and rule).
void AddListCommand(CLI::App& app);
/// `ocpbench solve --problem P --solver S [...] [--json FILE]`.
void AddSolveCommand(CLI::App& app);
/// `ocpbench run SUITE.json [--out DIR] [--resume|--overwrite] [--shard i/n] [--jobs N]`.
void AddRunCommand(CLI::App& app);
/// `ocpbench merge DIR [--suite FILE]` and `ocpbench status DIR [--suite FILE]`
/// (bench/cli/merge_command.cc).
void AddMergeCommand(CLI::App& app);
/// `ocpbench channel simulate|predict` (bench/cli/channel_command.cc).
void AddChannelCommand(CLI::App& app);
/// `ocpbench online --problem comm-path2d --solver S [...]` (bench/cli/online_command.cc).
void AddOnlineCommand(CLI::App& app);
/// `ocpbench compare BASE NEW [...]`: two runs of one suite, case by case
/// (bench/cli/compare_command.cc).
void AddCompareCommand(CLI::App& app);
/// `ocpbench report DIR [NEW] [--out SITE]`: a suite's results as a static web site
/// (bench/cli/report_command.cc).
void AddReportCommand(CLI::App& app);

/// ParseIntegrator with the flag's name in the message: "--evaluate-with: unknown integrator
/// 'rk45' (valid: euler, rk4)".
Integrator ParseFlagIntegrator(const std::string& flag, const std::string& text);

/// Subcommands set this when their work ran but some cases failed.
void ReportSomeFailed();
/// `merge` and `status` set this when the suite's cases are not all there exactly once (exit
/// code kExitIncomplete, before kExitSomeFailed).
void ReportIncomplete();

/// "key=value" items of a repeatable flag (`--option`, `--replan-option`) as text values (each
/// resolved later by its owner's schema). Throws std::invalid_argument "malformed FLAG 'item':
/// expected key=value".
OptionMap ParseKeyValues(const std::vector<std::string>& items, const std::string& flag);

}  // namespace ocpb
