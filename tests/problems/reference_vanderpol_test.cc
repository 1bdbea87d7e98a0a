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

constexpr double kVdpJ = VanDerPol::kReferenceCost;

struct VdpIpoptCase {
  const char* transcription;
  int N;
  double tolerance;  // on |Jbar_fine - J*| / J*: measured accuracy rounded up
};

class VanDerPolIpopt : public ::testing::TestWithParam<VdpIpoptCase> {};

TEST_P(VanDerPolIpopt, ReachesTheReference) {
  const VdpIpoptCase c = GetParam();
  const auto ocp = MakeProblem("vanderpol", {}, 0);
  const SolveResult r = SolveWithIpopt(*ocp, c.transcription, c.N);
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.solver_status << " " << r.message;
  const double jbar = FineEvaluation(*ocp, r, c.N).Jbar;
  EXPECT_LT(RelativeError(jbar, kVdpJ), c.tolerance) << "Jbar_fine = " << jbar;
}

// Measured: Euler 8.6e-5 (N = 100), trapezoid 9.7e-6 (N = 50), Hermite-Simpson 1.2e-7 (N = 25),
// LGR 8.1e-11 (N = 25; the reference has 11 digits, so this also checks them).
INSTANTIATE_TEST_SUITE_P(Transcriptions,
                         VanDerPolIpopt,
                         ::testing::Values(VdpIpoptCase{"euler", 100, 1.3e-4},
                                           VdpIpoptCase{"trapezoid", 50, 1.5e-5},
                                           VdpIpoptCase{"hermite-simpson", 25, 2e-7},
                                           VdpIpoptCase{"lgr", 25, 2e-10}),
                         [](const auto& info) {
                           std::string n = info.param.transcription;
                           for (char& ch : n) ch = ch == '-' ? '_' : ch;
                           return n + "_N" + std::to_string(info.param.N);
                         });

// The project notes give p(0) = (1.717177, 0.011261) from shooting (6 decimals).
TEST(VanDerPol, IpoptCostateAtTheStartMatchesTheShootingSolution) {
  const auto ocp = MakeProblem("vanderpol", {}, 0);
  const SolveResult r = SolveWithIpopt(*ocp, "lgr", 25);
  ASSERT_EQ(r.status, SolveStatus::kConverged);
  ASSERT_EQ(r.state_grid.t(0), 0.0);
  EXPECT_NEAR(r.costates(0, 0), 1.717177, 2e-6);
  EXPECT_NEAR(r.costates(1, 0), 0.011261, 2e-6);
}

TEST(VanDerPol, NloptSlsqpReachesTheSameOptimumAsIpopt) {
  const auto ocp = MakeProblem("vanderpol", {}, 0);
  SolveRequest req = Request(*ocp, 20, TerminalMode::kHard, "hermite-simpson");
  req.algorithm = "LD_SLSQP";
  const SolveResult nlopt = SolveWith("nlopt", *ocp, req);
  ASSERT_EQ(nlopt.status, SolveStatus::kConverged) << nlopt.solver_status << " " << nlopt.message;
  const SolveResult ipopt = SolveWithIpopt(*ocp, "hermite-simpson", 20);
  EXPECT_NEAR(nlopt.objective, ipopt.objective, 1e-7);
  EXPECT_LT(RelativeError(FineEvaluation(*ocp, nlopt, 20).Jbar, kVdpJ), 6e-7);  // measured 3.0e-7
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
  EXPECT_LT(RelativeError(FineEvaluation(*ocp, h, N).Jbar, kVdpJ), 1.3e-4);
}

}  // namespace
}  // namespace ocpb
