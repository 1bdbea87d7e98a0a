// Van der Pol (J* = 1.0478069082): every method against the reference, and the costate at t = 0
// against the shooting solution's p(0).
#include "problems/reference/vanderpol.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "problems/registry.h"
#include "tests/problems/reference_test_support.h"

namespace ocpb {
namespace {

using reference_testing::FineEvaluation;
using reference_testing::RelativeError;
using reference_testing::Request;
using reference_testing::SolveWith;
using reference_testing::SolveWithHamiltonian;
using reference_testing::SolveWithIpopt;

constexpr double kVanDerPolJ = VanDerPol::kReferenceCost;

// The project notes give p(0) = (1.717177, 0.011261) from shooting (6 decimals).
TEST(VanDerPol, IpoptCostateAtTheStartMatchesTheShootingSolution) {
  const auto ocp = MakeProblem("vanderpol", {}, 0);
  const SolveResult r = SolveWithIpopt(*ocp, "lgr", 25);
  ASSERT_EQ(r.status, SolveStatus::kConverged);
  ASSERT_EQ(r.state_grid.t(0), 0.0);
  EXPECT_NEAR(r.costates(0, 0), 1.717177, 2e-6);
  EXPECT_NEAR(r.costates(1, 0), 0.011261, 2e-6);
}

// Forward Euler: the Hamiltonian method reaches the optimum Ipopt finds for the same discrete
// problem (the Euler transcription; the problem is nonconvex, both start from u = 0), and its
// controls cost within 1.3e-4 of J* (measured 8.6e-5 at N = 100).
TEST(VanDerPol, HamiltonianReachesTheEulerOptimumAndTheReference) {
  const auto ocp = MakeProblem("vanderpol", {}, 0);
  const int N = 100;
  const SolveResult h =
      SolveWithHamiltonian(*ocp, N, {{"max_iterations", "500"}, {"theta_tolerance", "1e-12"}});
  ASSERT_EQ(h.status, SolveStatus::kConverged) << h.solver_status << " " << h.message;
  const SolveResult ipopt = SolveWithIpopt(*ocp, "euler", N, TerminalMode::kPenalty);
  EXPECT_NEAR(h.objective, ipopt.objective, 1e-9);
  EXPECT_LT(RelativeError(FineEvaluation(*ocp, h, N).Jbar, kVanDerPolJ), 1.3e-4);
}

}  // namespace
}  // namespace ocpb
