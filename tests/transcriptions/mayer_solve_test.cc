// A Mayer problem written without a running cost (tests/core/max_range_ocp.h), solved by Ipopt on
// every transcription through the solver registry, as a user of the installed library would.
#include <algorithm>
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "solvers/judge.h"
#include "solvers/registry.h"
#include "tests/core/max_range_ocp.h"

namespace ocpb {
namespace {

using testing::MaxRangeOcp;

// J* = -0.8, theta* = asin(0.6), p* = (-1, -0.75): every scheme integrates the constant optimal
// heading exactly, so each discrete optimum is the continuous one, to Ipopt's tolerance.
TEST(MayerProblem, SolvesWithIpoptOnEveryTranscriptionToItsKnownOptimum) {
  const MaxRangeOcp ocp(0.6);
  ASSERT_FALSE(MaxRangeOcp::DefinesRunningCost());
  int with_costates = 0;
  for (const std::string transcription :
       {"euler", "trapezoid", "hermite-simpson", "lgr", "single-shooting"}) {
    SolveRequest request;
    request.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), 10);
    request.terminal = TerminalMode::kHard;
    request.transcription = transcription;
    request.options = {{"tol", "1e-11"}};
    const SolveResult r = FindSolver("ipopt").make()->Solve(ocp, request);
    ASSERT_EQ(r.status, SolveStatus::kConverged)
        << transcription << ": " << r.solver_status << " " << r.message;
    EXPECT_NEAR(r.objective, -0.8, 1e-9) << transcription;
    EXPECT_NEAR(ocp.OptimalCost(), -0.8, 1e-15);
    double heading_error = 0.0;
    for (int k = 0; k <= 40; ++k) {
      heading_error =
          std::max(heading_error, std::abs(r.controls(k / 40.0)[0] - ocp.OptimalHeading()));
    }
    EXPECT_LT(heading_error, 1e-7) << transcription;
    if (r.costates.cols() > 0) {  // the multipliers' costates: p = (-1, -0.75) throughout
      ++with_costates;
      EXPECT_LT((r.costates.row(0).array() + 1.0).abs().maxCoeff(), 1e-6) << transcription;
      EXPECT_LT((r.costates.row(1).array() - ocp.OptimalCostateY()).abs().maxCoeff(), 1e-6)
          << transcription;
    }
    // Judged on the fine re-simulation, as every result is.
    const Judgement judged = JudgeResult(ocp, request, r);
    ASSERT_TRUE(judged.judged) << transcription << ": " << judged.not_judged;
    EXPECT_EQ(judged.fine.running_cost, 0.0) << transcription;
    EXPECT_NEAR(judged.fine.Jbar, -0.8, 1e-9) << transcription;
    EXPECT_LT(judged.fine.terminal_violation, 1e-9) << transcription;
  }
  EXPECT_GE(with_costates, 4);  // at least the four collocation schemes
}

}  // namespace
}  // namespace ocpb
