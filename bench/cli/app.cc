#include "bench/cli/app.h"

#include <cerrno>
#include <csignal>
#include <exception>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "bench/cli/main.h"
#include "bench/cli/version.h"
#include "core/input_file.h"

namespace ocpb {
namespace {
bool g_some_failed = false;
bool g_incomplete = false;
}  // namespace

void ReportSomeFailed() { g_some_failed = true; }
void ReportIncomplete() { g_incomplete = true; }

Integrator ParseFlagIntegrator(const std::string& flag, const std::string& text) {
  try {
    return ParseIntegrator(text);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(flag + ": " + e.what());
  }
}

OptionMap ParseKeyValues(const std::vector<std::string>& items, const std::string& flag) {
  OptionMap out;
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw std::invalid_argument("malformed " + flag + " '" + item + "': expected key=value");
    }
    out.Set(item.substr(0, eq), item.substr(eq + 1));
  }
  return out;
}

namespace {

// "run " when the command line named a command, else "".
std::string CommandName(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) return sub->get_name() + " ";
  return "";
}

// CLI11's "Could not convert: --jobs = abc" with the rule: "--jobs 'abc': must be an integer".
std::string ConversionRule(const CLI::App& app, const std::string& message) {
  const std::string lead = "Could not convert: ";
  const auto eq = message.find(" = ");
  if (message.rfind(lead, 0) != 0 || eq == std::string::npos) return message;
  const std::string name = message.substr(lead.size(), eq - lead.size());
  const std::string value = message.substr(eq + 3);
  std::string type;
  for (const CLI::App* sub : app.get_subcommands()) {
    if (const CLI::Option* option = sub->get_option_no_throw(name)) type = option->get_type_name();
  }
  const std::string rule = type == "INT"     ? "must be an integer"
                           : type == "UINT"  ? "must be an integer >= 0"
                           : type == "FLOAT" ? "must be a number"
                                             : "is not a value of this option's type";
  return name + " '" + value + "': " + rule;
}

}  // namespace

int Main(int argc, char** argv) {
  g_some_failed = false;
  g_incomplete = false;
  // Past a file-size limit (RLIMIT_FSIZE) a write then fails with EFBIG, which the writers turn
  // into an error that keeps the records file whole, instead of the signal killing the process
  // mid-record.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{
      "OCPBench: optimal-control problems solved by Hamiltonian descent and by sparse NLPs",
      "ocpbench"};
  app.set_version_flag("--version", VersionString());
  app.require_subcommand(1);
  AddListCommand(app);
  AddSolveCommand(app);
  AddRunCommand(app);
  AddMergeCommand(app);
  AddChannelCommand(app);
  AddOnlineCommand(app);
  AddCompareCommand(app);
  AddReportCommand(app);
  try {
    // Name an unknown command plainly (CLI11 alone would say "A subcommand is required").
    if (argc >= 2 && argv[1][0] != '-') {
      std::string valid;
      bool known = false;
      for (const CLI::App* sub : app.get_subcommands({})) {
        known = known || sub->get_name() == argv[1];
        valid += (valid.empty() ? "" : ", ") + sub->get_name();
      }
      if (!known) {
        throw std::invalid_argument("unknown command '" + std::string(argv[1]) +
                                    "' (valid: " + valid + ")");
      }
    }
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // Every message is one line, whatever the input it quotes holds (OneLine escapes newlines).
    std::cerr << "ocpbench: error: " << OneLine(ConversionRule(app, e.what())) << " (see ocpbench "
              << CommandName(app) << "--help)\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "ocpbench: error: " << OneLine(e.what()) << "\n";
    return kExitBadInput;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path the system cannot follow for a reason in the path itself (a loop of symbolic
    // links, a name longer than the file system allows, a file where a folder should be) is
    // input at fault, wherever it is met. The commands check their paths before any work
    // (FilePlan, bench/cli/output_place.h); this is the net under those checks.
    const int code = e.code().value();
    std::cerr << "ocpbench: error: " << OneLine(e.what()) << "\n";
    return code == ELOOP || code == ENAMETOOLONG || code == ENOTDIR ? kExitBadInput
                                                                    : kExitInternalError;
  } catch (const std::exception& e) {
    std::cerr << "ocpbench: error: " << OneLine(e.what()) << "\n";
    return kExitInternalError;
  }
  if (g_incomplete) return kExitIncomplete;
  return g_some_failed ? kExitSomeFailed : kExitOk;
}

}  // namespace ocpb
