// JudgeResult, the one public way to judge a result: the horizon comes from the result, and what
// a status does not say (default terminal weights, a grid that is too coarse) is reported.
#include "solvers/judge.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "core/evaluator.h"
#include "problems/registry.h"
#include "solvers/registry.h"
#include "tests/core/slip_ocp.h"
#include "tests/core/user_double_integrator.h"

namespace ocpb {
namespace {

using testing::SlipOcp;
using testing::UserDoubleIntegrator;

SolveRequest RequestFor(const Ocp& ocp, int N, TerminalMode terminal, const char* transcription) {
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  request.terminal = terminal;
  request.transcription = transcription;
  return request;
}

SolveResult Solve(const char* solver, const Ocp& ocp, const SolveRequest& request) {
  return FindSolver(solver).make()->Solve(ocp, request);
}

// The free-final-time mistake: Evaluate on the request's grid judged [t0, nominal tf]
// (Jbar 1.876 instead of 2.746, terminal miss 0.58 instead of 2e-13). JudgeResult takes T from
// the result; the old recipe is now refused instead of answering.
TEST(JudgeResult, JudgesAFreeFinalTimeOnTheSolutionsOwnHorizon) {
  const auto ocp = MakeProblem("double-integrator-free-time", {}, 0);
  const SolveRequest request = RequestFor(*ocp, 25, TerminalMode::kHard, "hermite-simpson");
  const SolveResult r = Solve("ipopt", *ocp, request);
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
  const Judgement j = JudgeResult(*ocp, request, r);
  ASSERT_TRUE(j.judged);
  const double reference = *FindProblem("double-integrator-free-time").reference_value;
  EXPECT_NEAR(j.final_time, r.state_grid.tf(), 0.0);
  EXPECT_GT(std::abs(j.final_time - ocp->tf()), 0.05) << "the premise: T differs from nominal";
  EXPECT_NEAR(j.fine.Jbar, reference, 1e-8 * reference);
  EXPECT_LT(j.fine.terminal_violation, 1e-8);
  EXPECT_FALSE(j.HasWarning("discretization")) << j.discretization_gap;
  EXPECT_THROW(Evaluate(*ocp, r.controls, request.grid.Refined(10), Integrator::kRk4),
               std::invalid_argument);
}

// The default-weights mistake: penalty form, terminal weights never chosen (w = 1), and
// the double integrator "converges" far from its target. The judgement says why.
TEST(JudgeResult, ReportsTerminalWeightsThatWereNeverChosen) {
  const UserDoubleIntegrator unchosen;
  const SolveRequest penalty = RequestFor(unchosen, 50, TerminalMode::kPenalty, "euler");
  const SolveResult r = Solve("ipopt", unchosen, penalty);
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
  const Judgement j = JudgeResult(unchosen, penalty, r);
  EXPECT_TRUE(j.HasWarning("terminal_weights_default"));
  EXPECT_GT(j.fine.terminal_violation, 0.5);  // measured 0.75 (the number)
  // Chosen weights, or the hard form: nothing to report.
  const UserDoubleIntegrator chosen(-1, 1e4);
  EXPECT_FALSE(JudgeResult(chosen, penalty, Solve("ipopt", chosen, penalty))
                   .HasWarning("terminal_weights_default"));
  const SolveRequest hard = RequestFor(unchosen, 50, TerminalMode::kHard, "euler");
  EXPECT_FALSE(JudgeResult(unchosen, hard, Solve("ipopt", unchosen, hard))
                   .HasWarning("terminal_weights_default"));
}

// The indirect method "converges" (rightly, for its discrete problem) on a coarse grid whose
// continuous cost is 7x off: the warning names the grid as the problem.
TEST(JudgeResult, ReportsAGridWhereTheDiscreteProblemIsNotTheContinuousOne) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const SolveRequest coarse = RequestFor(*ocp, 2, TerminalMode::kPenalty, "");
  const SolveResult r = Solve("indirect-newton", *ocp, coarse);
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
  const Judgement j = JudgeResult(*ocp, coarse, r);
  EXPECT_GT(j.fine.J, 5.0 * r.objective);  // measured 114.2 against 15.76
  EXPECT_GT(j.discretization_gap, 0.5);
  EXPECT_TRUE(j.HasWarning("discretization"));
  // The same method on a fine grid: no warning (measured gap 4e-4 at N = 100).
  const SolveRequest fine = RequestFor(*ocp, 100, TerminalMode::kPenalty, "");
  const Judgement k = JudgeResult(*ocp, fine, Solve("indirect-newton", *ocp, fine));
  EXPECT_LT(k.discretization_gap, 1e-2);
  EXPECT_FALSE(k.HasWarning("discretization"));
}

// Every method takes a non-uniform grid (TimeGrid::FromPoints), and so does the judge. On
// double-integrator-bounded, u* = clip(6.4549722 - 12.9099445 t, -5, 5) has kinks at
// t = 0.1127017 and 0.8872983: 20 intervals with nodes there beat 20 uniform ones. Hermite-Simpson,
// whose own error (O(h^4)) is below what a kink inside an interval costs; the trapezoid's O(h^2)
// hides the gain at N = 20 (measured 4.2e-3 at the kinks against 4.5e-3 uniform).
TEST(JudgeResult, JudgesNonUniformGridsWithNodesWhereTheSolutionKinks) {
  const auto ocp = MakeProblem("double-integrator-bounded", {}, 0);
  const double reference = *FindProblem("double-integrator-bounded").reference_value;
  const double t1 = (6.4549722 - 5.0) / 12.9099445, t2 = (6.4549722 + 5.0) / 12.9099445;
  std::vector<double> points;
  auto piece = [&](double a, double b, int n) {
    for (int k = 0; k < n; ++k) points.push_back(a + (b - a) * k / n);
  };
  piece(0.0, t1, 2);
  piece(t1, t2, 16);
  piece(t2, 1.0, 2);
  points.push_back(1.0);
  double error[2];
  for (int at_kinks = 0; at_kinks < 2; ++at_kinks) {
    SolveRequest request = RequestFor(*ocp, 20, TerminalMode::kHard, "hermite-simpson");
    if (at_kinks) request.grid = TimeGrid::FromPoints(points);
    ASSERT_EQ(request.grid.intervals(), 20);
    request.options.Set("tol", 1e-12);
    const SolveResult r = Solve("ipopt", *ocp, request);
    ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
    error[at_kinks] = std::abs(JudgeResult(*ocp, request, r).fine.Jbar - reference) / reference;
  }
  std::printf(
      "double-integrator-bounded, Ipopt + hermite-simpson, N = 20: rel. error of Jbar fine "
      "%.3g (uniform), %.3g (nodes at the kinks)\n",
      error[0],
      error[1]);
  EXPECT_LT(error[1], 0.1 * error[0]);
}

TEST(JudgeResult, NamesTheSolversStoppingToleranceWithTheValueUsed) {
  const auto ocp = MakeProblem("hager", {}, 0);
  SolveRequest request = RequestFor(*ocp, 20, TerminalMode::kPenalty, "trapezoid");
  const Judgement defaults = JudgeResult(*ocp, request, Solve("ipopt", *ocp, request));
  EXPECT_EQ(defaults.accuracy_option, "tol");
  EXPECT_EQ(defaults.accuracy_value, 1e-8);  // Ipopt's default
  EXPECT_NE(defaults.accuracy_note.find("large N"), std::string::npos);
  request.options.Set("tol", "1e-10");
  EXPECT_EQ(JudgeResult(*ocp, request, Solve("ipopt", *ocp, request)).accuracy_value, 1e-10);
}

TEST(JudgeResult, JudgesNothingForAMethodThatDidNotRun) {
  const auto ocp = MakeProblem("double-integrator-free-time", {}, 0);
  const SolveRequest request = RequestFor(*ocp, 10, TerminalMode::kPenalty, "");
  const SolveResult r = Solve("hamiltonian", *ocp, request);  // keeps the horizon fixed
  ASSERT_EQ(r.status, SolveStatus::kNotApplicable);
  const Judgement j = JudgeResult(*ocp, request, r);
  EXPECT_FALSE(j.judged);
  EXPECT_FALSE(j.not_judged.empty());
  EXPECT_FALSE(j.fine.finite);  // nothing was simulated
  EXPECT_TRUE(std::isnan(j.final_time));
}

// What a status cannot say about feasibility: controls outside U (a MinimizeHamiltonian that
// forgets to clamp), or, in the hard form, a terminal miss, are "infeasible" whatever the
// status. double-integrator-bounded: |u| <= 5, x(1) = (0, 0) in the hard form.
TEST(JudgeResult, ReportsControlsThatLeaveTheFeasibleSet) {
  const auto ocp = MakeProblem("double-integrator-bounded", {}, 0);
  const SolveRequest hard = RequestFor(*ocp, 50, TerminalMode::kHard, "hermite-simpson");
  const SolveResult solved = Solve("ipopt", *ocp, hard);
  ASSERT_EQ(solved.status, SolveStatus::kConverged) << solved.message;
  const Judgement honest = JudgeResult(*ocp, hard, solved);
  EXPECT_FALSE(honest.HasWarning("infeasible"))
      << honest.fine.control_violation << " " << honest.fine.terminal_violation;

  SolveResult unclamped = solved;  // the same answer, its controls doubled: |u| up to 10
  unclamped.controls = ControlTrajectory::PiecewiseConstant(
      hard.grid, 2.0 * solved.controls.SampleIntervals(hard.grid));
  const Judgement j = JudgeResult(*ocp, hard, unclamped);
  ASSERT_TRUE(j.HasWarning("infeasible"));
  EXPECT_GT(j.fine.control_violation, 1.0);
  for (const JudgeWarning& w : j.warnings) {
    if (w.code != "infeasible") continue;
    EXPECT_NE(w.message.find("control set U"), std::string::npos) << w.message;
    EXPECT_NE(w.message.find("terminal constraints"), std::string::npos) << w.message;
  }

  // Inside U but off the target: infeasible in the hard form; the penalty form's terminal miss
  // is its answer, not a violation (its own warning is terminal_weights_default where it applies).
  SolveResult idle = solved;
  idle.controls = ControlTrajectory::Constant(hard.grid, Vec::Zero(1));
  EXPECT_TRUE(JudgeResult(*ocp, hard, idle).HasWarning("infeasible"));
  const SolveRequest penalty = RequestFor(*ocp, 50, TerminalMode::kPenalty, "hermite-simpson");
  EXPECT_FALSE(JudgeResult(*ocp, penalty, idle).HasWarning("infeasible"));

  // The tolerance is the rule: a looser one accepts the terminal miss of the idle controls.
  JudgeOptions loose;
  loose.feasibility_tolerance = 1e3;
  EXPECT_FALSE(JudgeResult(*ocp, hard, idle, loose).HasWarning("infeasible"));
}

// A NominalControl of the wrong size: every method refuses it naming the problem (it used to
// crash, or pass silently with two components).
TEST(DefaultStart, ANominalControlOfTheWrongSizeIsRefusedByEveryMethod) {
  for (const int size : {0, 2}) {
    const SlipOcp ocp(size);
    for (const auto& [solver, transcription] :
         std::vector<std::pair<std::string, std::string>>{{"ipopt", "trapezoid"},
                                                          {"ipopt", "single-shooting"},
                                                          {"hamiltonian", ""},
                                                          {"indirect-newton", ""}}) {
      SolveRequest request;
      request.grid = TimeGrid::Uniform(0.0, 1.0, 10);
      request.transcription = transcription;
      const std::string method = solver + " " + transcription;
      try {
        FindSolver(solver).make()->Solve(ocp, request);
        ADD_FAILURE() << method << " accepted " << size << " components";
      } catch (const std::invalid_argument& e) {
        EXPECT_NE(std::string(e.what()).find("NominalControl() must return nu = 1"),
                  std::string::npos)
            << method << ": " << e.what();
      }
    }
  }
}

// A method that solved the problem's Hamiltonian reformulation (bryson-denham's state
// constraint as a penalty) says so, whatever its status; Ipopt on the problem itself does not.
TEST(JudgeResult, SaysWhenTheMethodSolvedAReformulation) {
  const auto ocp = MakeProblem("bryson-denham", {}, 0);
  const SolveRequest request = RequestFor(*ocp, 50, TerminalMode::kHard, "");
  const SolveResult polish = Solve("hamiltonian-polish", *ocp, request);
  ASSERT_NE(polish.status, SolveStatus::kNotApplicable) << polish.message;
  ASSERT_EQ(polish.solver_stats.at("reformulated"), 1.0);
  EXPECT_TRUE(JudgeResult(*ocp, request, polish).HasWarning("reformulated"));
  const SolveRequest nlp = RequestFor(*ocp, 50, TerminalMode::kHard, "euler");
  const SolveResult ipopt = Solve("ipopt", *ocp, nlp);
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged) << ipopt.message;
  EXPECT_FALSE(JudgeResult(*ocp, nlp, ipopt).HasWarning("reformulated"));
  // A failed solve is judged by nothing: no warning about what it solved.
  SolveResult failed = polish;
  failed.status = SolveStatus::kNumericalFailure;
  EXPECT_FALSE(JudgeResult(*ocp, request, failed).HasWarning("reformulated"));
}

TEST(JudgeResult, RefusesOptionsOutOfRange) {
  const auto ocp = MakeProblem("hager", {}, 0);
  const SolveRequest request = RequestFor(*ocp, 10, TerminalMode::kPenalty, "");
  const SolveResult r = Solve("hamiltonian", *ocp, request);
  JudgeOptions bad;
  bad.refine = 0;
  EXPECT_THROW(JudgeResult(*ocp, request, r, bad), std::invalid_argument);
  bad = JudgeOptions();
  bad.discretization_tolerance = 0.0;
  EXPECT_THROW(JudgeResult(*ocp, request, r, bad), std::invalid_argument);
  bad = JudgeOptions();
  bad.feasibility_tolerance = -1.0;
  EXPECT_THROW(JudgeResult(*ocp, request, r, bad), std::invalid_argument);
}

// Issue 38's glider: Ipopt solves the trapezoid NLP (N = 200), but forward Euler on the same
// grid, the record's J, diverges (measured: not finite) while RK4 on the 10x finer grid does not.
// The judge says which evaluation failed; the solver's status is not the judge's to change.
TEST(JudgeResult, SaysWhichReSimulationIsNotFinite) {
  const auto ocp = MakeProblem("glider", {}, 0);
  const SolveRequest request = RequestFor(*ocp, 200, TerminalMode::kHard, "trapezoid");
  const SolveResult r = Solve("ipopt", *ocp, request);
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
  const Judgement j = JudgeResult(*ocp, request, r);
  ASSERT_FALSE(j.own_grid.finite) << "the premise: Euler on the method's grid diverges";
  ASSERT_TRUE(j.fine.finite);
  ASSERT_TRUE(j.HasWarning("not_finite"));
  for (const JudgeWarning& w : j.warnings) {
    if (w.code != "not_finite") continue;
    EXPECT_NE(w.message.find("euler on the method's grid (200 intervals)"), std::string::npos)
        << w.message;
    EXPECT_NE(w.message.find("the fine RK4 re-simulation is finite"), std::string::npos)
        << w.message;
  }
  // RK4 on the same grid does not diverge: nothing to report.
  JudgeOptions rk4;
  rk4.integrator = Integrator::kRk4;
  EXPECT_FALSE(JudgeResult(*ocp, request, r, rk4).HasWarning("not_finite"));
}

}  // namespace
}  // namespace ocpb
