// Grid sequencing's pieces: the levels, the coarser grid, the interpolation, and Newton on
// finer grids from a coarse solution.
#include "solvers/grid_sequence.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "problems/registry.h"

namespace ocpb {
namespace {

TEST(GridSequenceLevels, HalvesWhileEvenAndAboveTheFloor) {
  const auto grid = [](int n) { return TimeGrid::Uniform(0.0, 1.0, n); };
  EXPECT_EQ(GridSequenceLevels(grid(400), 2, 100), 2);  // 200, 100
  EXPECT_EQ(GridSequenceLevels(grid(400), 5, 100), 2);  // 50 would be below the floor
  EXPECT_EQ(GridSequenceLevels(grid(400), 1, 100), 1);
  EXPECT_EQ(GridSequenceLevels(grid(400), 0, 100), 0);
  EXPECT_EQ(GridSequenceLevels(grid(400), 5, 1), 4);    // 200, 100, 50, 25: then odd
  EXPECT_EQ(GridSequenceLevels(grid(300), 2, 100), 1);  // 150, then odd
  EXPECT_EQ(GridSequenceLevels(grid(402), 2, 100), 1);  // 201, then odd
  EXPECT_EQ(GridSequenceLevels(grid(199), 2, 50), 0);   // odd
  EXPECT_EQ(GridSequenceLevels(grid(100), 2, 100), 0);
  EXPECT_EQ(GridSequenceLevels(grid(2), 3, 0), 1);  // a floor below 1 counts as 1
}

TEST(InterpolateNodes, IsExactForLinesAndKeepsTheEnds) {
  const TimeGrid from = TimeGrid::FromPoints({0.0, 0.5, 2.0});
  Mat values(2, 3);
  values << 1.0, 2.0, 5.0,  // 1 + 2t
      -1.0, -1.0, -1.0;
  const TimeGrid to = TimeGrid::FromPoints({-1.0, 0.0, 0.25, 0.5, 1.25, 2.0, 3.0});
  const Mat out = InterpolateNodes(from, values, to);
  ASSERT_EQ(out.rows(), 2);
  ASSERT_EQ(out.cols(), to.size());
  const std::vector<double> expected = {1.0, 1.0, 1.5, 2.0, 3.5, 5.0, 5.0};  // ends held
  for (int j = 0; j < to.size(); ++j) {
    EXPECT_DOUBLE_EQ(out(0, j), expected[j]) << j;
    EXPECT_DOUBLE_EQ(out(1, j), -1.0) << j;
  }
  EXPECT_THROW(InterpolateNodes(from, Mat(2, 2), to), std::invalid_argument);
}

// From the converged solution on 50 intervals, Newton on 100 and then 200 intervals lands on
// each grid's own solution (the one Newton finds from that grid's own start, to its tolerance)
// in a few steps; the rows carry their grid (the last grid's: -1) and are numbered on.
TEST(NewtonOnFinerGrids, ReachesEachGridsOwnSolutionFromTheCoarserOne) {
  const auto ocp = MakeProblem("vanderpol", {}, 0);
  IndirectNewtonOptions o;
  o.scheme = IndirectNewtonOptions::Scheme::kEuler;
  o.linear_solver = IndirectNewtonOptions::LinearSolver::kRiccati;
  const auto solve = [&](int n) {
    SolveRequest r;
    r.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), n);
    r.terminal = TerminalMode::kHard;
    IndirectNewtonOptions cold = o;
    cold.max_iterations = 100;
    return IndirectNewton(cold).Solve(*ocp, r);
  };
  const SolveResult coarse = solve(50);
  ASSERT_EQ(coarse.status, SolveStatus::kConverged) << coarse.message;
  std::vector<IterationRecord> history(3);  // rows already there
  const Stopwatch clock;
  const std::vector<TimeGrid> finer = {TimeGrid::Uniform(ocp->t0(), ocp->tf(), 100),
                                       TimeGrid::Uniform(ocp->t0(), ocp->tf(), 200)};
  const GridSequenceOutcome out =
      NewtonOnFinerGrids(*ocp, o, TerminalMode::kHard, coarse, finer, clock, &history);
  ASSERT_TRUE(out.converged) << out.message;
  EXPECT_EQ(out.failed_intervals, -1);
  EXPECT_EQ(out.last.state_grid.intervals(), 200);
  const SolveResult own = solve(200);
  ASSERT_EQ(own.status, SolveStatus::kConverged) << own.message;
  EXPECT_NEAR(out.last.objective, own.objective, 1e-9 * std::abs(own.objective));
  EXPECT_LT((out.last.states - own.states).cwiseAbs().maxCoeff(), 1e-8);
  // Interpolated starts: a few steps per grid, fewer than the cold start's.
  EXPECT_LT(out.newton_iterations, own.iterations) << out.message;
  // Rows: the three given, then 100-interval rows, then the request grid's (-1).
  ASSERT_EQ(static_cast<int>(history.size()), 3 + out.newton_iterations + 2);
  int grid_changes = 0;
  for (size_t i = 3; i < history.size(); ++i) {
    EXPECT_EQ(history[i].iteration, static_cast<int>(i));
    EXPECT_TRUE(history[i].intervals == 100 || history[i].intervals == -1) << i;
    if (history[i].intervals != history[i - 1].intervals) ++grid_changes;
  }
  EXPECT_EQ(history[3].intervals, 100);
  EXPECT_EQ(history.back().intervals, -1);
  EXPECT_EQ(grid_changes, 2);  // from the given rows' -1 to 100, from 100 to -1
  EXPECT_NE(out.message.find("Newton on 100 intervals"), std::string::npos) << out.message;
  EXPECT_NE(out.message.find("Newton on 200 intervals"), std::string::npos) << out.message;
  EXPECT_THROW(NewtonOnFinerGrids(*ocp, o, TerminalMode::kHard, coarse, {}, clock, &history),
               std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
