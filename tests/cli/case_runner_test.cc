// In-process checks of the case runner: validation before solving, the memory estimate, and
// failures turned into records.
#include "bench/cli/case_runner.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace ocpb {
namespace {

using nlohmann::json;

CaseSpec Spec(const std::string& problem, const std::string& solver) {
  CaseSpec spec;
  spec.problem = problem;
  spec.solver = solver;
  return spec;
}

std::string ErrorOf(const CaseSpec& spec) {
  try {
    ValidateCase(spec);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(valid)";
}

TEST(ValidateCase, RunsTheSolversOptionParsers) {
  CaseSpec spec = Spec("double-integrator", "hamiltonian");
  EXPECT_EQ(ErrorOf(spec), "(valid)");
  spec.options["bogus"] = "1";
  EXPECT_EQ(ErrorOf(spec).rfind("hamiltonian: unknown option 'bogus'", 0), 0u) << ErrorOf(spec);
  spec = Spec("double-integrator", "ipopt");
  spec.transcription = "euler";
  spec.options["max_iter"] = "many";
  EXPECT_EQ(ErrorOf(spec), "ipopt option 'max_iter': 'many' is not an integer");
  spec.options = {{"state_scale", "-1,1"}};  // the transcription's scaling keys are checked too
  EXPECT_NE(ErrorOf(spec).find("state_scale"), std::string::npos) << ErrorOf(spec);
  spec = Spec("double-integrator", "nlopt");
  spec.transcription = "single-shooting";
  spec.algorithm = "NOPE";
  EXPECT_EQ(ErrorOf(spec).rfind("nlopt option 'algorithm': 'NOPE' is not one of: ", 0), 0u)
      << ErrorOf(spec);
  spec.algorithm = "LD_MMA";
  EXPECT_EQ(ErrorOf(spec), "(valid)");
  spec = Spec("double-integrator", "indirect-newton");
  spec.options = {{"warm_start", "hamiltonian"}, {"hamiltonian.alpah", "0.5"}};
  EXPECT_EQ(ErrorOf(spec).rfind("hamiltonian: unknown option 'alpah'", 0), 0u) << ErrorOf(spec);
  spec = Spec("double-integrator", "hamiltonian");
  spec.algorithm = "LD_MMA";
  EXPECT_EQ(ErrorOf(spec), "algorithm: only the nlopt solver takes one (solver 'hamiltonian')");
}

TEST(ValidateCase, RunsTheProblemsOwnChecksWithoutBuildingItsChannel) {
  CaseSpec spec = Spec("comm-path2d", "hamiltonian");
  EXPECT_EQ(ErrorOf(spec), "(valid)");
  spec.set = {"t0=40"};
  EXPECT_EQ(ErrorOf(spec), "comm-path2d: t0 must satisfy 0 <= t0 < tf");
  spec.set = {"xi=0"};  // allowed by the parameter's range, refused by the channel model
  EXPECT_EQ(ErrorOf(spec), "channel: xi must be finite and > 0 (dB)");
  spec = Spec("comm-fixed-path", "hamiltonian");
  spec.set = {"W=20,40"};  // W = S: a zero-length segment
  EXPECT_EQ(ErrorOf(spec), "path: consecutive waypoints must differ");
}

TEST(MemoryEstimate, GrowsWithTheGridAndTheSparseSolvers) {
  CaseSpec h = Spec("double-integrator", "hamiltonian");
  // nx = 2, nu = 1: 512 * 3 bytes per node.
  EXPECT_DOUBLE_EQ(EstimateCaseMemoryBytes(h, 2, 1, 99), 512.0 * 3 * 100);
  CaseSpec ipopt = Spec("double-integrator", "ipopt");
  ipopt.transcription = "hermite-simpson";  // m = 2: nodes = 2 N + 1
  const double nodes = 2 * 99 + 1;
  EXPECT_DOUBLE_EQ(EstimateCaseMemoryBytes(ipopt, 2, 1, 99),
                   512.0 * 3 * nodes + 320.0 * nodes * 3 * (3 + 3 * 2));
  EXPECT_GT(CaseMemoryBudgetBytes(), 1e8);
  // The paper's grid passes; a billion intervals do not.
  EXPECT_EQ(ErrorOf(h), "(valid)");
  h.intervals = 1000000000;
  EXPECT_NE(ErrorOf(h).find("N: 1000000000 intervals need about 1.54 TB by OCPBench's estimate"),
            std::string::npos)
      << ErrorOf(h);
  EXPECT_NE(ErrorOf(h).find("beyond this machine's memory budget of"), std::string::npos);
}

TEST(RunCaseRecordingFailures, AnyExceptionBecomesTheCasesRecord) {
  const CaseSpec spec = Spec("double-integrator", "hamiltonian");
  const json error = RunCaseRecordingFailures(
      spec, [](const CaseSpec&) -> json { throw std::runtime_error("the channel went away"); });
  EXPECT_EQ(error["status"], "error");
  EXPECT_EQ(error["solver_status"], "exception");
  EXPECT_EQ(error["message"], "the channel went away");
  EXPECT_EQ(error["key"], spec.Key());
  EXPECT_TRUE(IsFailure(error["status"].get<std::string>()));
  const json invalid = RunCaseRecordingFailures(
      spec, [](const CaseSpec&) -> json { throw std::invalid_argument("bad once built"); });
  EXPECT_EQ(invalid["status"], "invalid_input");
  EXPECT_EQ(invalid["message"], "bad once built");
  const json fine = RunCaseRecordingFailures(spec, [](const CaseSpec&) {
    return json{{"status", "converged"}};
  });
  EXPECT_EQ(fine, (json{{"status", "converged"}}));
}

TEST(IsFailure, StatusNamesMatchTheEnum) {
  for (SolveStatus s : {SolveStatus::kConverged,
                        SolveStatus::kAcceptable,
                        SolveStatus::kMaxIterations,
                        SolveStatus::kMaxTime,
                        SolveStatus::kStepTooSmall,
                        SolveStatus::kRoundoffLimited,
                        SolveStatus::kInfeasible,
                        SolveStatus::kNumericalFailure,
                        SolveStatus::kInvalidInput,
                        SolveStatus::kNotApplicable,
                        SolveStatus::kError}) {
    EXPECT_EQ(IsFailure(std::string(ToString(s))), IsFailure(s)) << ToString(s);
  }
  EXPECT_FALSE(IsFailure(std::string("no-such-status")));
}

}  // namespace
}  // namespace ocpb
