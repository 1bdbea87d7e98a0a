// The indirect method with a free final time: the unknown T and the condition H(T) = 0
// (PmpResidual, IndirectNewton), on the free-final-time reference problems.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/evaluator.h"
#include "problems/reference/free_time_brachistochrone.h"
#include "problems/reference/free_time_double_integrator.h"
#include "problems/registry.h"
#include "solvers/indirect_newton.h"
#include "solvers/pmp_residual.h"
#include "solvers/registry.h"
#include "tests/solvers/indirect_test_support.h"

namespace ocpb {
namespace {

const double kT = FreeTimeDoubleIntegrator::OptimalTime();

// The analytic costate of double-integrator-free-time: p1 = -12/T^3, p2 = 12 t/T^3 - 6/T^2.
Vec ExactCostate(double t) {
  Vec p(2);
  p << -12.0 / std::pow(kT, 3), 12.0 * t / std::pow(kT, 3) - 6.0 / (kT * kT);
  return p;
}

std::unique_ptr<Ocp> DoubleIntegratorFreeTime(std::vector<std::string> set = {}) {
  return MakeProblem("double-integrator-free-time", set, 0);
}

// ---- the problems ------------------------------------------------------------------------------

TEST(FreeFinalTimeProblems, DeclareTheirBoundsAndAreAutonomous) {
  for (const char* name : {"double-integrator-free-time", "brachistochrone-free-time"}) {
    SCOPED_TRACE(name);
    const ProblemInfo& info = FindProblem(name);
    EXPECT_NE(info.hamiltonian_note.find("not applicable"), std::string::npos);
    ASSERT_TRUE(info.reference_value.has_value());
    const auto ocp = MakeProblem(name, {}, 0);
    ASSERT_TRUE(ocp->free_final_time().has_value());
    EXPECT_DOUBLE_EQ(ocp->free_final_time()->lower, 0.1);
    EXPECT_TRUE(ocp->AdmitsFinalTime(0.1));
    EXPECT_TRUE(ocp->AdmitsFinalTime(3.0));
    EXPECT_FALSE(ocp->AdmitsFinalTime(0.05));
    EXPECT_FALSE(ocp->AdmitsFinalTime(NAN));
    // f and L do not depend on t (the contract of a free final time).
    const Vec x = Vec::LinSpaced(ocp->nx(), 0.3, 1.1);
    const Vec u = Vec::Constant(ocp->nu(), 0.4);
    Vec f0(ocp->nx()), f1(ocp->nx());
    ocp->Dynamics(0.0, x, u, f0);
    ocp->Dynamics(7.5, x, u, f1);
    EXPECT_EQ(f0, f1);
    EXPECT_EQ(ocp->RunningCost(0.0, x, u), ocp->RunningCost(7.5, x, u));
  }
  EXPECT_NEAR(*FindProblem("double-integrator-free-time").reference_value, 2.7463561, 1e-7);
  // A nominal tf outside the bounds is bad input, named.
  EXPECT_THROW(DoubleIntegratorFreeTime({"tf=0.05"}), std::invalid_argument);
  EXPECT_THROW(DoubleIntegratorFreeTime({"tf_min=3", "tf_max=2", "tf=2.5"}), std::invalid_argument);
  // Fixed-horizon problems admit their own tf only.
  const auto fixed = MakeProblem("double-integrator", {}, 0);
  EXPECT_FALSE(fixed->free_final_time().has_value());
  EXPECT_TRUE(fixed->AdmitsFinalTime(1.0));
  EXPECT_FALSE(fixed->AdmitsFinalTime(1.1));
}

TEST(FreeFinalTimeProblems, EvaluatorJudgesTheSolutionsHorizonWithinTheBounds) {
  const auto ocp = DoubleIntegratorFreeTime();
  const TimeGrid grid = TimeGrid::Uniform(0.0, 2.0, 20);
  const ControlTrajectory u = ControlTrajectory::Constant(grid, Vec::Ones(1));
  const Evaluation ev = Evaluate(*ocp, u, grid, Integrator::kRk4);
  EXPECT_NEAR(ev.Jbar, 2.0 * 1.5, 1e-12);  // int_0^2 (1 + 1/2) dt
  EXPECT_NEAR(ev.X(0, 20), -1.0 + 2.0, 1e-12);
  const TimeGrid beyond = TimeGrid::Uniform(0.0, 200.0, 20);
  EXPECT_THROW(
      Evaluate(*ocp, ControlTrajectory::Constant(beyond, Vec::Ones(1)), beyond, Integrator::kRk4),
      std::invalid_argument);
}

TEST(FreeFinalTimeProblems, MethodsThatKeepTheHorizonFixedReportNotApplicable) {
  const auto ocp = DoubleIntegratorFreeTime();
  for (const char* solver : {"hamiltonian", "ipopt", "nlopt"}) {
    SCOPED_TRACE(solver);
    SolveRequest request = Request(*ocp, 20);
    request.transcription = "single-shooting";
    if (std::string(solver) == "nlopt") request.options.Set("algorithm", "LD_SLSQP");
    const SolveResult r = FindSolver(solver).make()->Solve(*ocp, request);
    EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
    EXPECT_EQ(r.solver_status, "not_applicable");
    EXPECT_NE(r.message.find("free final time"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("indirect-newton"), std::string::npos) << r.message;
  }
}

// ---- the residual with T -----------------------------------------------------------------------

TEST(PmpResidualFreeTime, HasTheTimeUnknownAndTheHamiltonianRow) {
  const auto ocp = DoubleIntegratorFreeTime();
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, 4);
  for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
    PmpResidual pmp(*ocp, grid, mode);
    EXPECT_TRUE(pmp.free_final_time());
    EXPECT_EQ(pmp.size(), 2 * 2 * 5 + pmp.num_multipliers() + 1);
    const Mat X = Mat::Constant(2, 5, 0.3), P = Mat::Constant(2, 5, -0.7);
    const Vec nu = Vec::Constant(pmp.num_multipliers(), 0.2);
    const Vec z = pmp.Pack(X, P, nu, 1.7);
    EXPECT_DOUBLE_EQ(pmp.FinalTime(z), 1.7);
    const TimeGrid g = pmp.GridOf(z);
    EXPECT_DOUBLE_EQ(g.tf(), 1.7);
    EXPECT_NEAR(g.t(1), 1.7 / 4, 1e-15);
    Mat X2, P2;
    Vec nu2;
    pmp.Unpack(z, &X2, &P2, &nu2);
    EXPECT_EQ(X2, X);
    EXPECT_EQ(P2, P);
    EXPECT_EQ(nu2, nu);
    // The last row is H at the last node: with u* = -p2 = 0.7, H = 1 + p1 x2 + p2 u + u^2/2.
    Vec F(pmp.size());
    ASSERT_TRUE(pmp.Evaluate(z, F, nullptr, false));
    EXPECT_NEAR(F[pmp.size() - 1], 1.0 - 0.7 * 0.3 - 0.7 * 0.7 + 0.5 * 0.49, 1e-14);
    // T outside the bounds (or at t0) is a failed evaluation, not a number.
    for (double T : {0.05, 0.0, 150.0}) {
      EXPECT_FALSE(pmp.Evaluate(pmp.Pack(X, P, nu, T), F, nullptr, false)) << T;
      EXPECT_EQ(pmp.failure(), PmpResidual::Failure::kBadFinalTime);
    }
  }
}

TEST(PmpResidualFreeTime, JacobianMatchesFiniteDifferences) {
  const auto di = DoubleIntegratorFreeTime();
  const auto brach = MakeProblem("brachistochrone-free-time", {}, 0);
  for (const Ocp* ocp : {di.get(), brach.get()}) {
    for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
      SCOPED_TRACE(ocp->name() + " " + ToString(mode));
      PmpResidual pmp(*ocp, TimeGrid::Uniform(ocp->t0(), ocp->tf(), 5), mode);
      Vec z = SomePoint(pmp.size(), 0.8, 0.1);
      z[pmp.size() - 1] = 1.3;  // T
      ExpectJacobianMatchesFiniteDifferences(*ocp, mode, z);
    }
  }
}

// ---- Newton with T -----------------------------------------------------------------------------

// Hard form from u = 1 on [0, 1]: T, the costate and the cost converge to the analytic optimum at
// second order (T* = 18^(1/4), J* = 4 T*/3), H vanishes along the whole discrete solution to
// O(h^2), and the tail is quadratic.
TEST(IndirectNewtonFreeTime, DoubleIntegratorReachesTheAnalyticOptimumAtSecondOrder) {
  const auto ocp = DoubleIntegratorFreeTime();
  double errT[2], errP[2], errJ[2];
  for (int i = 0; i < 2; ++i) {
    const int N = 50 << i;
    const SolveResult r = IndirectNewton().Solve(*ocp, Request(*ocp, N, TerminalMode::kHard));
    ExpectConverged(r);
    EXPECT_GE(ExpectQuadraticTail(r, 1e3), 1);
    const double T = r.state_grid.tf();
    EXPECT_DOUBLE_EQ(r.solver_stats.at("final_time"), T);
    EXPECT_EQ(r.controls.grid().tf(), T);
    errT[i] = std::abs(T - kT);
    errP[i] = 0.0;
    double worstH = 0.0;
    Vec u(1);
    for (int k = 0; k <= N; ++k) {
      const double t = r.state_grid.t(k);
      errP[i] = std::max(errP[i], (r.costates.col(k) - ExactCostate(t * kT / T)).lpNorm<1>());
      ocp->MinimizeHamiltonian(t, r.states.col(k), r.costates.col(k), u);
      worstH =
          std::max(worstH, std::abs(ocp->Hamiltonian(t, r.states.col(k), u, r.costates.col(k))));
    }
    EXPECT_LE(worstH, 10.0 / (N * N)) << N;
    const Evaluation ev = Evaluate(*ocp, r.controls, r.state_grid.Refined(10), Integrator::kRk4);
    errJ[i] = std::abs(ev.Jbar - FreeTimeDoubleIntegrator::OptimalCost());
    EXPECT_LE(ev.terminal_violation, 1e-3);
  }
  EXPECT_LE(errT[0], 1e-3);
  EXPECT_NEAR(std::log2(errT[0] / errT[1]), 2.0, 0.15) << errT[0] << " " << errT[1];
  EXPECT_NEAR(std::log2(errP[0] / errP[1]), 2.0, 0.2) << errP[0] << " " << errP[1];
  EXPECT_GT(errJ[0] / errJ[1], 3.0) << errJ[0] << " " << errJ[1];
}

// Penalty form: T solves the penalized problem (C = 1e3), whose optimum moves to T* as C grows;
// H(T) = 0 holds at the solution either way (it is the residual's last row).
TEST(IndirectNewtonFreeTime, DoubleIntegratorPenaltyFormConvergesTowardsTheHardOptimum) {
  double gap[2];
  for (int i = 0; i < 2; ++i) {
    const auto ocp = DoubleIntegratorFreeTime({i == 0 ? "C=1e3" : "C=1e5"});
    const SolveResult r = IndirectNewton().Solve(*ocp, Request(*ocp, 200));
    ExpectConverged(r);
    EXPECT_GE(ExpectQuadraticTail(r, 1e3), 1);
    gap[i] = std::abs(r.state_grid.tf() - kT);
  }
  EXPECT_LE(gap[0], 3e-3);
  EXPECT_LT(gap[1], gap[0] / 10.0) << gap[0] << " " << gap[1];
}

// The optimum lies above tf_max: Newton keeps T within the bounds and says the line search
// failed rather than reporting a root outside them.
TEST(IndirectNewtonFreeTime, AnOptimumBeyondTheBoundIsALineSearchFailure) {
  const auto ocp = DoubleIntegratorFreeTime({"tf_max=1.5"});
  const SolveResult r = IndirectNewton().Solve(*ocp, Request(*ocp, 50, TerminalMode::kHard));
  EXPECT_NE(r.status, SolveStatus::kConverged);
  EXPECT_LE(r.state_grid.tf(), 1.5 + 1e-9);
  EXPECT_GT(r.history.back().primal_inf, 1e-3);
}

// The brachistochrone with an explicit T, started from Ipopt's solution of the time-scaled
// "brachistochrone" (its states, multiplier costates and clock): Newton converges to the
// cycloid's time at second order in both terminal forms, from a start whose costates are
// those of a different formulation. (From the default controls the costates are zero in the hard
// form, so w* is undefined at the start: singular_minimizer; solvers/README-indirect.md.)
TEST(IndirectNewtonFreeTime, BrachistochroneFromTheTimeScaledIpoptSolution) {
  const auto scaled = MakeProblem("brachistochrone", {}, 0);
  const auto ocp = MakeProblem("brachistochrone-free-time", {}, 0);
  double err[2];
  for (int i = 0; i < 2; ++i) {
    const int N = 50 << i;
    SolveRequest ipopt_request = Request(*scaled, N, TerminalMode::kHard);
    ipopt_request.transcription = "trapezoid";
    const SolveResult start = FindSolver("ipopt").make()->Solve(*scaled, ipopt_request);
    ASSERT_TRUE(IsSuccess(start.status)) << start.message;
    ASSERT_EQ(start.costates.cols(), N + 1);
    const double T0 = start.states(3, N);  // the clock
    for (TerminalMode mode : {TerminalMode::kHard, TerminalMode::kPenalty}) {
      SCOPED_TRACE(std::to_string(N) + " " + ToString(mode));
      SolveRequest request = Request(*ocp, N, mode);
      request.grid = TimeGrid::Uniform(0.0, T0, N);
      const SolveResult r = IndirectNewton().SolveFrom(
          *ocp, request, start.states.topRows(3), start.costates.topRows(3));
      ExpectConverged(r);
      EXPECT_LE(r.iterations, 8);
      if (mode == TerminalMode::kHard) {
        err[i] = std::abs(r.state_grid.tf() - FreeTimeBrachistochrone::kReferenceTime);
      } else {
        EXPECT_NEAR(r.state_grid.tf(), FreeTimeBrachistochrone::kReferenceTime, 2e-3);
      }
    }
  }
  EXPECT_LE(err[0], 1e-3);
  EXPECT_NEAR(std::log2(err[0] / err[1]), 2.0, 0.3) << err[0] << " " << err[1];
}

// ---- the direct transcriptions with T as a variable -------------------------------------------

// Ipopt with T as the NLP's last variable: Hermite-Simpson and LGR are exact on the double
// integrator (cubic states, linear control), the trapezoid is second order and Euler at least
// first order in T; on the brachistochrone Hermite-Simpson and LGR reach the cycloid's T* to 1e-6.
// The result's grid and controls live on [0, T] and solver_stats["final_time"] says T.
TEST(DirectFreeTime, IpoptOnEveryCollocationTranscriptionReachesTheOptimalTime) {
  const auto di = DoubleIntegratorFreeTime();
  const auto brach = MakeProblem("brachistochrone-free-time", {}, 0);
  auto solve = [](const Ocp& ocp, const std::string& scheme, int N) {
    SolveRequest request = Request(ocp, N, TerminalMode::kHard);
    request.transcription = scheme;
    const SolveResult r = FindSolver("ipopt").make()->Solve(ocp, request);
    EXPECT_EQ(r.status, SolveStatus::kConverged) << scheme << ": " << r.message;
    EXPECT_DOUBLE_EQ(r.solver_stats.at("final_time"), r.state_grid.tf());
    EXPECT_DOUBLE_EQ(r.controls.grid().tf(), r.state_grid.tf());
    return r.state_grid.tf();
  };
  for (const char* scheme : {"hermite-simpson", "lgr"}) {
    SCOPED_TRACE(scheme);
    EXPECT_NEAR(solve(*di, scheme, 20), kT, 1e-8);
    EXPECT_NEAR(solve(*brach, scheme, 50), FreeTimeBrachistochrone::kReferenceTime, 1e-6);
  }
  const double trap[2] = {std::abs(solve(*di, "trapezoid", 50) - kT),
                          std::abs(solve(*di, "trapezoid", 100) - kT)};
  EXPECT_NEAR(std::log2(trap[0] / trap[1]), 2.0, 0.2) << trap[0] << " " << trap[1];
  const double euler[2] = {std::abs(solve(*di, "euler", 50) - kT),
                           std::abs(solve(*di, "euler", 100) - kT)};
  // Euler is first order in general; its T here comes out second order (2.1e-4, 5.1e-5).
  EXPECT_GT(std::log2(euler[0] / euler[1]), 0.8) << euler[0] << " " << euler[1];
  // The multiplier costates on the stretched grid follow the analytic costate.
  SolveRequest request = Request(*di, 40, TerminalMode::kHard);
  request.transcription = "hermite-simpson";
  const SolveResult r = FindSolver("ipopt").make()->Solve(*di, request);
  ASSERT_EQ(r.costates.cols(), r.state_grid.size());
  double err = 0.0;
  for (int k = 0; k < r.state_grid.size(); ++k) {
    err = std::max(err,
                   (r.costates.col(k) - ExactCostate(r.state_grid.t(k))).lpNorm<Eigen::Infinity>());
  }
  EXPECT_LE(err, 1e-3);
}

// The Euler transcription's controls, read on the stretched grid by the Euler evaluator,
// reproduce the NLP's own discrete problem exactly (as on a fixed horizon): every stretched node
// keeps its own interval's control (a regression: mapping times back to the nominal grid put
// nodes an ulp into the previous interval, 1e-3 terminal violation on the brachistochrone).
TEST(DirectFreeTime, EulerControlsOnTheStretchedGridReproduceTheNlp) {
  const auto ocp = MakeProblem("brachistochrone-free-time", {}, 0);
  for (int N : {100, 400}) {
    SolveRequest request = Request(*ocp, N, TerminalMode::kHard);
    request.transcription = "euler";
    const SolveResult r = FindSolver("ipopt").make()->Solve(*ocp, request);
    ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
    const TimeGrid grid = request.grid.StretchedTo(r.state_grid.tf());
    const Evaluation ev = Evaluate(*ocp, r.controls, grid, Integrator::kEuler);
    EXPECT_LE(ev.terminal_violation, 1e-8) << N;
    EXPECT_NEAR(ev.J, r.objective, 1e-9 * r.objective) << N;
    EXPECT_LE((ev.X - r.states).lpNorm<Eigen::Infinity>(), 1e-8) << N;
  }
}

// The indirect method warm-started from Ipopt's trapezoid solution of the same free-time problem
// (warm_start = ipopt, whose default costates are Ipopt's multiplier costates): where its cold
// start fails (brachistochrone-free-time), it converges in a few steps to Ipopt's T.
TEST(DirectFreeTime, IndirectNewtonWarmStartedFromIpoptOnTheBrachistochrone) {
  const auto ocp = MakeProblem("brachistochrone-free-time", {}, 0);
  for (TerminalMode mode : {TerminalMode::kHard, TerminalMode::kPenalty}) {
    SCOPED_TRACE(ToString(mode));
    const SolveResult cold = IndirectNewton().Solve(*ocp, Request(*ocp, 100, mode));
    EXPECT_NE(cold.status, SolveStatus::kConverged);
    const SolveResult r =
        IndirectNewton().Solve(*ocp, Request(*ocp, 100, mode, {{"warm_start", "ipopt"}}));
    ExpectConverged(r);
    EXPECT_LE(r.iterations, 4);
    EXPECT_GT(r.solver_stats.at("warm_start_iterations"), 0);
    EXPECT_NE(r.message.find("costates adjoint"), std::string::npos) << r.message;
    EXPECT_NEAR(r.state_grid.tf(), FreeTimeBrachistochrone::kReferenceTime, 2e-5);
  }
}

// NLopt takes the same NLP (T a variable, bounded): SLSQP on a small grid.
TEST(DirectFreeTime, NloptSlsqpSolvesTheFreeTimeDoubleIntegrator) {
  const auto ocp = DoubleIntegratorFreeTime();
  SolveRequest request = Request(*ocp, 10, TerminalMode::kHard);
  request.transcription = "hermite-simpson";
  request.options.Set("algorithm", "LD_SLSQP");
  const SolveResult r = FindSolver("nlopt").make()->Solve(*ocp, request);
  EXPECT_TRUE(IsSuccess(r.status)) << r.solver_status << ": " << r.message;
  EXPECT_NEAR(r.state_grid.tf(), kT, 1e-5);
}

}  // namespace
}  // namespace ocpb
