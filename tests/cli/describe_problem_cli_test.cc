// `ocpbench describe problem` tells a user the problem's sizes and which parts of the problem
// class it uses (they decide which methods take it).
#include <string>

#include <gtest/gtest.h>

#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

using testing::ProgramRun;
using testing::RunOcpbenchProgram;

TEST(DescribeProblemCli, NamesSizesAndFeatures) {
  const ProgramRun parameter =
      RunOcpbenchProgram({"describe", "problem", "double-integrator-time-parameter"});
  ASSERT_EQ(parameter.exit_code, 0) << parameter.err;
  EXPECT_NE(parameter.out.find("sizes: nx = 3, nu = 1, terminal constraints 2, path constraints "
                               "0, boundary constraints 0, static parameters 1"),
            std::string::npos)
      << parameter.out;
  EXPECT_NE(parameter.out.find("features: free initial state (ipopt and nlopt"), std::string::npos)
      << parameter.out;
  const ProgramRun coupled = RunOcpbenchProgram({"describe", "problem", "coupled-ends"});
  ASSERT_EQ(coupled.exit_code, 0) << coupled.err;
  EXPECT_NE(coupled.out.find("features: free initial state, boundary constraints"),
            std::string::npos)
      << coupled.out;
  const ProgramRun bounds = RunOcpbenchProgram({"describe", "problem", "bryson-denham-bounds"});
  EXPECT_NE(bounds.out.find("features: state bounds"), std::string::npos) << bounds.out;
  const ProgramRun free_time =
      RunOcpbenchProgram({"describe", "problem", "double-integrator-free-time"});
  EXPECT_NE(free_time.out.find("features: free final time"), std::string::npos) << free_time.out;
  const ProgramRun plain = RunOcpbenchProgram({"describe", "problem", "bryson-denham"});
  EXPECT_NE(plain.out.find("features: none (fixed horizon"), std::string::npos) << plain.out;
}

}  // namespace
}  // namespace ocpb
