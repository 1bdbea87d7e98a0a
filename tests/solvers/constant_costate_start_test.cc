// The constant-costate start of the Euler polish (ConstantCostateStart): the solved costate of
// comm-path2d's bits meets the bit budget on a given path, it is the optimum's own costate at the
// optimum, and the start is skipped (and recorded so) where no integrator state qualifies.
#include <cmath>

#include <gtest/gtest.h>

#include "problems/registry.h"
#include "solvers/constant_costate_start.h"
#include "solvers/euler_costate_fit.h"
#include "solvers/hamiltonian_family.h"

namespace ocpb {
namespace {

constexpr int kBits = 4;  // comm-path2d's x5: bits sent, x5' = R

SolveRequest StartRequest(const Ocp& ocp, int N, const OptionMap& options) {
  SolveRequest r;
  r.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  r.terminal = TerminalMode::kHard;
  r.options = options;
  return r;
}

double StartStat(const SolveResult& r, const std::string& key) {
  const auto it = r.solver_stats.find(key);
  return it == r.solver_stats.end() ? NAN : it->second;
}

// The descent's iterate alone (no Newton step): its path is far from the optimum's, and its
// fitted costate of the bits far from the one that sends the budget along that path.
SolveResult DescentOnly(const Ocp& ocp, int N) {
  const SolveRequest request = StartRequest(
      ocp, N, {{"newton_max_iterations", "0"}, {"polish_attempts", "1"}, {"max_iterations", "60"}});
  return HamiltonianFamily(HamiltonianFamily::Preset::kPolish).Solve(ocp, request);
}

// With the descent's path held, the solved constant costate sends exactly the budget: the
// terminal row of the bits vanishes, the bits' row of X is its Euler trajectory under the new
// rates, and the other rows are untouched.
TEST(ConstantCostateStart, SolvedCostateMeetsTheBitBudgetOnAFixedPath) {
  const auto ocp = MakeProblem("comm-path2d", {"channel=0", "gamma=1e-4"}, 1);
  const int N = 100;
  const SolveResult descent = DescentOnly(*ocp, N);
  const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
  const Mat U = descent.controls.SampleIntervals(grid);
  Mat X = descent.states;
  Mat P = FitEulerCostates(*ocp, grid, TerminalMode::kHard, U, X);
  const Mat X0 = X, P0 = P;

  Vec psi(ocp->num_terminal());
  ocp->TerminalConstraints(X.col(N), psi);
  ASSERT_GT(std::abs(psi[kBits]), 1e-3);  // the fit alone misses the budget

  const ConstantCostateStartOutcome out =
      ConstantCostateStart(*ocp, grid, TerminalMode::kHard, U, &X, &P);
  EXPECT_EQ(out.candidates, 1);
  EXPECT_EQ(out.solved, 1);
  EXPECT_GT(out.evaluations, 1);

  ocp->TerminalConstraints(X.col(N), psi);
  EXPECT_LE(std::abs(psi[kBits]), 1e-10);
  const double c = P(kBits, N);
  EXPECT_LT(c, 0.0);  // bits are worth sending
  EXPECT_NE(c, P0(kBits, N));
  Vec u(ocp->nu()), f(ocp->nx());
  for (int k = 0; k < N; ++k) {
    EXPECT_EQ(P(kBits, k), c);
    ocp->MinimizeHamiltonian(grid.t(k), X.col(k), P.col(k + 1), u);
    ocp->Dynamics(grid.t(k), X.col(k), u, f);
    EXPECT_NEAR(X(kBits, k + 1), X(kBits, k) + grid.h(k) * f[kBits], 1e-12 * (1 + X(kBits, k)));
  }
  EXPECT_EQ(X(kBits, 0), X0(kBits, 0));
  for (int i = 0; i < ocp->nx(); ++i) {
    if (i == kBits) continue;
    EXPECT_EQ(X.row(i), X0.row(i)) << i;
    EXPECT_EQ(P.row(i), P0.row(i)) << i;
  }
}

// At the Euler optimum (the polish converged) the costate of the bits is already the constant
// that sends the budget along the optimal path: the start returns it (the equation is exact).
TEST(ConstantCostateStart, OptimumIsAFixedPoint) {
  const auto ocp = MakeProblem("comm-path2d", {"channel=0", "gamma=1e-3"}, 1);
  const int N = 100;
  const SolveResult opt =
      HamiltonianFamily(HamiltonianFamily::Preset::kPolish).Solve(*ocp, StartRequest(*ocp, N, {}));
  ASSERT_EQ(opt.status, SolveStatus::kConverged);
  const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
  const Mat U = opt.controls.SampleIntervals(grid);
  Mat X = opt.states, P = opt.costates;
  const double c_opt = P(kBits, N);
  const ConstantCostateStartOutcome out =
      ConstantCostateStart(*ocp, grid, TerminalMode::kHard, U, &X, &P);
  EXPECT_EQ(out.solved, 1);
  EXPECT_NEAR(P(kBits, N), c_opt, 1e-8 * std::abs(c_opt));
  EXPECT_NEAR(X(kBits, N), opt.states(kBits, N), 1e-9 * opt.states(kBits, N));
}

// vanderpol has no integrator state (every column of f_x or L_x is nonzero somewhere); the
// double integrator's position is one (p1 constant), but its rate does not depend on the control,
// so its equation has no bracket. Both skip the start and say so; the solve is unchanged.
TEST(ConstantCostateStart, SkippedAndRecordedWithoutAnIntegratorStateOrBracket) {
  for (const char* name : {"vanderpol", "double-integrator"}) {
    SCOPED_TRACE(name);
    const auto ocp = MakeProblem(name, {}, 0);
    const HamiltonianFamily polish(HamiltonianFamily::Preset::kPolish);
    const SolveResult on =
        polish.Solve(*ocp, StartRequest(*ocp, 50, {{"polish_constant_costate_start", "true"}}));
    const SolveResult off =
        polish.Solve(*ocp, StartRequest(*ocp, 50, {{"polish_constant_costate_start", "false"}}));
    EXPECT_EQ(StartStat(on, "start_constant_costates"), 0.0);
    EXPECT_TRUE(std::isnan(StartStat(off, "start_constant_costates")));
    EXPECT_EQ(on.status, off.status);
    EXPECT_EQ(on.objective, off.objective);
    EXPECT_EQ(StartStat(on, "newton_iterations"), StartStat(off, "newton_iterations"));

    // From the descent's iterate (psi != 0 there): nothing is set.
    const SolveResult descent = DescentOnly(*ocp, 50);
    const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 50);
    const Mat U = descent.controls.SampleIntervals(grid);
    Mat X = descent.states;
    Mat P = FitEulerCostates(*ocp, grid, TerminalMode::kHard, U, X);
    const Mat P0 = P;
    const ConstantCostateStartOutcome out =
        ConstantCostateStart(*ocp, grid, TerminalMode::kHard, U, &X, &P);
    EXPECT_EQ(out.candidates, std::string(name) == "vanderpol" ? 0 : 1);
    EXPECT_EQ(out.solved, 0);
    EXPECT_EQ(X, descent.states);
    EXPECT_EQ(P, P0);
  }
}

}  // namespace
}  // namespace ocpb
