#include "bench/cli/app.h"

#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "bench/cli/channel_command.h"
#include "bench/cli/online_command.h"
#include "bench/cli/version.h"

namespace ocpb {
namespace {
bool g_some_failed = false;
}  // namespace

void ReportSomeFailed() { g_some_failed = true; }

int RunOcpbench(int argc, char** argv) {
  g_some_failed = false;
  CLI::App app{
      "OCPBench: optimal-control problems solved by Hamiltonian descent and by sparse NLPs",
      "ocpbench"};
  app.set_version_flag("--version", VersionString());
  app.require_subcommand(1);
  AddListCommand(app);
  AddSolveCommand(app);
  AddRunCommand(app);
  AddChannelCommand(app);
  AddOnlineCommand(app);
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
    std::cerr << "ocpbench: error: " << e.what() << " (see ocpbench --help)\n";
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "ocpbench: error: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "ocpbench: error: " << e.what() << "\n";
    return kExitInternalError;
  }
  return g_some_failed ? kExitSomeFailed : kExitOk;
}

}  // namespace ocpb
