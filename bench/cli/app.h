// The `ocpbench` command-line program: subcommands register themselves on one CLI11 app.
#pragma once

namespace CLI {
class App;
}  // namespace CLI

namespace ocpb {

/// Exit codes of `ocpbench`.
enum ExitCode : int {
  kExitOk = 0,            ///< everything ran and every case succeeded
  kExitSomeFailed = 1,    ///< everything ran; some solves ended with a failure status
  kExitBadInput = 2,      ///< invalid input (one-line message on stderr); nothing was run
  kExitInternalError = 3, ///< an unexpected error
};

/// `ocpbench list problems|solvers|transcriptions`.
void AddListCommand(CLI::App& app);
/// `ocpbench solve --problem P --solver S [...] [--json FILE]`.
void AddSolveCommand(CLI::App& app);
/// `ocpbench run SUITE.json [--out DIR] [--resume|--overwrite] [--shard i/n]`, `ocpbench merge DIR`.
void AddRunCommand(CLI::App& app);

/// Builds the app with every subcommand and runs it on argv; returns the process exit code.
/// All errors are reported as one line "ocpbench: error: ..." on stderr.
int RunOcpbench(int argc, char** argv);

/// Subcommands set this when their work ran but some cases failed.
void ReportSomeFailed();

}  // namespace ocpb
