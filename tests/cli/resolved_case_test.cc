// A case is resolved and checked once (ResolveAndValidate) and run as resolved; the case fields
// `algorithm` and `degree` are spellings of their owners' options.
#include "bench/cli/resolved_case.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "bench/cli/case_runner.h"
#include "bench/cli/online_case.h"
#include "problems/registry.h"
#include "tests/core/user_double_integrator.h"

namespace ocpb {
namespace {

CaseSpec CaseOf(const std::string& problem, const std::string& solver) {
  CaseSpec spec;
  spec.problem = problem;
  spec.solver = solver;
  spec.keep_trajectory = false;
  return spec;
}

TEST(ResolveAndValidate, HoldsTheRegistryEntriesTypedOptionsParametersGridAndEstimate) {
  CaseSpec spec = CaseOf("double-integrator", "ipopt");
  spec.transcription = "lgr";
  spec.set = {"tf=2"};
  spec.options = {{"tol", "1e-9"}, {"degree", "5"}};
  const ResolvedCase c = ResolveAndValidate(spec);
  EXPECT_EQ(c.problem, &FindProblem("double-integrator"));
  EXPECT_EQ(c.solver, &FindSolver("ipopt"));
  EXPECT_EQ(c.transcription, &FindTranscription("lgr"));
  EXPECT_EQ(c.options.solver.Find("tol")->number(), 1e-9);
  EXPECT_EQ(c.options.transcription.Find("degree")->integer(), 5);
  EXPECT_EQ(c.parameters.Scalar("tf"), 2.0);
  EXPECT_EQ(c.intervals, FindProblem("double-integrator").default_intervals);  // N omitted
  EXPECT_EQ(c.nx, 2);
  EXPECT_EQ(c.nu, 1);
  EXPECT_EQ(c.estimate.memory_bytes, EstimateCaseMemoryBytes(spec, 2, 1, c.intervals));
  EXPECT_EQ(c.estimate.record_bytes, EstimateRecordBytes(spec, 2, 1, c.intervals));
  // The channel problems are checked on a build without their channel: that build is not kept.
  EXPECT_TRUE(c.built_problem);
  EXPECT_FALSE(ResolveAndValidate(CaseOf("comm-path2d", "hamiltonian")).built_problem);
  EXPECT_FALSE(c.online);
}

// An online case keeps its resolved scenario (the run uses it instead of resolving it again).
TEST(ResolveAndValidate, KeepsAnOnlineCasesScenario) {
  CaseSpec spec = CaseOf("comm-path2d", "hamiltonian");
  spec.kind = "online";
  spec.online = {{"update_period", "5"}};
  const ResolvedCase c = ResolveAndValidate(spec);
  ASSERT_TRUE(c.online);
  EXPECT_EQ(c.online->settings.Find("update_period")->number(), 5.0);
  spec.online = {{"update_period", "-5"}};
  EXPECT_THROW(ResolveAndValidate(spec), std::invalid_argument);
}

// The problem is built once for a case whose checks build the real problem: by the checks,
// and the solve uses that build.
TEST(ResolveAndValidate, BuildsACheapProblemOnceForChecksAndSolve) {
  static std::atomic<int> builds{0};
  ProblemInfo info;
  info.name = "resolved-case-test-counted";
  info.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> {
    ++builds;
    return std::make_unique<testing::UserDoubleIntegrator>();
  };
  if (std::none_of(Problems().begin(), Problems().end(), [&](const ProblemInfo& p) {
        return p.name == info.name;
      })) {
    RegisterProblem(info);  // once per process (--gtest_repeat runs the test again)
  }
  builds = 0;
  CaseSpec spec = CaseOf(info.name, "ipopt");
  spec.transcription = "euler";
  spec.intervals = 20;
  spec.terminal = TerminalMode::kHard;
  const ResolvedCase c = ResolveAndValidate(spec);
  EXPECT_EQ(builds.load(), 1);
  const Record r = RunCase(c);
  EXPECT_EQ(builds.load(), 1);
  EXPECT_EQ(r.status, "converged") << r.message;
  EXPECT_NEAR(r.J, 12.0, 0.5);  // J* = 12 in the continuous problem; Euler's N = 20 near it
  // Running from the spec resolves it again (and builds once more), to the same record.
  const Record again = RunCase(spec);
  EXPECT_EQ(builds.load(), 2);
  EXPECT_EQ(again.key, r.key);
  EXPECT_EQ(again.J, r.J);
}

TEST(ResolveAndValidate, RefusesWhatValidateCaseRefuses) {
  CaseSpec spec = CaseOf("double-integrator", "ipopt");
  EXPECT_THROW(ResolveAndValidate(spec), std::invalid_argument);  // needs a transcription
  spec.transcription = "euler";
  spec.set = {"tf=-1"};
  EXPECT_THROW(ResolveAndValidate(spec), std::invalid_argument);
  spec.set.clear();
  spec.intervals = -1;
  EXPECT_THROW(ResolveAndValidate(spec), std::invalid_argument);
}

// The run uses the scenario the resolution kept: a case whose kept scenario is replaced runs
// the replacement (its settings are the record's).
TEST(ResolveAndValidate, AnOnlineCaseRunsTheScenarioItKept) {
  CaseSpec spec = CaseOf("comm-path2d", "hamiltonian");
  spec.kind = "online";
  spec.intervals = 40;
  spec.options = {{"max_iterations", "3"}};
  spec.online = {{"update_period", "10"}};
  ResolvedCase c = ResolveAndValidate(spec);
  CaseSpec other = spec;
  other.online = {{"update_period", "20"}};
  c.online = ResolveAndValidate(other).online;
  const Record r = RunCase(c);
  EXPECT_EQ(r.kind, "online");
  const nlohmann::json j = r.ToJson();
  ASSERT_TRUE(j.contains("online")) << j.dump().substr(0, 300);
  EXPECT_EQ(j["online"]["update_period"].get<double>(), 20.0) << j["online"].dump();
}

// The order of the messages: the names and options before the spec's own rules (as `solve`
// reported them), an option before a case field that spells another, and an online case's
// problem rule before any lookup of the name.
TEST(ResolveAndValidate, ReportsErrorsInTheOrderSolveAlwaysHad) {
  auto error_of = [](const CaseSpec& spec) {
    try {
      ResolveAndValidate(spec);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(valid)");
  };
  CaseSpec spec = CaseOf("double-integrator", "nope");
  spec.repeats = 0;
  EXPECT_NE(error_of(spec).find("nope"), std::string::npos) << error_of(spec);
  spec = CaseOf("double-integrator", "nlopt");
  spec.transcription = "euler";
  spec.options = {{"bogus", 1}};
  spec.algorithm = "NOPE";
  EXPECT_EQ(error_of(spec).rfind("options: nlopt: unknown option 'bogus'", 0), 0u)
      << error_of(spec);
  spec.options = {};
  EXPECT_EQ(error_of(spec).rfind("algorithm: nlopt option 'algorithm'", 0), 0u) << error_of(spec);
  spec = CaseOf("double-integrator", "hamiltonian");
  spec.kind = "online";
  EXPECT_NE(error_of(spec).find("online re-planning is defined for comm-path2d only"),
            std::string::npos)
      << error_of(spec);
}

// NLopt's "algorithm" and LGR's "degree" given as case fields or as options make one case:
// one key, one record identity; the fields end up among the options.
TEST(ResolveCase, CaseFieldsAreSpellingsOfTheirOwnersOptions) {
  CaseSpec field = CaseOf("double-integrator", "nlopt");
  field.transcription = "euler";
  field.algorithm = "LD_MMA";
  CaseSpec option = field;
  option.algorithm.clear();
  option.options = {{"algorithm", "LD_MMA"}};
  CaseSpec both = field;
  both.options = {{"algorithm", "LD_MMA"}};
  const CaseSpec resolved = ResolveCase(field);
  EXPECT_TRUE(resolved.algorithm.empty());
  EXPECT_EQ(resolved.options.Find("algorithm")->text(), "LD_MMA");
  EXPECT_EQ(resolved.Key(), ResolveCase(option).Key());
  EXPECT_EQ(resolved.Key(), ResolveCase(both).Key());
  EXPECT_NE(resolved.Key().find("|nlopt|euler|LD_MMA|"), std::string::npos) << resolved.Key();
  EXPECT_EQ(resolved.Key().find("opt:algorithm"), std::string::npos) << resolved.Key();
  const Record a = CaseIdentityRecord(resolved);
  const Record b = CaseIdentityRecord(ResolveCase(option));
  EXPECT_EQ(a.algorithm, "LD_MMA");
  EXPECT_EQ(b.algorithm, "LD_MMA");
  EXPECT_EQ(a.options, b.options);

  CaseSpec lgr = CaseOf("double-integrator", "ipopt");
  lgr.transcription = "lgr";
  lgr.degree = 5;
  lgr.degree_given = true;
  CaseSpec lgr_option = lgr;
  lgr_option.degree = CaseSpec::kDefaultDegree;
  lgr_option.degree_given = false;
  lgr_option.options = {{"degree", "5"}};
  EXPECT_EQ(ResolveCase(lgr).Key(), ResolveCase(lgr_option).Key());
  EXPECT_NE(ResolveCase(lgr).Key().find("|deg=5|"), std::string::npos);
  EXPECT_EQ(ResolveCase(lgr).options.Find("degree")->integer(), 5);
  EXPECT_EQ(ResolveCase(lgr).degree, CaseSpec::kDefaultDegree);
  lgr_option.options = {{"degree", "4"}};
  lgr_option.degree = 5;
  lgr_option.degree_given = true;  // both spellings, disagreeing
  EXPECT_THROW(ResolveCase(lgr_option), std::invalid_argument);

  // A transcription without a degree ignores the field, in the key too.
  CaseSpec euler = CaseOf("double-integrator", "ipopt");
  euler.transcription = "euler";
  CaseSpec euler_degree = euler;
  euler_degree.degree = 7;
  euler_degree.degree_given = true;
  EXPECT_EQ(ResolveCase(euler).Key(), ResolveCase(euler_degree).Key());
  EXPECT_FALSE(ResolveCase(euler_degree).options.Has("degree"));

  // A case that does not resolve (an unknown solver: its record says invalid_input) keeps its
  // options as given, both in the record and in the key.
  CaseSpec unknown = CaseOf("double-integrator", "no-such-solver");
  unknown.options = {{"algorithm", "X"}, {"degree", 4}};
  EXPECT_EQ(unknown.OptionsBesideCaseFields().size(), 1u);  // degree belongs to no solver here
  EXPECT_NE(unknown.Key().find("|opt:algorithm=X"), std::string::npos) << unknown.Key();
}

}  // namespace
}  // namespace ocpb
