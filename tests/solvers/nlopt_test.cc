#include "solvers/nlopt_solver.h"

#include <nlopt.h>

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/evaluator.h"
#include "problems/registry.h"
#include "solvers/ipopt_adapter.h"
#include "solvers/nlopt_adapter.h"
#include "solvers/registry.h"
#include "tests/solvers/test_nlps.h"

namespace ocpb {
namespace {

using testing::Hs071;
using testing::RosenbrockDisc;

/// f = |x - (1, 2)|^2 + 1e-9 sin(1e7 x0), and (m = 1) x0 + x1 = 1; the gradient deliberately
/// omits the noise term, so a line search near the optimum sees directional derivatives that do
/// not match f: SLSQP then stops with ROUNDOFF_LIMITED. (Inexact by design; no FD test.)
class NoisyQuadratic final : public Nlp {
 public:
  int num_variables() const override { return 2; }
  int num_constraints() const override { return 0; }
  void Bounds(Vec* zl, Vec* zu, Vec* gl, Vec* gu) const override {
    *zl = Vec::Constant(2, -INFINITY);
    *zu = Vec::Constant(2, INFINITY);
    gl->resize(0);
    gu->resize(0);
  }
  Vec StartingPoint() const override { return Eigen::Vector2d(3.0, 2.0); }
  bool Objective(ConstVecRef x, double* f) const override {
    *f = (x - Eigen::Vector2d(1.0, 2.0)).squaredNorm() + 1e-9 * std::sin(1e7 * x[0]);
    return true;
  }
  bool Gradient(ConstVecRef x, VecRef g) const override {
    g = 2.0 * (x - Eigen::Vector2d(1.0, 2.0));
    return true;
  }
  bool Constraints(ConstVecRef, VecRef) const override { return true; }
  bool JacobianValues(ConstVecRef, VecRef) const override { return true; }
};

// f = 1e20 + |x - (1, 2)|^2 with its exact gradient: in double precision f is the constant
// 1e20 near the start (its spacing there is 16384), so no step decreases it and NLopt cannot
// leave the start although the gradient is far from zero (a stand-in for a start where
// roundoff stops the first line search: NLopt's ROUNDOFF_LIMITED after one evaluation).
class FlatToRoundoffQuadratic final : public Nlp {
 public:
  int num_variables() const override { return 2; }
  int num_constraints() const override { return 0; }
  void Bounds(Vec* zl, Vec* zu, Vec* gl, Vec* gu) const override {
    *zl = Vec::Constant(2, -INFINITY);
    *zu = Vec::Constant(2, INFINITY);
    gl->resize(0);
    gu->resize(0);
  }
  Vec StartingPoint() const override { return Eigen::Vector2d(3.0, 2.0); }
  bool Objective(ConstVecRef x, double* f) const override {
    *f = 1e20 + (x - Eigen::Vector2d(1.0, 2.0)).squaredNorm();
    return true;
  }
  bool Gradient(ConstVecRef x, VecRef g) const override {
    g = 2.0 * (x - Eigen::Vector2d(1.0, 2.0));
    return true;
  }
  bool Constraints(ConstVecRef, VecRef) const override { return true; }
  bool JacobianValues(ConstVecRef, VecRef) const override { return true; }
};

NlpSolution RunNlopt(const Nlp& nlp,
                     const std::string& algorithm,
                     const std::string& local = "LD_LBFGS") {
  NloptOptions options;
  options.algorithm = algorithm;
  options.local_algorithm = local;
  return SolveNlpWithNlopt(nlp, nlp.StartingPoint(), options);
}

// ---- hand-written NLPs: every algorithm against Ipopt's optimum ------------------------------

TEST(NloptAdapter, Hs071EqualityAndInequality) {
  const Hs071 nlp;
  const NlpSolution ipopt = SolveNlpWithIpopt(nlp, nlp.StartingPoint(), IpoptOptions());
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged);
  // Algorithms that take equality constraints reach Ipopt's optimum (measured: |df| < 2e-7).
  for (const auto& [alg, local] :
       std::vector<std::pair<std::string, std::string>>{{"LD_SLSQP", ""},
                                                        {"AUGLAG", "LD_LBFGS"},
                                                        {"AUGLAG", "LD_SLSQP"},
                                                        {"AUGLAG_EQ", "LD_SLSQP"}}) {
    const NlpSolution s = RunNlopt(nlp, alg, local.empty() ? "LD_LBFGS" : local);
    EXPECT_EQ(s.status, SolveStatus::kConverged) << alg << "(" << local << "): " << s.message;
    EXPECT_NEAR(s.objective, ipopt.objective, 1e-6) << alg << "(" << local << ")";
    EXPECT_LT((s.z - ipopt.z).cwiseAbs().maxCoeff(), 1e-4) << alg << "(" << local << ")";
    EXPECT_LT(s.stats.at("nlopt_final_violation"), 1e-7);
    EXPECT_TRUE(s.lambda.size() == 0);  // NLopt has no multipliers
  }
  // The others cannot take the equality: refused up front, nothing evaluated.
  for (const std::string alg : {"LD_MMA", "LD_CCSAQ", "LD_LBFGS"}) {
    const NlpSolution s = RunNlopt(nlp, alg);
    EXPECT_EQ(s.status, SolveStatus::kNotApplicable) << alg;
    EXPECT_EQ(s.solver_status, "not_run");
    EXPECT_NE(s.message.find("equality"), std::string::npos) << s.message;
    EXPECT_FALSE(s.has_iterate);
  }
  // AUGLAG_EQ hands the inequality to its local algorithm: L-BFGS cannot take it.
  const NlpSolution s = RunNlopt(nlp, "AUGLAG_EQ", "LD_LBFGS");
  EXPECT_EQ(s.status, SolveStatus::kNotApplicable);
  EXPECT_NE(s.message.find("local algorithm"), std::string::npos) << s.message;
}

TEST(NloptAdapter, RosenbrockDiscInequalityOnly) {
  const RosenbrockDisc nlp;
  const NlpSolution ipopt = SolveNlpWithIpopt(nlp, nlp.StartingPoint(), IpoptOptions());
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged);
  EXPECT_NEAR(ipopt.objective, 0.0456748, 1e-6);
  for (const auto& [alg, local] :
       std::vector<std::pair<std::string, std::string>>{{"LD_SLSQP", "LD_LBFGS"},
                                                        {"LD_MMA", "LD_LBFGS"},
                                                        {"LD_CCSAQ", "LD_LBFGS"},
                                                        {"AUGLAG", "LD_LBFGS"},
                                                        {"AUGLAG_EQ", "LD_MMA"}}) {
    const NlpSolution s = RunNlopt(nlp, alg, local);
    EXPECT_EQ(s.status, SolveStatus::kConverged) << alg << ": " << s.message;
    // Measured: every one within 1e-9 of Ipopt's f.
    EXPECT_NEAR(s.objective, ipopt.objective, 1e-7) << alg;
    EXPECT_LT((s.z - ipopt.z).cwiseAbs().maxCoeff(), 1e-4) << alg;
  }
  EXPECT_EQ(RunNlopt(nlp, "LD_LBFGS").status, SolveStatus::kNotApplicable);
}

TEST(NloptAdapter, InfeasibleProblemIsNeverReportedConverged) {
  const RosenbrockDisc nlp(1.0, 3.0);  // |x|^2 <= 1 and x0 + x1 >= 3: empty
  for (const std::string alg : {"LD_SLSQP", "LD_MMA", "LD_CCSAQ", "AUGLAG"}) {
    const NlpSolution s = RunNlopt(nlp, alg);
    EXPECT_FALSE(IsSuccess(s.status)) << alg << ": " << ToString(s.status) << " " << s.message;
    EXPECT_GT(s.stats.at("nlopt_final_violation"), 0.1) << alg;
  }
  // SLSQP stops by its x tolerance (a "success" code for NLopt) at an infeasible point: OCPBench's
  // feasibility check turns that into kInfeasible and keeps NLopt's status verbatim.
  const NlpSolution s = RunNlopt(nlp, "LD_SLSQP");
  EXPECT_EQ(s.status, SolveStatus::kInfeasible);
  EXPECT_EQ(s.solver_status, "XTOL_REACHED");
  EXPECT_NE(s.message.find("violating"), std::string::npos);
}

// A stop at the starting point is no answer: whatever code NLopt returns there, the status is
// a failure (the start is not stationary), never "converged" or a limit that reads as usable.
// (Measured codes at this start: FTOL_REACHED after 25 evaluations (SLSQP) and after 2 (MMA,
// CCSAQ); the ROUNDOFF_LIMITED after one evaluation takes the same path.)
TEST(NloptAdapter, AStopAtTheStartIsAFailure) {
  const FlatToRoundoffQuadratic nlp;
  for (const std::string alg : {"LD_SLSQP", "LD_MMA", "LD_CCSAQ"}) {
    const NlpSolution s = RunNlopt(nlp, alg);
    SCOPED_TRACE(alg + ": " + s.solver_status + ", " + s.message);
    EXPECT_EQ(s.z, nlp.StartingPoint()) << "the premise: NLopt did not move";
    EXPECT_EQ(s.status, SolveStatus::kNumericalFailure);
    EXPECT_NE(s.message.find("stopped at the starting point"), std::string::npos);
  }
  // The same start on the true gradient: NLopt moves and converges (the check is not a
  // blanket refusal).
  const RosenbrockDisc moving;
  EXPECT_EQ(RunNlopt(moving, "LD_SLSQP").status, SolveStatus::kConverged);
}

TEST(NloptAdapter, RoundoffLimitedResultIsKeptAndLabelled) {
  const NoisyQuadratic nlp;
  NloptOptions options;
  options.algorithm = "LD_SLSQP";
  options.ftol_rel = 0.0;
  options.xtol_rel = 0.0;
  options.maxeval = 2000;
  const NlpSolution s = SolveNlpWithNlopt(nlp, nlp.StartingPoint(), options);
  EXPECT_EQ(s.status, SolveStatus::kRoundoffLimited) << s.solver_status;
  EXPECT_EQ(s.solver_status, "ROUNDOFF_LIMITED");
  EXPECT_TRUE(s.has_iterate);
  EXPECT_LT((s.z - Eigen::Vector2d(1.0, 2.0)).norm(), 1e-3) << s.z.transpose();
  EXPECT_NE(s.message.find("roundoff"), std::string::npos);
}

TEST(NloptAdapter, FailedEvaluationStopsWithNumericalFailure) {
  const Hs071 nlp(true, /*fail_from=*/0.0);
  NlpSolution s;
  ASSERT_NO_THROW(s = RunNlopt(nlp, "LD_SLSQP"));
  EXPECT_EQ(s.status, SolveStatus::kNumericalFailure);
  EXPECT_EQ(s.solver_status, "FORCED_STOP");
  EXPECT_NE(s.message.find("Nlp::Objective failed"), std::string::npos) << s.message;
}

TEST(NloptAdapter, EvaluationLimitMapsToMaxTimeAndHistoryHasEveryEvaluation) {
  const RosenbrockDisc nlp;
  NloptOptions options;
  options.algorithm = "LD_MMA";
  options.maxeval = 7;
  const NlpSolution s = SolveNlpWithNlopt(nlp, nlp.StartingPoint(), options);
  EXPECT_EQ(s.status, SolveStatus::kMaxTime);
  EXPECT_EQ(s.solver_status, "MAXEVAL_REACHED");
  EXPECT_EQ(s.iterations, 7);
  ASSERT_EQ(s.history.size(), 7u);
  for (size_t i = 0; i < s.history.size(); ++i) {
    EXPECT_EQ(s.history[i].iteration, static_cast<int>(i) + 1);
    EXPECT_TRUE(std::isfinite(s.history[i].J));
    // MMA evaluates the constraints at every point it evaluates f at.
    EXPECT_TRUE(std::isfinite(s.history[i].primal_inf)) << i;
    if (i > 0) {
      EXPECT_GE(s.history[i].cpu_seconds, s.history[i - 1].cpu_seconds);
    }
  }
  EXPECT_NEAR(s.history[0].J, 29.0, 1e-12);           // f(-1, 0.5) = 4 + 100 * 0.25
  EXPECT_NEAR(s.history[0].primal_inf, 0.25, 1e-12);  // |(-1, 0.5)|^2 - 1
}

TEST(NloptAdapter, RefusesSizesBeyondItsLimits) {
  const Hs071 nlp;
  NloptOptions options;
  options.slsqp_max_variables = 3;
  NlpSolution s = SolveNlpWithNlopt(nlp, nlp.StartingPoint(), options);
  EXPECT_EQ(s.status, SolveStatus::kNotApplicable);
  EXPECT_NE(s.message.find("slsqp_max_variables"), std::string::npos) << s.message;
  options = NloptOptions();
  options.max_dense_jacobian = 7;  // m n = 8
  s = SolveNlpWithNlopt(nlp, nlp.StartingPoint(), options);
  EXPECT_EQ(s.status, SolveStatus::kNotApplicable);
  EXPECT_NE(s.message.find("max_dense_jacobian"), std::string::npos) << s.message;
  options = NloptOptions();
  options.algorithm = "LD_MMA";
  options.mma_max_inequalities = 0;
  s = SolveNlpWithNlopt(RosenbrockDisc(), RosenbrockDisc().StartingPoint(), options);
  EXPECT_EQ(s.status, SolveStatus::kNotApplicable);
  EXPECT_NE(s.message.find("mma_max_inequalities"), std::string::npos) << s.message;
}

TEST(NloptStatus, EveryResultCodeHasANameAndAGroup) {
  EXPECT_EQ(MapNloptResult(NLOPT_SUCCESS, false), SolveStatus::kConverged);
  EXPECT_EQ(MapNloptResult(NLOPT_STOPVAL_REACHED, false), SolveStatus::kConverged);
  EXPECT_EQ(MapNloptResult(NLOPT_FTOL_REACHED, false), SolveStatus::kConverged);
  EXPECT_EQ(MapNloptResult(NLOPT_XTOL_REACHED, false), SolveStatus::kConverged);
  EXPECT_EQ(MapNloptResult(NLOPT_MAXEVAL_REACHED, false), SolveStatus::kMaxTime);
  EXPECT_EQ(MapNloptResult(NLOPT_MAXTIME_REACHED, false), SolveStatus::kMaxTime);
  EXPECT_EQ(MapNloptResult(NLOPT_ROUNDOFF_LIMITED, false), SolveStatus::kRoundoffLimited);
  EXPECT_EQ(MapNloptResult(NLOPT_INVALID_ARGS, false), SolveStatus::kInvalidInput);
  EXPECT_EQ(MapNloptResult(NLOPT_FORCED_STOP, true), SolveStatus::kNumericalFailure);
  EXPECT_EQ(MapNloptResult(NLOPT_FORCED_STOP, false), SolveStatus::kError);
  EXPECT_EQ(MapNloptResult(NLOPT_FAILURE, false), SolveStatus::kError);
  EXPECT_EQ(MapNloptResult(NLOPT_OUT_OF_MEMORY, false), SolveStatus::kError);
  for (int code = NLOPT_FORCED_STOP; code <= NLOPT_MAXTIME_REACHED; ++code) {
    if (code == 0) continue;
    // Our names agree with NLopt's own.
    EXPECT_EQ(NloptResultName(code), nlopt_result_to_string(static_cast<nlopt_result>(code)));
  }
  EXPECT_EQ(NloptResultName(99), "UNKNOWN_RESULT(99)");
}

TEST(NloptOptions, DefaultsAreValidAndOptionsAreResolvedBySchema) {
  std::string error;
  EXPECT_TRUE(NloptOptions().IsValid(&error)) << error;
  const NloptOptions o = NloptOptions::Apply({{"algorithm", "LD_MMA"},
                                              {"ftol_rel", "1e-6"},
                                              {"maxeval", "50"},
                                              {"record_history", "false"}},
                                             NloptOptions());
  EXPECT_EQ(o.algorithm, "LD_MMA");
  EXPECT_EQ(o.ftol_rel, 1e-6);
  EXPECT_EQ(o.maxeval, 50);
  EXPECT_FALSE(o.record_history);
  auto message = [](const std::map<std::string, std::string>& m) {
    try {
      NloptOptions::Apply(m, NloptOptions());
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_NE(message({{"max_eval", "5"}}).find("'max_eval'"), std::string::npos);
  EXPECT_NE(message({{"max_eval", "5"}}).find("maxeval"), std::string::npos);
  EXPECT_NE(message({{"algorithm", "LN_COBYLA"}}).find("LD_SLSQP"), std::string::npos);
  EXPECT_NE(message({{"local_algorithm", "AUGLAG"}}).find("local_algorithm"), std::string::npos);
  EXPECT_NE(message({{"maxeval", "0"}}).find("'maxeval': must be an integer >= 1"),
            std::string::npos)
      << message({{"maxeval", "0"}});
  // The one grammar: an integer option takes 1e3, a number option inf only where allowed.
  EXPECT_EQ(NloptOptions::Apply({{"maxeval", "1e3"}}, NloptOptions()).maxeval, 1000);
  EXPECT_NE(message({{"ftol_rel", "inf"}}).find("'ftol_rel'"), std::string::npos);
  EXPECT_NE(message({{"maxtime", "x"}}).find("number"), std::string::npos);
}

// ---- optimal-control problems through the solver ----------------------------------------------

SolveRequest ShootingRequest(double tf, int N, TerminalMode mode) {
  SolveRequest request;
  request.grid = TimeGrid::Uniform(0.0, tf, N);
  request.terminal = mode;
  request.transcription = "single-shooting";
  return request;
}

// Single shooting of the double integrator, N = 20, penalty form (bounds only): every algorithm
// reaches Ipopt's optimum of the same NLP. MMA and CCSAQ are first-order methods with
// conservative models; on this penalized problem (C = 1000) their steps shrink and NLopt's
// ftol_rel test stops them early: measured 0.3% and 0.06% above the optimum after ~3600
// evaluations, where the stationarity check finds relative KKT residuals of 2.8e-2 and 1.2e-2
// (> stationarity_tol = 1e-2): step_too_small, NLopt's FTOL_REACHED kept. The stated tolerances
// are those measurements rounded up.
TEST(NloptSolver, EveryAlgorithmOnThePenalizedDoubleIntegrator) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  SolveRequest request = ShootingRequest(1.0, 20, TerminalMode::kPenalty);
  request.transcription = "single-shooting";
  const SolveResult ipopt = FindSolver("ipopt").make()->Solve(*ocp, request);
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged);
  const NloptSolver solver;
  const std::map<std::string, double> tolerance = {{"LD_SLSQP", 1e-8},
                                                   {"LD_LBFGS", 1e-8},
                                                   {"AUGLAG", 1e-8},
                                                   {"AUGLAG_EQ", 1e-8},
                                                   {"LD_MMA", 4e-3},
                                                   {"LD_CCSAQ", 1e-3}};
  for (const auto& [alg, tol] : tolerance) {
    request.options.Set("algorithm", alg);
    const SolveResult r = solver.Solve(*ocp, request);
    const bool creeps = alg == "LD_MMA" || alg == "LD_CCSAQ";
    EXPECT_EQ(r.status, creeps ? SolveStatus::kStepTooSmall : SolveStatus::kConverged)
        << alg << ": " << r.message;
    EXPECT_GE(r.objective, ipopt.objective * (1.0 - 1e-10)) << alg;
    EXPECT_LE(r.objective, ipopt.objective * (1.0 + tol)) << alg;
    EXPECT_EQ(r.solver, "nlopt");
    EXPECT_EQ(static_cast<int>(r.history.size()), r.iterations) << alg;
    // The evaluator judges the same controls and finds the same cost.
    const Evaluation ev = Evaluate(*ocp, r.controls, request.grid, Integrator::kEuler);
    EXPECT_NEAR(ev.J, r.objective, 1e-10 * r.objective) << alg;
  }
}

TEST(NloptSolver, HardTerminalConstraintsOnTheBoundedDoubleIntegrator) {
  // |u| <= 5 as bounds, psi = 0 as two equalities (dense rows from the adjoint).
  const auto ocp = MakeProblem("double-integrator-bounded", {}, 0);
  SolveRequest request = ShootingRequest(1.0, 20, TerminalMode::kHard);
  const SolveResult ipopt = FindSolver("ipopt").make()->Solve(*ocp, request);
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged);
  const NloptSolver solver;
  for (const std::string alg : {"LD_SLSQP", "AUGLAG", "AUGLAG_EQ"}) {
    request.options.Set("algorithm", alg);
    const SolveResult r = solver.Solve(*ocp, request);
    EXPECT_EQ(r.status, SolveStatus::kConverged) << alg << ": " << r.message;
    EXPECT_NEAR(r.objective, ipopt.objective, 1e-6 * ipopt.objective) << alg;
    const Evaluation ev = Evaluate(*ocp, r.controls, request.grid, Integrator::kEuler);
    EXPECT_LT(ev.terminal_violation, 1e-6) << alg;
    EXPECT_LE(ev.control_violation, 0.0) << alg;
  }
  for (const std::string alg : {"LD_MMA", "LD_CCSAQ", "LD_LBFGS"}) {
    request.options.Set("algorithm", alg);
    const SolveResult r = solver.Solve(*ocp, request);
    EXPECT_EQ(r.status, SolveStatus::kNotApplicable) << alg;
    EXPECT_EQ(r.controls.values().cols(), 20);  // the starting controls, still judged
  }
}

// ---- the paper's problem: every algorithm the adapter offers ----------------------------------
// comm-path2d as registered (the predicted channel as a bicubic map, seed 1), N = 20 (dt = 2 s),
// single shooting: n = 60 controls, the ball |u_k| <= umax as 20 inequality rows (and, in hard
// form, psi(x_N) = 0 as 5 equalities). Reference: Ipopt on the Euler transcription, the same
// discrete problem. Each case states NLopt's outcome and how far above Ipopt's J it may end.

struct PaperCase {
  const char* algorithm;
  const char* local;  // AUGLAG / AUGLAG_EQ only
  int maxeval;        // 0: the default (20000)
  SolveStatus status;
  const char* solver_status;
  double gap;            // (J - J_ipopt) / J_ipopt <= gap (converged or stopped runs)
  const char* refusal;   // kNotApplicable: a substring of the stated reason
  bool feasible = true;  // false: stopped at a point violating the constraints by > 1e-3
};

// Runs NLopt on `request` for every case and judges it against Ipopt on `reference` (the same
// discrete problem).
void ExpectCases(const Ocp& ocp,
                 const SolveRequest& reference,
                 SolveRequest request,
                 const std::vector<PaperCase>& cases) {
  const SolveResult ipopt = FindSolver("ipopt").make()->Solve(ocp, reference);
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged) << ipopt.message;
  const NloptSolver solver;
  for (const PaperCase& c : cases) {
    const std::string name = std::string(c.algorithm) + "(" + c.local + ")";
    request.options = {{"local_algorithm", c.local}};
    request.options.Set("algorithm", c.algorithm);
    if (c.maxeval > 0) request.options.Set("maxeval", std::to_string(c.maxeval));
    const SolveResult r = solver.Solve(ocp, request);
    EXPECT_EQ(r.status, c.status) << name << ": " << r.message;
    EXPECT_EQ(r.solver_status, c.solver_status) << name << ": " << r.message;
    if (c.status == SolveStatus::kNotApplicable) {
      EXPECT_NE(r.message.find(c.refusal), std::string::npos) << name << ": " << r.message;
      EXPECT_EQ(r.iterations, -1) << name;  // refused before any evaluation
      continue;
    }
    if (!c.feasible) {
      EXPECT_GT(r.solver_stats.at("nlp_violation"), 1e-3) << name;
      continue;
    }
    const double gap = (r.objective - ipopt.objective) / ipopt.objective;
    // Nobody beats the same NLP's optimum, beyond Ipopt's tolerance and what a violation within
    // feasibility_tol buys (AUGLAG on collocation: 4e-8 below at a violation of 2e-9).
    EXPECT_GE(gap, -1e-7) << name;
    EXPECT_LE(gap, c.gap) << name << ": J = " << r.objective << " vs " << ipopt.objective;
    EXPECT_LE(r.solver_stats.at("nlp_violation"), 1e-6) << name;
  }
}

void ExpectPaperCases(TerminalMode mode, const std::vector<PaperCase>& cases) {
  const auto ocp = MakeProblem("comm-path2d", {}, 1);
  SolveRequest reference = ShootingRequest(ocp->tf(), 20, mode);
  reference.transcription = "euler";
  ExpectCases(*ocp, reference, ShootingRequest(ocp->tf(), 20, mode), cases);
}

// Penalty form (the paper's). Measured gaps: SLSQP and every AUGLAG around L-BFGS or SLSQP below
// 2e-9. MMA and CCSAQ creep (conservative first-order models): after 1000 evaluations still
// 1.4e-3 and 1.2e-3 above (after 2000: the same to two digits). Around MMA or CCSAQ, AUGLAG's local
// run stops at local_maxeval = 5000 and the next one barely moves, so NLopt's outer ftol test
// reports FTOL_REACHED 1.0e-3 to 1.3e-3 above the optimum: "converged" from NLopt means f stopped
// changing, not that it is optimal. OCPBench's stationarity check (relative KKT residuals 0.47 to
// 1.0 there, against 1e-2) reports them step_too_small, NLopt's FTOL_REACHED kept. L-BFGS takes
// bounds only, so the ball rows refuse it (alone, or as AUGLAG_EQ's local algorithm, which keeps
// the inequalities).
TEST(NloptSolver, PaperProblemPenaltyFormEveryAlgorithm) {
  const SolveStatus ok = SolveStatus::kConverged, stop = SolveStatus::kMaxTime,
                    no = SolveStatus::kNotApplicable, stall = SolveStatus::kStepTooSmall;
  ExpectPaperCases(
      TerminalMode::kPenalty,
      {
          {"LD_SLSQP", "LD_LBFGS", 0, ok, "FTOL_REACHED", 1e-8, ""},
          {"AUGLAG", "LD_LBFGS", 0, ok, "FTOL_REACHED", 1e-8, ""},
          {"AUGLAG", "LD_SLSQP", 0, ok, "FTOL_REACHED", 1e-8, ""},
          {"AUGLAG_EQ", "LD_SLSQP", 0, ok, "FTOL_REACHED", 1e-8, ""},
          {"LD_MMA", "LD_LBFGS", 1000, stop, "MAXEVAL_REACHED", 3e-3, ""},
          {"LD_CCSAQ", "LD_LBFGS", 1000, stop, "MAXEVAL_REACHED", 3e-3, ""},
          {"AUGLAG", "LD_MMA", 0, stall, "FTOL_REACHED", 2.5e-3, ""},
          {"AUGLAG", "LD_CCSAQ", 0, stall, "FTOL_REACHED", 2.5e-3, ""},
          {"AUGLAG_EQ", "LD_MMA", 0, stall, "FTOL_REACHED", 2.5e-3, ""},
          {"AUGLAG_EQ", "LD_CCSAQ", 0, stall, "FTOL_REACHED", 2.5e-3, ""},
          {"LD_LBFGS", "LD_LBFGS", 0, no, "not_run", 0, "takes only bound constraints"},
          {"AUGLAG_EQ", "LD_LBFGS", 0, no, "not_run", 0, "local algorithm LD_LBFGS"},
      });
}

// Hard form, psi(x_N) = 0: SLSQP and AUGLAG(L-BFGS) reach Ipopt's optimum (measured gaps below
// 2e-9). AUGLAG around SLSQP ends with NLopt's generic FAILURE (after ~900 evaluations, at a point
// within 1e-9 of the optimum): reported as an error, never as converged. AUGLAG_EQ(MMA) stops at
// the evaluation limit still violating psi = 0 by ~3 (measured at 2000 evaluations; 20000 take
// 1.2 s and end 8e-3 off). MMA, CCSAQ and L-BFGS take no equalities: refused.
TEST(NloptSolver, PaperProblemHardFormEveryAlgorithm) {
  const SolveStatus ok = SolveStatus::kConverged, stop = SolveStatus::kMaxTime,
                    no = SolveStatus::kNotApplicable, error = SolveStatus::kError;
  ExpectPaperCases(TerminalMode::kHard,
                   {
                       {"LD_SLSQP", "LD_LBFGS", 0, ok, "FTOL_REACHED", 1e-8, ""},
                       {"AUGLAG", "LD_LBFGS", 0, ok, "FTOL_REACHED", 1e-8, ""},
                       {"AUGLAG", "LD_SLSQP", 0, error, "FAILURE", 1e-8, ""},
                       {"AUGLAG_EQ", "LD_SLSQP", 0, error, "FAILURE", 1e-8, ""},
                       {"AUGLAG_EQ", "LD_MMA", 2000, stop, "MAXEVAL_REACHED", 0, "", false},
                       {"LD_MMA", "LD_LBFGS", 0, no, "not_run", 0, "takes no equality"},
                       {"LD_CCSAQ", "LD_LBFGS", 0, no, "not_run", 0, "takes no equality"},
                       {"LD_LBFGS", "LD_LBFGS", 0, no, "not_run", 0, "takes no equality"},
                   });
}

// NLopt on a collocation transcription: Hermite-Simpson, double integrator, hard form, N = 10
// (n = 63 variables, 42 equalities: 40 defects and psi). Reference: Ipopt on the same NLP.
// Measured: SLSQP 1.9e-11 above Ipopt (28 evaluations); AUGLAG and AUGLAG_EQ around L-BFGS stop
// by their x tolerance 4.4e-8 below it at a defect violation of 1.9e-9 (1202 evaluations).
// Around SLSQP they end the same way but need 3594 evaluations (0.9 s), so they are left out
// here. The equalities refuse MMA, CCSAQ and L-BFGS.
TEST(NloptSolver, EveryAlgorithmOnHermiteSimpsonCollocation) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  SolveRequest request = ShootingRequest(1.0, 10, TerminalMode::kHard);
  request.transcription = "hermite-simpson";
  const SolveStatus ok = SolveStatus::kConverged, no = SolveStatus::kNotApplicable;
  ExpectCases(*ocp,
              request,
              request,
              {
                  {"LD_SLSQP", "LD_LBFGS", 0, ok, "FTOL_REACHED", 1e-8, ""},
                  {"AUGLAG", "LD_LBFGS", 0, ok, "XTOL_REACHED", 1e-8, ""},
                  {"AUGLAG_EQ", "LD_LBFGS", 0, ok, "XTOL_REACHED", 1e-8, ""},
                  {"LD_MMA", "LD_LBFGS", 0, no, "not_run", 0, "takes no equality"},
                  {"LD_CCSAQ", "LD_LBFGS", 0, no, "not_run", 0, "takes no equality"},
                  {"LD_LBFGS", "LD_LBFGS", 0, no, "not_run", 0, "takes no equality"},
              });
}

// The default refusal limits at the sizes they were set from (NloptOptions; measured on this
// problem, solvers/README-nlp.md). One evaluation (maxeval = 1) shows a size just inside a limit
// runs; the path-loss channel keeps the problem cheap to build (the limits count sizes only).
TEST(NloptSolver, DefaultLimitsOnThePapersGrids) {
  const auto ocp = MakeProblem("comm-path2d", {"channel=0"}, 1);
  const NloptSolver solver;
  auto run = [&](const std::string& algorithm, int N, bool one_evaluation) {
    SolveRequest request = ShootingRequest(ocp->tf(), N, TerminalMode::kPenalty);
    if (one_evaluation) request.options = {{"maxeval", "1"}};
    request.options.Set("algorithm", algorithm);
    return solver.Solve(*ocp, request);
  };
  // SLSQP: n = 3N; the paper's N = 400 (n = 1200) is refused, N = 166 (n = 498) runs.
  SolveResult r = run("LD_SLSQP", 400, false);
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_NE(r.message.find("n = 1200 > slsqp_max_variables = 500"), std::string::npos) << r.message;
  EXPECT_EQ(run("LD_SLSQP", 166, true).solver_status, "MAXEVAL_REACHED");
  // MMA / CCSAQ: N ball rows.
  for (const std::string alg : {"LD_MMA", "LD_CCSAQ"}) {
    r = run(alg, 201, false);
    EXPECT_EQ(r.status, SolveStatus::kNotApplicable) << alg;
    EXPECT_NE(r.message.find("201 > mma_max_inequalities = 200"), std::string::npos) << r.message;
    EXPECT_EQ(run(alg, 200, true).solver_status, "MAXEVAL_REACHED") << alg;
  }
  // AUGLAG: m n = N * 3N > 2e7 from N = 2582.
  r = run("AUGLAG", 2600, false);
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_NE(r.message.find("max_dense_jacobian"), std::string::npos) << r.message;
}

TEST(NloptSolver, AlgorithmOptionOverridesAndBadRequestsThrow) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const NloptSolver solver;
  SolveRequest request = ShootingRequest(1.0, 5, TerminalMode::kHard);
  request.options.Set("algorithm", "LD_LBFGS");
  EXPECT_EQ(solver.Solve(*ocp, request).status, SolveStatus::kNotApplicable);
  request.options.Set("algorithm", "LD_NEWTON");
  EXPECT_THROW(solver.Solve(*ocp, request), std::invalid_argument);
  request.options = {{"tol", "1e-8"}};  // an Ipopt key
  EXPECT_THROW(solver.Solve(*ocp, request), std::invalid_argument);
  EXPECT_TRUE(FindSolver("nlopt").uses_transcription);
}

}  // namespace
}  // namespace ocpb
