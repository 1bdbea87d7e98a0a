// In-process checks of the case runner: validation before solving, the memory estimate, and
// failures turned into records.
#include "bench/cli/case_runner.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "bench/cli/online_case.h"
#include "problems/registry.h"
#include "tests/core/user_double_integrator.h"

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

TEST(ValidateCase, ResolvesTheMethodsOptionsByTheirSchemas) {
  CaseSpec spec = Spec("double-integrator", "hamiltonian");
  EXPECT_EQ(ErrorOf(spec), "(valid)");
  spec.options.Set("bogus", "1");
  EXPECT_EQ(ErrorOf(spec).rfind("options: hamiltonian: unknown option 'bogus' (valid: alpha, ", 0),
            0u)
      << ErrorOf(spec);
  spec = Spec("double-integrator", "ipopt");
  spec.transcription = "euler";
  spec.options.Set("max_iter", "many");
  EXPECT_EQ(ErrorOf(spec),
            "options: ipopt option 'max_iter': must be an integer >= 0 (got 'many')");
  spec.options = {{"state_scale", "-1,1"}};  // the transcription's scaling keys are checked too
  EXPECT_NE(ErrorOf(spec).find("euler option 'state_scale'"), std::string::npos) << ErrorOf(spec);
  spec.options = {{"nonsense", 1}};  // unknown to both: both lists are named
  EXPECT_NE(ErrorOf(spec).find("transcription euler: objective_scale"), std::string::npos)
      << ErrorOf(spec);
  spec = Spec("double-integrator", "nlopt");
  spec.transcription = "single-shooting";
  spec.algorithm = "NOPE";
  EXPECT_EQ(ErrorOf(spec).rfind("algorithm: nlopt option 'algorithm': must be one of: ", 0), 0u)
      << ErrorOf(spec);
  spec.algorithm = "LD_MMA";
  EXPECT_EQ(ErrorOf(spec), "(valid)");
  spec.options = {{"algorithm", "LD_SLSQP"}};  // the case field and the option disagree
  EXPECT_NE(ErrorOf(spec).find("disagrees"), std::string::npos) << ErrorOf(spec);
  spec = Spec("double-integrator", "indirect-newton");
  spec.options = {{"warm_start", "hamiltonian"}, {"hamiltonian.alpah", "0.5"}};
  EXPECT_EQ(ErrorOf(spec).rfind("options: indirect-newton: unknown option 'hamiltonian.alpah'", 0),
            0u)
      << ErrorOf(spec);
  spec.options = {{"hamiltonian.alpha", "0.5"}};  // a cross-field rule of the solver's
  EXPECT_NE(ErrorOf(spec).find("need warm_start = hamiltonian"), std::string::npos)
      << ErrorOf(spec);
  spec = Spec("double-integrator", "hamiltonian");
  spec.algorithm = "LD_MMA";
  EXPECT_EQ(ErrorOf(spec),
            "algorithm: solver 'hamiltonian' has no option 'algorithm' (it takes none)");
}

TEST(ResolveCase, GivesTypedValuesAndCanonicalKeys) {
  CaseSpec a = Spec("double-integrator", "ipopt");
  a.transcription = "lgr";
  a.options = {{"tol", "0.00000001"}, {"max_iter", "1e3"}};
  CaseSpec b = a;
  b.options = {{"tol", 1e-8}, {"max_iter", 1000}};
  EXPECT_EQ(ResolveCase(a).Key(), ResolveCase(b).Key());
  EXPECT_NE(ResolveCase(a).Key().find("|opt:max_iter=1000|opt:tol=1e-08"), std::string::npos)
      << ResolveCase(a).Key();
  EXPECT_EQ(ResolveCase(a).options.Find("max_iter")->integer(), 1000);
  const MethodOptions m = ResolveMethodOptions(a);
  EXPECT_EQ(m.transcription.Find("degree")->integer(), 3);  // LGR's degree from the case field
  EXPECT_FALSE(m.solver.Has("degree"));
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
  // Mesh refinement is sized by the largest mesh it may solve (mesh_max_nodes), not the first.
  ipopt.intervals = 10;
  ipopt.options = {{"mesh_tolerance", 1e-6}, {"mesh_max_nodes", 1000000001}};
  EXPECT_NE(ErrorOf(ipopt).find("mesh_max_nodes: 1000000000 intervals need about"),
            std::string::npos)
      << ErrorOf(ipopt);
  ipopt.options = {{"mesh_max_nodes", 1000000001}};  // refinement off: the first grid only
  EXPECT_EQ(ErrorOf(ipopt), "(valid)");
}

TEST(RunCaseRecordingFailures, AnyExceptionBecomesTheCasesRecord) {
  const CaseSpec spec = Spec("double-integrator", "hamiltonian");
  const Record error = RunCaseRecordingFailures(
      spec, [](const CaseSpec&) -> Record { throw std::runtime_error("the channel went away"); });
  EXPECT_EQ(error.status, "error");
  EXPECT_EQ(error.solver_status, "exception");
  EXPECT_EQ(error.message, "the channel went away");
  EXPECT_EQ(error.key, spec.Key());
  EXPECT_TRUE(IsFailure(error.status));
  const Record invalid = RunCaseRecordingFailures(
      spec, [](const CaseSpec&) -> Record { throw std::invalid_argument("bad once built"); });
  EXPECT_EQ(invalid.status, "invalid_input");
  EXPECT_EQ(invalid.message, "bad once built");
  const Record fine = RunCaseRecordingFailures(spec, [](const CaseSpec&) {
    Record r;
    r.status = "converged";
    return r;
  });
  EXPECT_EQ(fine.status, "converged");
}

TEST(Record, RoundTripsThroughJsonAndNamesTheFieldOfAWrongType) {
  CaseSpec spec = Spec("double-integrator", "hamiltonian");
  spec.intervals = 20;
  spec.options = {{"max_iterations", 5}};
  const Record r = RunCase(spec);
  EXPECT_EQ(r.schema_version, kRecordSchemaVersion);
  EXPECT_EQ(r.solver_options.at("max_iterations"), 5);
  EXPECT_EQ(r.solver_options.at("alpha"), 0.1);  // defaults are listed too
  const json j = r.ToJson();
  EXPECT_EQ(Record::FromJson(j).ToJson(), j);
  json bad = j;
  bad["J_fine"] = "low";
  try {
    Record::FromJson(bad);
    ADD_FAILURE() << "accepted a text J_fine";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "J_fine: must be a number or null");
  }
  bad = j;
  bad["schema_version"] = kRecordSchemaVersion + 1;
  EXPECT_THROW(Record::FromJson(bad), std::invalid_argument);
  json old = j;  // a record from before the typed record: no schema_version
  old.erase("schema_version");
  EXPECT_EQ(Record::FromJson(old).schema_version, 1);
}

// A user's problem whose SetDimensions disagrees with its AutoDiffOcp template arguments: the
// case is refused before anything runs (ocpbench exits 2), naming the dimension.
TEST(ValidateCase, RefusesAProblemThatStatesItsDimensionsTwiceDifferently) {
  ProblemInfo info;
  info.name = "case-runner-test-two-dimensions";
  info.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<testing::UserDoubleIntegrator>(/*declared_npsi=*/1);
  };
  RegisterProblem(info);
  CaseSpec spec = Spec(info.name, "ipopt");
  spec.transcription = "euler";
  const std::string error = ErrorOf(spec);
  EXPECT_NE(error.find("SetDimensions gives npsi = 1 but AutoDiffOcp's template argument says 2"),
            std::string::npos)
      << error;
  EXPECT_THROW(RunCase(spec), std::invalid_argument);
}

TEST(WorstCycleStatus, KeepsAnAcceptableStopApartFromConverged) {
  using S = SolveStatus;
  EXPECT_EQ(WorstCycleStatus({S::kConverged, S::kConverged}), "converged");
  EXPECT_EQ(WorstCycleStatus({S::kConverged, S::kAcceptable}), "acceptable");
  EXPECT_EQ(WorstCycleStatus({S::kAcceptable, S::kMaxIterations}), "max_iterations");
  EXPECT_EQ(WorstCycleStatus({S::kMaxIterations, S::kNumericalFailure}), "numerical_failure");
}

// A continuation's record keeps the penalty stage, the warnings and the method's own states and
// costates through JSON (summary, merge and --initial-guess read them back).
TEST(Record, ContinuationWarningsAndOwnTrajectoryRoundTrip) {
  CaseSpec spec = Spec("zermelo", "ipopt");
  spec.transcription = "trapezoid";
  spec.intervals = 20;
  spec.terminal = TerminalMode::kHard;
  spec.continuation = "penalty";
  const Record r = RunCase(spec);
  ASSERT_TRUE(r.continuation.has_value());
  EXPECT_EQ(r.continuation->from, "penalty");
  ASSERT_TRUE(r.trajectory.has_value());
  EXPECT_EQ(r.trajectory->own_x.rows(), 3);  // zermelo: x, y and the clock
  EXPECT_EQ(r.trajectory->own_p.rows(), 3);
  ASSERT_TRUE(r.stopping_tolerance.has_value());
  const json j = r.ToJson();
  const Record back = Record::FromJson(j);
  EXPECT_EQ(back.ToJson(), j);
  EXPECT_EQ(back.continuation->iterations, r.continuation->iterations);
  EXPECT_EQ(back.trajectory->own_p, r.trajectory->own_p);
  json bad = j;
  bad["warnings"] = json::array({"a string"});
  EXPECT_THROW(Record::FromJson(bad), std::invalid_argument);
}

// The costate fields round-trip, and a costate matrix that does not fit its times is refused by
// field.
TEST(Record, CostatesRoundTripAndMustFitTheirTimes) {
  CaseSpec spec = Spec("hager", "ipopt");
  spec.transcription = "hermite-simpson";
  spec.intervals = 8;
  spec.keep_trajectory = true;
  const Record r = RunCase(spec);
  EXPECT_EQ(r.costate_source, "NLP multipliers (hermite-simpson)");
  ASSERT_TRUE(r.costates);
  EXPECT_EQ(r.costates->t.size(), 17u);  // nodes and midpoints
  EXPECT_LT(r.costate_error, 1e-5);      // 1.6e-6 measured at N = 8
  const json j = r.ToJson();
  const Record back = Record::FromJson(j);
  EXPECT_EQ(back.ToJson(), j);
  EXPECT_EQ(back.costate_error, r.costate_error);
  json bad = j;
  bad["costates"]["t"].erase(0);
  try {
    Record::FromJson(bad);
    ADD_FAILURE() << "accepted costates with one time too few";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "costates.p: must be rows of as many values as t");
  }
  json old = j;  // records from before the costate fields read without them
  old.erase("costates");
  old.erase("costate_error");
  old.erase("costate_source");
  const Record plain = Record::FromJson(old);
  EXPECT_FALSE(plain.costates);
  EXPECT_TRUE(std::isnan(plain.costate_error));
  EXPECT_EQ(plain.ToJson(), old);
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

// The record's status when the judge's re-simulation on the method's grid is not finite
// (issue 38's glider): the solver's own when the fine RK4 one is finite and the method's scheme
// is not the judge's Euler; numerical_failure when no re-simulation is finite (hypersensitive,
// whose unstable dynamics overflow both), or when the method solved the judge's scheme itself.
TEST(RunCase, ANotFiniteReSimulationIsTheSolversFailureOnlyWhenItIsItsOwn) {
  auto run = [](const std::string& problem, const std::string& transcription, int N) {
    CaseSpec spec = Spec(problem, "ipopt");
    spec.transcription = transcription;
    spec.intervals = N;
    spec.terminal = TerminalMode::kHard;
    spec.keep_trajectory = false;
    return RunCase(spec);
  };
  auto has_warning = [](const Record& r, const std::string& code) {
    for (const RecordWarning& w : r.warnings) {
      if (w.code == code) return true;
    }
    return false;
  };
  const Record trapezoid = run("glider", "trapezoid", 200);
  EXPECT_EQ(trapezoid.solver_status, "Solve_Succeeded");
  EXPECT_EQ(trapezoid.status, "converged") << trapezoid.message;
  EXPECT_TRUE(has_warning(trapezoid, "not_finite"));
  EXPECT_TRUE(std::isfinite(trapezoid.J_fine));

  const Record neither = run("hypersensitive", "trapezoid", 100);
  EXPECT_EQ(neither.solver_status, "Solve_Succeeded");
  EXPECT_EQ(neither.status, "numerical_failure");
  EXPECT_NE(neither.message.find("evaluator: trajectory or cost not finite"), std::string::npos);
  EXPECT_TRUE(has_warning(neither, "not_finite"));

  // The rule itself (glider's Ipopt + euler at N = 40..100 is such a case, but takes 600-1300
  // Ipopt iterations).
  CaseSpec spec = Spec("glider", "ipopt");
  spec.transcription = "trapezoid";
  EXPECT_FALSE(NotFiniteIsNumericalFailure(spec, true, false));
  EXPECT_FALSE(NotFiniteIsNumericalFailure(spec, false, true));
  EXPECT_TRUE(NotFiniteIsNumericalFailure(spec, false, false));
  spec.transcription = "euler";
  EXPECT_TRUE(NotFiniteIsNumericalFailure(spec, false, true));
  spec.evaluate_with = Integrator::kRk4;
  EXPECT_FALSE(NotFiniteIsNumericalFailure(spec, false, true));
  EXPECT_TRUE(NotFiniteIsNumericalFailure(Spec("glider", "hamiltonian"), false, true));
}

}  // namespace
}  // namespace ocpb
