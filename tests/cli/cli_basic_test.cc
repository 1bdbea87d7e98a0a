// End-to-end: `ocpbench --help`, `--version` and `list problems|solvers|transcriptions`.
#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "bench/cli/version.h"
#include "problems/registry.h"
#include "solvers/registry.h"
#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

using testing::ProgramRun;
using testing::RunOcpbenchProgram;

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

TEST(CliBasic, HelpNamesEveryCommand) {
  const ProgramRun run = RunOcpbenchProgram({"--help"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  for (const char* command : {"list", "solve", "run", "merge", "channel", "online"}) {
    EXPECT_NE(run.out.find(std::string("\n  ") + command + " "), std::string::npos)
        << command << " missing from:\n"
        << run.out;
  }
}

TEST(CliBasic, VersionIsOneLineWithTheLibraries) {
  const ProgramRun run = RunOcpbenchProgram({"--version"});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.out, VersionString() + "\n");
  EXPECT_EQ(run.out.rfind("ocpbench ", 0), 0u) << run.out;
  EXPECT_NE(run.out.find("Ipopt "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("NLopt "), std::string::npos) << run.out;
}

// `list WHAT` prints exactly the registry's names, in order, one per line.
void ExpectList(const std::string& what,
                const std::vector<std::string>& registry,
                const std::vector<std::string>& known) {
  const ProgramRun run = RunOcpbenchProgram({"list", what});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(run.err.empty()) << run.err;
  ASSERT_FALSE(run.out.empty());
  EXPECT_EQ(run.out.back(), '\n');
  const std::vector<std::string> lines = Lines(run.out);
  EXPECT_EQ(lines, registry);
  for (const std::string& line : lines) {
    EXPECT_FALSE(line.empty());
    EXPECT_EQ(line.find_first_of(" \t,"), std::string::npos) << "'" << line << "'";
  }
  for (const std::string& name : known) {
    EXPECT_NE(std::find(lines.begin(), lines.end(), name), lines.end()) << name;
  }
}

// The problems registered as a program starts, before any test of this binary registers one of
// its own (ValidateCase does), which the `ocpbench` program does not have: taken by a global
// test environment, which runs after static initialization and before the first test, so the
// comparison holds whatever tests the process runs and in whatever order.
std::vector<std::string>& ProblemsAtStart() {
  static std::vector<std::string> names;
  return names;
}
class RegistryAtStart : public ::testing::Environment {
 public:
  void SetUp() override {
    for (const ProblemInfo& p : Problems()) ProblemsAtStart().push_back(p.name);
  }
};
[[maybe_unused]] ::testing::Environment* const kRegistryAtStart =
    ::testing::AddGlobalTestEnvironment(new RegistryAtStart);

TEST(CliBasic, ListProblems) {
  ASSERT_FALSE(ProblemsAtStart().empty());
  ExpectList("problems", ProblemsAtStart(), {"double-integrator", "bryson-denham", "comm-path2d"});
}

TEST(CliBasic, ListSolvers) {
  std::vector<std::string> names;
  for (const SolverInfo& s : Solvers()) names.push_back(s.name);
  ExpectList("solvers", names, {"hamiltonian", "indirect-newton", "ipopt", "nlopt"});
}

TEST(CliBasic, ListTranscriptions) {
  std::vector<std::string> names;
  for (const TranscriptionInfo& t : Transcriptions()) names.push_back(t.name);
  ExpectList(
      "transcriptions", names, {"euler", "trapezoid", "hermite-simpson", "lgr", "single-shooting"});
}

}  // namespace
}  // namespace ocpb
