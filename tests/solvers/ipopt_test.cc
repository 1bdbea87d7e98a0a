#include "solvers/ipopt_solver.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <set>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/derivative_check.h"
#include "core/evaluator.h"
#include "problems/registry.h"
#include "solvers/ipopt_adapter.h"
#include "solvers/registry.h"
#include "tests/solvers/test_nlps.h"

namespace ocpb {
namespace {

using testing::Hs071;
using testing::RosenbrockDisc;

// ---- the hand-written test NLPs' derivatives --------------------------------------------

Vec ObjectiveAsVector(const Nlp& nlp, const Vec& z) {
  double f = NAN;
  EXPECT_TRUE(nlp.Objective(z, &f));
  return Vec::Constant(1, f);
}

Vec ConstraintsAsVector(const Nlp& nlp, const Vec& z) {
  Vec g(nlp.num_constraints());
  EXPECT_TRUE(nlp.Constraints(z, g));
  return g;
}

Mat DenseJacobian(const Nlp& nlp, const Vec& z) {
  Vec v(nlp.jacobian_rows().size());
  EXPECT_TRUE(nlp.JacobianValues(z, v));
  Mat J = Mat::Zero(nlp.num_constraints(), nlp.num_variables());
  for (Eigen::Index k = 0; k < v.size(); ++k)
    J(nlp.jacobian_rows()[k], nlp.jacobian_cols()[k]) += v[k];
  return J;
}

Vec LagrangianGradient(const Nlp& nlp, const Vec& z, double sigma, const Vec& lambda) {
  Vec g(nlp.num_variables());
  EXPECT_TRUE(nlp.Gradient(z, g));
  return sigma * g + DenseJacobian(nlp, z).transpose() * lambda;
}

void ExpectDerivativesMatchFiniteDifferences(const Nlp& nlp, const Vec& z, const Vec& lambda) {
  Vec grad(nlp.num_variables());
  ASSERT_TRUE(nlp.Gradient(z, grad));
  const Mat fd_grad = CentralJacobian([&](const Vec& v) { return ObjectiveAsVector(nlp, v); }, z);
  EXPECT_LT((grad - fd_grad.row(0).transpose()).cwiseAbs().maxCoeff(), 1e-7 * (1 + fd_grad.norm()));
  const Mat fd_jac = CentralJacobian([&](const Vec& v) { return ConstraintsAsVector(nlp, v); }, z);
  EXPECT_LT((DenseJacobian(nlp, z) - fd_jac).cwiseAbs().maxCoeff(), 1e-7 * (1 + fd_jac.norm()));
  // Hessian of the Lagrangian: lower triangle only, against differences of its gradient.
  const double sigma = 0.7;
  Vec h(nlp.hessian_rows().size());
  ASSERT_TRUE(nlp.HessianValues(z, sigma, lambda, h));
  Mat H = Mat::Zero(nlp.num_variables(), nlp.num_variables());
  for (Eigen::Index k = 0; k < h.size(); ++k) {
    const int r = nlp.hessian_rows()[k], c = nlp.hessian_cols()[k];
    ASSERT_GE(r, c) << "Hessian triplets must be the lower triangle";
    H(r, c) += h[k];
    if (r != c) H(c, r) += h[k];
  }
  const Mat fd_hess =
      CentralJacobian([&](const Vec& v) { return LagrangianGradient(nlp, v, sigma, lambda); }, z);
  EXPECT_LT((H - fd_hess).cwiseAbs().maxCoeff(), 1e-6 * (1 + fd_hess.norm())) << H << "\n\n"
                                                                              << fd_hess;
}

TEST(TestNlps, Hs071DerivativesMatchFiniteDifferences) {
  ExpectDerivativesMatchFiniteDifferences(
      Hs071(), Eigen::Vector4d(1.3, 4.1, 3.2, 1.7), Eigen::Vector2d(-0.4, 0.9));
}

TEST(TestNlps, RosenbrockDiscDerivativesMatchFiniteDifferences) {
  ExpectDerivativesMatchFiniteDifferences(
      RosenbrockDisc(1.0, 0.5), Eigen::Vector2d(0.3, -0.8), Eigen::Vector2d(1.3, -0.6));
}

// ---- the adapter on hand-written NLPs ----------------------------------------------------------

TEST(IpoptAdapter, SolvesHs071WithTheKnownOptimumAndMultipliers) {
  const Hs071 nlp;
  const NlpSolution sol = SolveNlpWithIpopt(nlp, nlp.StartingPoint(), IpoptOptions());
  ASSERT_EQ(sol.status, SolveStatus::kConverged) << sol.message;
  EXPECT_EQ(sol.solver_status, "Solve_Succeeded");
  EXPECT_TRUE(sol.has_iterate);
  EXPECT_NEAR(sol.objective, 17.0140173, 1e-6);
  const Eigen::Vector4d x_star(1.0, 4.74299963, 3.82114998, 1.37940829);
  EXPECT_LT((sol.z - x_star).cwiseAbs().maxCoeff(), 1e-6) << sol.z.transpose();
  ASSERT_EQ(sol.lambda.size(), 2);
  EXPECT_NEAR(sol.lambda[0], -0.552293, 1e-5);
  EXPECT_NEAR(sol.lambda[1], 0.161469, 1e-5);
  EXPECT_EQ(sol.stats.at("ipopt_exact_hessian"), 1.0);
  EXPECT_GT(sol.stats.at("ipopt_hessian_evaluations"), 0.0);
  EXPECT_GE(sol.stats.at("ipopt_cpu_seconds"), 0.0);
  EXPECT_LT(sol.stats.at("ipopt_constr_viol"), 1e-8);
}

TEST(IpoptAdapter, HistoryHasOneRowPerIteration) {
  const Hs071 nlp;
  const NlpSolution sol = SolveNlpWithIpopt(nlp, nlp.StartingPoint(), IpoptOptions());
  ASSERT_GT(sol.iterations, 2);
  // Row 0 is the starting point, then one row per iteration.
  ASSERT_EQ(static_cast<int>(sol.history.size()), sol.iterations + 1);
  for (size_t i = 0; i < sol.history.size(); ++i) {
    EXPECT_EQ(sol.history[i].iteration, static_cast<int>(i));
    EXPECT_TRUE(std::isfinite(sol.history[i].primal_inf));
    EXPECT_TRUE(std::isfinite(sol.history[i].dual_inf));
    if (i > 0) {
      EXPECT_GE(sol.history[i].cpu_seconds, sol.history[i - 1].cpu_seconds);
    }
  }
  // f(1, 5, 5, 1) = 16, at the start Ipopt first pushes 1e-2 into the bounds' interior.
  EXPECT_NEAR(sol.history.front().J, 16.0, 0.2);
  EXPECT_NEAR(sol.history.back().J, sol.objective, 1e-9);
  EXPECT_LT(sol.history.back().primal_inf, 1e-8);
  EXPECT_GT(sol.history.front().primal_inf, 1.0);  // g2 = 52 at the start, not 40
}

TEST(IpoptAdapter, LimitedMemoryWhenTheNlpHasNoHessian) {
  const Hs071 nlp(/*with_hessian=*/false);
  IpoptOptions options;
  options.hessian_approximation = "exact";  // asked for, but not available
  const NlpSolution sol = SolveNlpWithIpopt(nlp, nlp.StartingPoint(), options);
  ASSERT_EQ(sol.status, SolveStatus::kConverged) << sol.message;
  EXPECT_EQ(sol.stats.at("ipopt_exact_hessian"), 0.0);
  EXPECT_EQ(sol.stats.at("ipopt_hessian_evaluations"), 0.0);
  EXPECT_NE(sol.message.find("limited-memory"), std::string::npos) << sol.message;
  EXPECT_NEAR(sol.objective, 17.0140173, 1e-6);
}

TEST(IpoptAdapter, IterationLimitMapsToMaxIterations) {
  const Hs071 nlp;
  IpoptOptions options;
  options.max_iter = 2;
  const NlpSolution sol = SolveNlpWithIpopt(nlp, nlp.StartingPoint(), options);
  EXPECT_EQ(sol.status, SolveStatus::kMaxIterations);
  EXPECT_EQ(sol.solver_status, "Maximum_Iterations_Exceeded");
  EXPECT_EQ(sol.iterations, 2);
  EXPECT_TRUE(sol.has_iterate);  // the last iterate is kept
  EXPECT_GT(std::abs(sol.objective - 17.0140173), 1e-3);
}

TEST(IpoptAdapter, InfeasibleProblemMapsToInfeasible) {
  const RosenbrockDisc nlp(1.0, 3.0);  // |x|^2 <= 1 and x0 + x1 >= 3: empty
  const NlpSolution sol = SolveNlpWithIpopt(nlp, nlp.StartingPoint(), IpoptOptions());
  EXPECT_EQ(sol.status, SolveStatus::kInfeasible) << sol.solver_status << ": " << sol.message;
  EXPECT_EQ(sol.solver_status, "Infeasible_Problem_Detected");
}

TEST(IpoptAdapter, FailedEvaluationsAreReportedNotThrown) {
  const Hs071 nlp(true, /*fail_from=*/0.0);  // every evaluation fails
  NlpSolution sol;
  ASSERT_NO_THROW(sol = SolveNlpWithIpopt(nlp, nlp.StartingPoint(), IpoptOptions()));
  EXPECT_EQ(sol.status, SolveStatus::kNumericalFailure) << sol.solver_status;
  EXPECT_EQ(sol.solver_status, "Invalid_Number_Detected");
  EXPECT_NE(sol.message.find("failed"), std::string::npos) << sol.message;
}

TEST(IpoptAdapter, CpuTimeLimitMapsToMaxTime) {
  const Hs071 nlp;
  IpoptOptions options;
  options.max_cpu_time = 1e-12;  // exceeded by the first iteration on any machine
  const NlpSolution sol = SolveNlpWithIpopt(nlp, nlp.StartingPoint(), options);
  EXPECT_EQ(sol.status, SolveStatus::kMaxTime);
  EXPECT_EQ(sol.solver_status, "Maximum_CpuTime_Exceeded");
}

TEST(IpoptAdapter, RejectsAStartingPointOfTheWrongSize) {
  EXPECT_THROW(SolveNlpWithIpopt(Hs071(), Vec::Zero(3), IpoptOptions()), std::invalid_argument);
}

// A re-solve from the solution's own primal-dual point (Ipopt's warm start with the given
// multipliers) ends within two iterations. The multipliers are what does it: from the same
// point with zero multipliers (the same warm-start options), or from the primal point alone
// (a cold start: mu = 0.1, least-squares multipliers), Ipopt takes more.
TEST(IpoptAdapter, WarmStartFromItsOwnOptimumTakesFewIterations) {
  const Hs071 nlp;
  IpoptOptions options;
  options.tol = 1e-10;
  const NlpSolution cold = SolveNlpWithIpopt(nlp, nlp.StartingPoint(), options);
  ASSERT_EQ(cold.status, SolveStatus::kConverged) << cold.message;
  ASSERT_EQ(cold.z_lower.size(), 4);
  ASSERT_EQ(cold.z_upper.size(), 4);
  // x1 = 1 sits on its lower bound with a positive multiplier; the others are interior.
  EXPECT_GT(cold.z_lower[0], 0.1);
  EXPECT_LT(cold.z_lower.tail(3).maxCoeff(), 1e-6);
  EXPECT_EQ(cold.stats.at("ipopt_warm_start"), 0.0);

  const NlpSolution warm =
      SolveNlpWithIpopt(nlp, cold.z, options, {cold.lambda, cold.z_lower, cold.z_upper});
  ASSERT_EQ(warm.status, SolveStatus::kConverged) << warm.message;
  EXPECT_EQ(warm.stats.at("ipopt_warm_start"), 1.0);
  EXPECT_LE(warm.iterations, 2);
  EXPECT_NEAR(warm.objective, cold.objective, 1e-9);
  EXPECT_LT((warm.lambda - cold.lambda).cwiseAbs().maxCoeff(), 1e-7);

  const NlpSolution zero_multipliers =
      SolveNlpWithIpopt(nlp, cold.z, options, {Vec::Zero(2), Vec::Zero(4), Vec::Zero(4)});
  ASSERT_EQ(zero_multipliers.status, SolveStatus::kConverged) << zero_multipliers.message;
  EXPECT_GT(zero_multipliers.iterations, warm.iterations + 2);
  const NlpSolution primal_only = SolveNlpWithIpopt(nlp, cold.z, options);
  ASSERT_EQ(primal_only.status, SolveStatus::kConverged) << primal_only.message;
  EXPECT_GT(primal_only.iterations, warm.iterations + 2);
  RecordProperty("cold_iterations", cold.iterations);
  RecordProperty("warm_iterations", warm.iterations);
  RecordProperty("zero_multiplier_iterations", zero_multipliers.iterations);
  RecordProperty("primal_only_iterations", primal_only.iterations);
}

TEST(IpoptAdapter, RejectsStartingMultipliersThatDoNotFit) {
  const Hs071 nlp;
  const Vec z0 = nlp.StartingPoint();
  EXPECT_THROW(
      SolveNlpWithIpopt(nlp, z0, IpoptOptions(), {Vec::Zero(1), Vec::Zero(4), Vec::Zero(4)}),
      std::invalid_argument);
  EXPECT_THROW(
      SolveNlpWithIpopt(nlp, z0, IpoptOptions(), {Vec::Zero(2), Vec::Zero(3), Vec::Zero(4)}),
      std::invalid_argument);
  EXPECT_THROW(SolveNlpWithIpopt(
                   nlp, z0, IpoptOptions(), {Vec::Constant(2, NAN), Vec::Zero(4), Vec::Zero(4)}),
               std::invalid_argument);
}

TEST(IpoptStatus, EveryReturnStatusHasItsIpoptNameAndAGroup) {
  std::set<std::string> names;
  for (int code : AllIpoptStatusCodes()) {
    const std::string name = IpoptStatusName(code);
    EXPECT_EQ(name.find("Unknown"), std::string::npos) << code;
    names.insert(name);
  }
  EXPECT_EQ(names.size(), AllIpoptStatusCodes().size());
  EXPECT_EQ(AllIpoptStatusCodes().size(), 19u);
  EXPECT_EQ(MapIpoptStatus(0), SolveStatus::kConverged);          // Solve_Succeeded
  EXPECT_EQ(MapIpoptStatus(1), SolveStatus::kAcceptable);         // Solved_To_Acceptable_Level
  EXPECT_EQ(MapIpoptStatus(2), SolveStatus::kInfeasible);         // Infeasible_Problem_Detected
  EXPECT_EQ(MapIpoptStatus(3), SolveStatus::kStepTooSmall);       // Search_Direction_...
  EXPECT_EQ(MapIpoptStatus(-1), SolveStatus::kMaxIterations);     // Maximum_Iterations_Exceeded
  EXPECT_EQ(MapIpoptStatus(-2), SolveStatus::kNumericalFailure);  // Restoration_Failed
  EXPECT_EQ(MapIpoptStatus(-4), SolveStatus::kMaxTime);           // Maximum_CpuTime_Exceeded
  EXPECT_EQ(MapIpoptStatus(-12), SolveStatus::kInvalidInput);     // Invalid_Option
  EXPECT_EQ(MapIpoptStatus(-199), SolveStatus::kError);           // Internal_Error
  EXPECT_EQ(IpoptStatusName(-2), "Restoration_Failed");
  EXPECT_EQ(IpoptStatusName(42), "Unknown_Status(42)");
  EXPECT_EQ(MapIpoptStatus(42), SolveStatus::kError);
}

// ---- options -----------------------------------------------------------------------------------

TEST(IpoptOptions, DefaultsAreValidAndTheTableMatchesIpopt) {
  std::string error;
  EXPECT_TRUE(IpoptOptions().IsValid(&error)) << error;
  EXPECT_TRUE(IpoptOptionTableMatchesIpopt(&error)) << error;
  EXPECT_EQ(IpoptOptions().print_level, 0);
}

// The warm-start fields: set by name, each > 0, refused in one line naming it.
TEST(IpoptOptions, WarmStartFieldsAreSetByNameAndChecked) {
  const IpoptOptions o = IpoptOptions::Apply({{"warm_start_mu_init", "1e-5"},
                                              {"warm_start_bound_push", "1e-4"},
                                              {"warm_start_mult_bound_push", "1e-7"},
                                              {"warm_start_slack_bound_frac", "0.1"}},
                                             IpoptOptions());
  EXPECT_EQ(o.warm_start_mu_init, 1e-5);
  EXPECT_EQ(o.warm_start_bound_push, 1e-4);
  EXPECT_EQ(o.warm_start_mult_bound_push, 1e-7);
  ASSERT_EQ(o.extra.size(), 1u);  // the pass-through one
  EXPECT_EQ(o.extra[0].name, "warm_start_slack_bound_frac");
  for (const char* key :
       {"warm_start_mu_init", "warm_start_bound_push", "warm_start_mult_bound_push"}) {
    try {
      IpoptOptions::Apply({{key, "0"}}, IpoptOptions());
      ADD_FAILURE() << key << " = 0 accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(key), std::string::npos) << what;
      EXPECT_NE(what.find("> 0"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

TEST(IpoptOptions, ParsesEachTypeAndRejectsBadInput) {
  const IpoptOptions o = IpoptOptions::Apply({{"tol", "1e-10"},
                                              {"max_iter", "77"},
                                              {"mu_strategy", "adaptive"},
                                              {"hessian_approximation", "limited-memory"},
                                              {"obj_scaling_factor", "0.01"},
                                              {"limited_memory_max_history", "12"},
                                              {"bound_push", "1e-3"},
                                              {"derivative_test", "first-order"}},
                                             IpoptOptions());
  EXPECT_EQ(o.tol, 1e-10);
  EXPECT_EQ(o.max_iter, 77);
  EXPECT_EQ(o.mu_strategy, "adaptive");
  EXPECT_EQ(o.hessian_approximation, "limited-memory");
  EXPECT_EQ(o.obj_scaling_factor, 0.01);
  ASSERT_EQ(o.extra.size(), 3u);
  for (const IpoptOptionValue& v : o.extra) {
    if (v.name == "limited_memory_max_history") {
      EXPECT_EQ(v.type, IpoptOptionType::kInteger);
      EXPECT_EQ(v.integer, 12);
    } else if (v.name == "bound_push") {
      EXPECT_EQ(v.type, IpoptOptionType::kNumber);
      EXPECT_EQ(v.number, 1e-3);
    } else {
      EXPECT_EQ(v.name, "derivative_test");
      EXPECT_EQ(v.text, "first-order");
    }
  }
  auto message = [](const std::map<std::string, std::string>& m) {
    try {
      IpoptOptions::Apply(m, IpoptOptions());
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message({{"max_itr", "5"}}).find("'max_itr'"), std::string::npos);
  EXPECT_NE(message({{"max_itr", "5"}}).find("max_iter"), std::string::npos);  // lists valid keys
  EXPECT_NE(message({{"max_iter", "1.5"}}).find("integer"), std::string::npos);
  EXPECT_NE(message({{"tol", "abc"}}).find("number"), std::string::npos);
  EXPECT_NE(message({{"tol", "-1"}}).find("'tol': must be a number > 0"), std::string::npos);
  EXPECT_NE(message({{"mu_strategy", "fast"}}).find("monotone"), std::string::npos);
  EXPECT_NE(message({{"linear_solver", "ma27"}}).find("mumps"), std::string::npos);
  EXPECT_NE(message({{"print_level", "13"}}).find("print_level"), std::string::npos);
  // Pass-through options take the range the linked Ipopt registers: refused when the options
  // are checked, not by Ipopt at solve time (an invalid_input record after the work).
  EXPECT_NE(message({{"mu_init", "-5"}}).find("'mu_init': must be a number > 0"), std::string::npos)
      << message({{"mu_init", "-5"}});
  EXPECT_NE(message({{"max_soc", "-1"}}).find("'max_soc': must be an integer >= 0"),
            std::string::npos)
      << message({{"max_soc", "-1"}});
  EXPECT_NE(message({{"mumps_mem_percent", "-100"}}).find("mumps_mem_percent"), std::string::npos);
  EXPECT_EQ(message({{"mu_init", "1e-3"}, {"max_soc", "2"}}), "no exception");
  // Ipopt's output file: a place Ipopt could not open is refused before the solve.
  const std::string folder = ::testing::TempDir();
  EXPECT_NE(message({{"output_file", folder}}).find("'output_file'"), std::string::npos);
  EXPECT_NE(message({{"output_file", folder + "/no-such-folder/ipopt.out"}}).find("in no folder"),
            std::string::npos);
  EXPECT_EQ(message({{"output_file", folder + "/ipopt.out"}}), "no exception");
}

// ---- the solver on optimal-control problems ---------------------------------------------------

SolveRequest DoubleIntegratorRequest(const std::string& transcription, int N, TerminalMode mode) {
  SolveRequest request;
  request.grid = TimeGrid::Uniform(0.0, 1.0, N);
  request.terminal = mode;
  request.transcription = transcription;
  return request;
}

bool TranscriptionRegistered(const std::string& transcription) {
  for (const TranscriptionInfo& t : Transcriptions()) {
    if (t.name == transcription) return true;
  }
  return false;
}

// The hard-form double integrator (J* = 6) on every transcription, N = 20: the NLP optimum is
// within the scheme's discretization error of 6 (stated per scheme below).
struct SchemeCase {
  const char* name;
  double expected;   ///< the discrete optimum where known in closed form, else 6
  double tolerance;  ///< |J_20 - expected| bound
};

class IpoptOnDoubleIntegrator : public ::testing::TestWithParam<SchemeCase> {};

TEST_P(IpoptOnDoubleIntegrator, ReachesSixWithinTheSchemesAccuracy) {
  const SchemeCase c = GetParam();
  if (!TranscriptionRegistered(c.name)) GTEST_SKIP() << c.name << " is not registered";
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const SolveRequest request = DoubleIntegratorRequest(c.name, 20, TerminalMode::kHard);
  const SolveResult r = FindSolver("ipopt").make()->Solve(*ocp, request);
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.solver_status << ": " << r.message;
  EXPECT_EQ(r.solver, "ipopt");
  EXPECT_EQ(r.solver_status, "Solve_Succeeded");
  EXPECT_NEAR(r.objective, c.expected, c.tolerance) << c.name;
  EXPECT_GT(r.iterations, 0);
  EXPECT_FALSE(r.history.empty());
  EXPECT_GE(r.cpu_seconds, 0.0);
  EXPECT_EQ(r.solver_stats.count("ipopt_cpu_seconds"), 1u);
  EXPECT_LT(r.solver_stats.at("nlp_violation"), 1e-7);
}

INSTANTIATE_TEST_SUITE_P(
    Schemes,
    IpoptOnDoubleIntegrator,
    // Euler's discrete optimum here is J_N = 6 N^2 / (N^2 - 1) (measured at N = 10..80 to 1e-10;
    // second order on this problem). Trapezoid is second order: J_N - 6 = 0.0583 at N = 20,
    // 0.0148 at N = 40. Hermite-Simpson and LGR are exact for the cubic optimal states.
    // Single shooting (Euler) is the Euler NLP in the controls alone: the same optimum.
    ::testing::Values(SchemeCase{"euler", 6.0 * 400.0 / 399.0, 1e-7},
                      SchemeCase{"trapezoid", 6.0, 0.07},
                      SchemeCase{"hermite-simpson", 6.0, 1e-7},
                      SchemeCase{"lgr", 6.0, 1e-7},
                      SchemeCase{"single-shooting", 6.0 * 400.0 / 399.0, 1e-7}),
    [](const ::testing::TestParamInfo<SchemeCase>& info) {
      std::string s = info.param.name;
      for (char& ch : s) ch = ch == '-' ? '_' : ch;
      return s;
    });

TEST(IpoptSolver, SingleShootingAndTheEulerTranscriptionShareTheirOptimum) {
  // Single shooting (Euler) and the Euler transcription are the same discrete problem.
  if (!TranscriptionRegistered("euler")) GTEST_SKIP() << "euler is not registered";
  const auto ocp = MakeProblem("double-integrator-bounded", {}, 0);
  const IpoptSolver solver;
  SolveRequest request = DoubleIntegratorRequest("euler", 40, TerminalMode::kHard);
  const SolveResult euler = solver.Solve(*ocp, request);
  request.transcription = "single-shooting";
  const SolveResult shooting = solver.Solve(*ocp, request);
  ASSERT_EQ(euler.status, SolveStatus::kConverged) << euler.message;
  ASSERT_EQ(shooting.status, SolveStatus::kConverged) << shooting.message;
  EXPECT_NEAR(euler.objective, shooting.objective, 1e-6 * euler.objective);
  EXPECT_LT((euler.controls.values() - shooting.controls.values()).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(IpoptSolver, CostatesFromMultipliersMatchTheAnalyticCostate) {
  // Double integrator: with H = p^T f + L, u* = -p2 = 6 - 12 t gives p2 = 12 t - 6 and
  // p1 = -p2' = -12. Single shooting's costates come from the multipliers of psi = 0; the Euler
  // discretization makes them O(h) accurate.
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const int N = 50;
  const SolveResult r =
      IpoptSolver().Solve(*ocp, DoubleIntegratorRequest("single-shooting", N, TerminalMode::kHard));
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
  ASSERT_EQ(r.costates.rows(), 2);
  ASSERT_EQ(r.costates.cols(), N + 1);
  for (int k = 0; k <= N; k += 10) {
    const double t = r.state_grid.t(k);
    EXPECT_NEAR(r.costates(0, k), -12.0, 0.05 * 12.0) << "t = " << t;
    EXPECT_NEAR(r.costates(1, k), 12.0 * t - 6.0, 0.5) << "t = " << t;
  }
}

TEST(IpoptSolver, ControlsAreWhatTheEvaluatorJudges) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const SolveRequest request =
      DoubleIntegratorRequest("single-shooting", 30, TerminalMode::kPenalty);
  const SolveResult r = IpoptSolver().Solve(*ocp, request);
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
  const Evaluation ev = Evaluate(*ocp, r.controls, request.grid, Integrator::kEuler);
  EXPECT_NEAR(ev.J, r.objective, 1e-10 * r.objective);
}

TEST(IpoptSolver, TranscriptionScalingKeepsResultsInProblemUnits) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  SolveRequest request = DoubleIntegratorRequest("single-shooting", 30, TerminalMode::kPenalty);
  const SolveResult plain = IpoptSolver().Solve(*ocp, request);
  request.transcription_options = {{"objective_scale", "0.01"}, {"control_scale", "5"}};
  const SolveResult scaled = IpoptSolver().Solve(*ocp, request);
  ASSERT_EQ(plain.status, SolveStatus::kConverged) << plain.message;
  ASSERT_EQ(scaled.status, SolveStatus::kConverged) << scaled.message;
  EXPECT_NEAR(scaled.objective, plain.objective, 1e-7 * plain.objective);
  EXPECT_NEAR(scaled.history.back().J, scaled.objective, 1e-7 * plain.objective);
  const Evaluation ev = Evaluate(*ocp, scaled.controls, request.grid, Integrator::kEuler);
  EXPECT_NEAR(ev.J, scaled.objective, 1e-10 * ev.J);
  EXPECT_LT((scaled.controls.values() - plain.controls.values()).cwiseAbs().maxCoeff(), 1e-4);
}

TEST(IpoptSolver, IterationLimitThroughTheRequestOptions) {
  const auto ocp = MakeProblem("double-integrator-bounded", {}, 0);
  SolveRequest request = DoubleIntegratorRequest("single-shooting", 30, TerminalMode::kHard);
  request.options = {{"max_iter", "1"}};
  const SolveResult r = IpoptSolver().Solve(*ocp, request);
  EXPECT_EQ(r.status, SolveStatus::kMaxIterations);
  EXPECT_EQ(r.solver_status, "Maximum_Iterations_Exceeded");
  EXPECT_EQ(r.iterations, 1);
  EXPECT_EQ(r.controls.values().cols(), 30);
}

TEST(IpoptSolver, StartsFromTheRequestsInitialGuess) {
  // With max_iter = 0 Ipopt returns its starting point: the guess (no bounds to push it from).
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  for (const std::string transcription : {"single-shooting", "euler"}) {
    if (!TranscriptionRegistered(transcription)) continue;
    SolveRequest request = DoubleIntegratorRequest(transcription, 10, TerminalMode::kHard);
    Mat guess(1, 10);
    for (int k = 0; k < 10; ++k) guess(0, k) = 0.3 * k - 1.0;
    request.initial_guess = ControlTrajectory::PiecewiseConstant(request.grid, guess);
    request.options = {{"max_iter", "0"}};
    const SolveResult r = IpoptSolver().Solve(*ocp, request);
    EXPECT_EQ(r.status, SolveStatus::kMaxIterations) << transcription;
    EXPECT_LT((r.controls.SampleIntervals(request.grid) - guess).cwiseAbs().maxCoeff(), 1e-12)
        << transcription;
  }
}

// The default ordering (-1: AMD for NLPs with an exact Hessian) and MUMPS' automatic choice
// (7, Ipopt's default, through the request's options, which override the field) take the same
// iterates on the paper's problem: same iteration count and objective to rounding.
TEST(IpoptSolver, MumpsOrderingChangesNoIterate) {
  const auto ocp = MakeProblem("comm-path2d", {"channel=0"}, 1);
  for (const std::string scheme : {"euler", "trapezoid", "hermite-simpson", "lgr"}) {
    SolveRequest request;
    request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 60);
    request.transcription = scheme;
    const SolveResult amd = IpoptSolver().Solve(*ocp, request);
    request.options = {{"mumps_pivot_order", "7"}};
    const SolveResult automatic = IpoptSolver().Solve(*ocp, request);
    ASSERT_EQ(amd.status, SolveStatus::kConverged) << scheme;
    EXPECT_EQ(amd.iterations, automatic.iterations) << scheme;
    EXPECT_NEAR(amd.objective, automatic.objective, 1e-10 * std::abs(automatic.objective))
        << scheme;
    // Ipopt's range is 0..7: refused when the options are read, before the solve (it used to
    // reach Ipopt and come back as an invalid_input result after the transcription's work).
    request.options = {{"mumps_pivot_order", "8"}};
    try {
      IpoptSolver().Solve(*ocp, request);
      ADD_FAILURE() << scheme << ": mumps_pivot_order = 8 accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("'mumps_pivot_order': must be an integer in [0, 7]"),
                std::string::npos)
          << e.what();
    }
  }
  IpoptOptions o;
  EXPECT_EQ(o.mumps_pivot_order, -1);
  o.mumps_pivot_order = 8;
  EXPECT_FALSE(o.IsValid(nullptr));
}

TEST(IpoptSolver, RejectsInvalidRequests) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const IpoptSolver solver;
  SolveRequest request = DoubleIntegratorRequest("", 10, TerminalMode::kHard);
  EXPECT_THROW(solver.Solve(*ocp, request), std::invalid_argument);  // no transcription
  request.transcription = "no-such-scheme";
  EXPECT_THROW(solver.Solve(*ocp, request), std::invalid_argument);
  request.transcription = "single-shooting";
  request.options = {{"bogus", "1"}};
  EXPECT_THROW(solver.Solve(*ocp, request), std::invalid_argument);
  request.options = {};
  request.transcription_options = {{"objective_scale", "-1"}};
  EXPECT_THROW(solver.Solve(*ocp, request), std::invalid_argument);
  request.transcription_options = {{"objective_scale", "1"}, {"max_iter", "3"}};  // Ipopt's key
  EXPECT_THROW(solver.Solve(*ocp, request), std::invalid_argument);
  request.transcription_options = {};
  request.grid = TimeGrid::Uniform(0.0, 2.0, 10);  // the horizon is [0, 1]
  EXPECT_THROW(solver.Solve(*ocp, request), std::invalid_argument);
}

TEST(IpoptSolver, PaperProblemHardTerminalFormSmallGrid) {
  // The paper's problem (deterministic path-loss channel), Euler, N = 40, psi(x(tf)) = 0 enforced:
  // the terminal residual of the returned controls (re-simulated by the evaluator) is <= 1e-6,
  // and the unpenalized cost is at least the penalty solution's (which may miss the target).
  const auto ocp = MakeProblem("comm-path2d", {"channel=0"}, 1);
  SolveRequest request;
  request.grid = TimeGrid::Uniform(0.0, ocp->tf(), 40);
  request.transcription = "euler";
  request.terminal = TerminalMode::kHard;
  const SolveResult hard = IpoptSolver().Solve(*ocp, request);
  request.terminal = TerminalMode::kPenalty;
  const SolveResult penalty = IpoptSolver().Solve(*ocp, request);
  ASSERT_EQ(hard.status, SolveStatus::kConverged) << hard.message;
  ASSERT_EQ(penalty.status, SolveStatus::kConverged) << penalty.message;
  const Evaluation ev_hard = Evaluate(*ocp, hard.controls, request.grid, Integrator::kEuler);
  const Evaluation ev_penalty = Evaluate(*ocp, penalty.controls, request.grid, Integrator::kEuler);
  EXPECT_LT(ev_hard.terminal_violation, 1e-6);
  EXPECT_GT(ev_penalty.terminal_violation, 1e-4);  // the penalty (C = 10, 50, 10) leaves a gap
  EXPECT_NEAR(ev_hard.Jbar, hard.objective, 1e-9 * hard.objective);
  EXPECT_GE(ev_hard.Jbar, ev_penalty.Jbar - 1e-9 * ev_penalty.Jbar);
  EXPECT_LE(ev_penalty.J, ev_hard.J + 1e-9 * ev_hard.J);  // the penalty optimum is optimal for J
  // Costates from the defect multipliers exist on the whole grid.
  EXPECT_EQ(hard.costates.cols(), 41);
  EXPECT_TRUE(hard.costates.allFinite());
}

// The paper's problem as registered (the predicted channel, a bicubic map; seed 1), hard
// terminal form psi(x(tf)) = 0 on every collocation scheme, N = 100 (dt = 0.4 s): the terminal
// residual of the NLP's own final state is <= 1e-6, and the unpenalized cost Jbar is reported and
// compared with the penalty solution's, which misses the target (C = 10, 50, 10).
struct PaperHardCase {
  const char* transcription;
  double jbar;  // measured Jbar of the hard solution (NLP objective), N = 100
};

class IpoptPaperHardTerminal : public ::testing::TestWithParam<PaperHardCase> {};

TEST_P(IpoptPaperHardTerminal, TerminalResidualBelow1e6) {
  const PaperHardCase c = GetParam();
  const auto ocp = MakeProblem("comm-path2d", {}, 1);
  SolveRequest request;
  request.grid = TimeGrid::Uniform(0.0, ocp->tf(), 100);
  request.transcription = c.transcription;
  request.terminal = TerminalMode::kHard;
  const SolveResult hard = IpoptSolver().Solve(*ocp, request);
  request.terminal = TerminalMode::kPenalty;
  const SolveResult penalty = IpoptSolver().Solve(*ocp, request);
  ASSERT_EQ(hard.status, SolveStatus::kConverged) << hard.solver_status << " " << hard.message;
  ASSERT_EQ(penalty.status, SolveStatus::kConverged) << penalty.message;
  // psi at the NLP's own final state (the scheme's discretization, not a re-simulation).
  ASSERT_EQ(hard.states.cols(), hard.state_grid.size());
  Vec psi(ocp->num_terminal()), psi_penalty(ocp->num_terminal());
  ocp->TerminalConstraints(hard.states.col(hard.states.cols() - 1), psi);
  ocp->TerminalConstraints(penalty.states.col(penalty.states.cols() - 1), psi_penalty);
  EXPECT_LE(psi.cwiseAbs().maxCoeff(), 1e-6) << psi.transpose();
  EXPECT_LE(hard.solver_stats.at("nlp_violation"), 1e-6);
  EXPECT_GT(psi_penalty.cwiseAbs().maxCoeff(), 1e-3);  // the penalty form leaves a gap
  // In hard form the NLP objective is Jbar in the scheme's own quadrature.
  const double jbar_hard = hard.objective;
  RecordProperty("Jbar_hard", std::to_string(jbar_hard));
  std::cout << std::setprecision(10) << c.transcription << ": Jbar hard = " << jbar_hard
            << ", |psi| = " << psi.cwiseAbs().maxCoeff()
            << ", penalty |psi| = " << psi_penalty.cwiseAbs().maxCoeff()
            << ", penalty J = " << penalty.objective << ", iterations " << hard.iterations << " / "
            << penalty.iterations << ", CPU s " << hard.cpu_seconds << " / " << penalty.cpu_seconds
            << "\n";
  // Pinned to 1e-7 (5e-5 absolute), well below the hard-penalty gap (~9e-4).
  EXPECT_NEAR(jbar_hard, c.jbar, 1e-7 * c.jbar);
  // Reaching the target costs a little motion energy: Jbar(hard) >= the penalty solution's Jbar
  // (its objective J minus the penalty sum w_i psi_i^2), and J(penalty) <= J(hard) = Jbar(hard).
  const double jbar_penalty =
      penalty.objective - (ocp->terminal_weights().array() * psi_penalty.array().square()).sum();
  EXPECT_GE(jbar_hard, jbar_penalty);
  EXPECT_LE(penalty.objective, jbar_hard);
  // Euler: the evaluator (Euler on the same grid) re-simulates exactly the NLP's trajectory.
  const Evaluation fine = Evaluate(*ocp, hard.controls, request.grid.Refined(10), Integrator::kRk4);
  if (std::string(c.transcription) == "euler") {
    EXPECT_LE(Evaluate(*ocp, hard.controls, request.grid, Integrator::kEuler).terminal_violation,
              1e-6);
  }
  std::cout << "  Jbar penalty = " << jbar_penalty << ", RK4 10x: Jbar hard = " << fine.Jbar
            << ", terminal violation " << fine.terminal_violation << "\n";
}

INSTANTIATE_TEST_SUITE_P(Schemes,
                         IpoptPaperHardTerminal,
                         ::testing::Values(PaperHardCase{"euler", 474.32188},
                                           PaperHardCase{"trapezoid", 474.31848},
                                           PaperHardCase{"hermite-simpson", 474.31813},
                                           PaperHardCase{"lgr", 474.31814}),
                         [](const auto& info) {
                           std::string n = info.param.transcription;
                           for (char& ch : n) ch = ch == '-' ? '_' : ch;
                           return n;
                         });

TEST(IpoptSolver, IsRegisteredAsAnNlpSolver) {
  const SolverInfo& info = FindSolver("ipopt");
  EXPECT_TRUE(info.uses_transcription);
  EXPECT_EQ(info.make()->name(), "ipopt");
}

}  // namespace
}  // namespace ocpb
