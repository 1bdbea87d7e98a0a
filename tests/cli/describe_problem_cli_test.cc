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

// Tags select problems (`list problems --tag`, every tag given), `list tags` says what each
// means, `describe problem` shows a problem's tags and references; an unknown tag is refused.
TEST(DescribeProblemCli, TagsSelectAndDescribe) {
  const ProgramRun free_time = RunOcpbenchProgram({"list", "problems", "--tag", "free-time"});
  ASSERT_EQ(free_time.exit_code, 0) << free_time.err;
  EXPECT_NE(free_time.out.find("goddard\n"), std::string::npos) << free_time.out;
  EXPECT_EQ(free_time.out.find("bryson-denham\n"), std::string::npos) << free_time.out;
  const ProgramRun both =
      RunOcpbenchProgram({"list", "problems", "--tag", "free-time", "--tag", "mayer"});
  ASSERT_EQ(both.exit_code, 0) << both.err;
  EXPECT_NE(both.out.find("goddard\n"), std::string::npos) << both.out;
  EXPECT_EQ(both.out.find("zermelo\n"), std::string::npos) << both.out;
  const ProgramRun tags = RunOcpbenchProgram({"list", "tags"});
  ASSERT_EQ(tags.exit_code, 0) << tags.err;
  EXPECT_NE(tags.out.find("singular-arc\t"), std::string::npos) << tags.out;
  const ProgramRun unknown = RunOcpbenchProgram({"list", "problems", "--tag", "smoth"});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.err.find("unknown tag 'smoth' (the tags: smooth,"), std::string::npos)
      << unknown.err;
  const ProgramRun solvers = RunOcpbenchProgram({"list", "solvers", "--tag", "smooth"});
  EXPECT_EQ(solvers.exit_code, 2);
  const ProgramRun goddard = RunOcpbenchProgram({"describe", "problem", "goddard"});
  EXPECT_NE(goddard.out.find("tags: singular-arc, free-time"), std::string::npos) << goddard.out;
  EXPECT_NE(goddard.out.find("reference J = -1.01283 (trapezoid NLP at N = 400;"),
            std::string::npos)
      << goddard.out;
  // The Ipopt options a reference's NLP needs, on the line under that reference
  // (make_library.py --peers reads it), only where the reference names some: jackson's N = 200
  // and 500, not its N = 2000.
  EXPECT_EQ(goddard.out.find("ipopt options"), std::string::npos) << goddard.out;
  const ProgramRun jackson = RunOcpbenchProgram({"describe", "problem", "jackson"});
  // The line under the reference at trapezoid N = n.
  const auto line_under = [&](const std::string& n) {
    const std::size_t at = jackson.out.find("(trapezoid NLP at N = " + n + ";");
    if (at == std::string::npos) return std::string("(no such reference)");
    const std::size_t begin = jackson.out.find('\n', at) + 1;
    return jackson.out.substr(begin, jackson.out.find('\n', begin) - begin);
  };
  EXPECT_EQ(line_under("200"), "  ipopt options its NLP needs: mu_strategy=adaptive")
      << jackson.out;
  EXPECT_EQ(line_under("500"), "  ipopt options its NLP needs: mu_strategy=adaptive")
      << jackson.out;
  EXPECT_EQ(line_under("2000").find("ipopt options"), std::string::npos) << jackson.out;
}

}  // namespace
}  // namespace ocpb
