// LQR (J* = 0.6739990459): the reference from the Riccati equation, every method against it, and
// costates against p = P(t) x(t).
#include "problems/reference/lqr.h"

#include <cmath>
#include <string>
#include <vector>

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

constexpr double kLqrJ = Lqr::kReferenceCost;

/// The Riccati solution and the optimal closed loop on [0, 5], by RK4 with step 5/kSteps:
///   -P' = A^T P + P A - P B B^T P + I, P(5) = 0;   x' = (A - B B^T P) x, x(0) = x0.
/// The closed loop uses RK4 with step 2 * 5/kSteps so that its stages fall on stored P values.
class RiccatiSolution {
 public:
  static constexpr int kSteps = 20000;
  RiccatiSolution() : P_(kSteps + 1), x_(kSteps / 2 + 1) {
    const Eigen::Matrix2d A = Lqr::A();
    const Eigen::Vector2d B = Lqr::B();
    auto rhs = [&](const Eigen::Matrix2d& P) -> Eigen::Matrix2d {  // dP/dt
      return -(A.transpose() * P + P * A - P * B * B.transpose() * P + Eigen::Matrix2d::Identity());
    };
    const double h = 5.0 / kSteps;
    P_[kSteps].setZero();
    for (int k = kSteps; k > 0; --k) {  // backward in time: step -h
      const Eigen::Matrix2d& P = P_[k];
      const Eigen::Matrix2d k1 = rhs(P);
      const Eigen::Matrix2d k2 = rhs(P - 0.5 * h * k1);
      const Eigen::Matrix2d k3 = rhs(P - 0.5 * h * k2);
      const Eigen::Matrix2d k4 = rhs(P - h * k3);
      P_[k - 1] = P - h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    auto closed = [&](int k, const Eigen::Vector2d& x) -> Eigen::Vector2d {
      return (A - B * B.transpose() * P_[k]) * x;
    };
    x_[0] = Eigen::Vector2d(0.0, 1.0);
    for (int m = 0; m < kSteps / 2; ++m) {
      const int k = 2 * m;
      const Eigen::Vector2d& x = x_[m];
      const Eigen::Vector2d k1 = closed(k, x);
      const Eigen::Vector2d k2 = closed(k + 1, x + h * k1);
      const Eigen::Vector2d k3 = closed(k + 1, x + h * k2);
      const Eigen::Vector2d k4 = closed(k + 2, x + 2.0 * h * k3);
      x_[m + 1] = x + 2.0 * h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
  }
  /// P(t), x*(t) and p*(t) = P(t) x*(t) at t = 5 m / (kSteps / 2).
  const Eigen::Matrix2d& P(double t) const { return P_[2 * Index(t)]; }
  const Eigen::Vector2d& x(double t) const { return x_[Index(t)]; }
  Eigen::Vector2d p(double t) const { return P(t) * x(t); }
  double u(double t) const { return -Lqr::B().dot(p(t)); }

 private:
  static int Index(double t) {
    const double m = t / 5.0 * (kSteps / 2);
    const int i = static_cast<int>(std::lround(m));
    EXPECT_NEAR(m, i, 1e-6) << "t = " << t << " is not a point of the Riccati grid";
    return i;
  }
  std::vector<Eigen::Matrix2d> P_;
  std::vector<Eigen::Vector2d> x_;
};

const RiccatiSolution& Riccati() {
  static const RiccatiSolution solution;
  return solution;
}

TEST(Lqr, RiccatiReproducesTheReferenceValue) {
  const Eigen::Vector2d x0(0.0, 1.0);
  EXPECT_NEAR(0.5 * x0.dot(Riccati().P(0.0) * x0), kLqrJ, 1e-10);
  // The closed loop's control, simulated open loop, costs the same.
  const auto ocp = MakeProblem("lqr", {}, 0);
  const TimeGrid grid = TimeGrid::Uniform(0.0, 5.0, 2000);
  Mat U(1, grid.size());
  for (int k = 0; k < grid.size(); ++k) U(0, k) = Riccati().u(grid.t(k));
  const Evaluation ev =
      Evaluate(*ocp, ControlTrajectory::PiecewiseLinear(grid, U), grid, Integrator::kRk4);
  EXPECT_LT(RelativeError(ev.Jbar, kLqrJ), 1e-7);  // linear interpolation of u*: O(h^2)
}

// The largest |p - P x*| over a result's state grid, relative to max |p*| (about 1.2 here).
double CostateError(const SolveResult& r) {
  double err = 0.0, scale = 0.0;
  for (int j = 0; j < r.state_grid.size(); ++j) {
    const double t = r.state_grid.t(j);
    // The Riccati grid has spacing 5e-4: use the nearest point (the costate is smooth).
    const double snapped = std::round(t / 5e-4) * 5e-4;
    const Eigen::Vector2d p = Riccati().p(snapped);
    err = std::max(err, (r.costates.col(j) - p).cwiseAbs().maxCoeff());
    scale = std::max(scale, p.cwiseAbs().maxCoeff());
  }
  return err / scale;
}

// Multiplier-based costates: Hermite-Simpson fourth order (measured 6.8e-7 at N = 50), trapezoid
// second order (1.5e-3 at N = 100), relative to max |p*|.
TEST(Lqr, IpoptCostatesMatchRiccati) {
  const auto ocp = MakeProblem("lqr", {}, 0);
  for (const auto& [transcription, N, tolerance] :
       {std::tuple{"hermite-simpson", 50, 1.5e-6}, std::tuple{"trapezoid", 100, 2.5e-3}}) {
    const SolveResult r = SolveWithIpopt(*ocp, transcription, N);
    ASSERT_EQ(r.status, SolveStatus::kConverged);
    ASSERT_EQ(r.costates.cols(), r.state_grid.size()) << transcription;
    EXPECT_LT(CostateError(r), tolerance) << transcription;
  }
}

// The Hamiltonian method on forward Euler solves the same discrete problem as Ipopt on the Euler
// transcription (penalty form; there is no terminal constraint): same optimum. Its continuous
// cost error is that of the Euler grid, O(h^2) in J (5.5e-3 at N = 100, 1.4e-3 at N = 200).
// Its costates are the exact discrete adjoint, first order: relative to max |p*| they err by
// 7.4e-2 at N = 100 (h = 0.05) and 3.6e-2 at N = 200.
TEST(Lqr, HamiltonianReachesTheEulerOptimumAndTheReference) {
  const auto ocp = MakeProblem("lqr", {}, 0);
  double previous = 0.0, previous_costate = 0.0;
  for (const auto& [N, tolerance, costate_tolerance] :
       {std::tuple{100, 8e-3, 0.1}, std::tuple{200, 2e-3, 0.05}}) {
    const SolveResult h =
        SolveWithHamiltonian(*ocp, N, {{"max_iterations", "500"}, {"theta_tolerance", "1e-12"}});
    ASSERT_EQ(h.status, SolveStatus::kConverged) << h.solver_status << " " << h.message;
    const SolveResult ipopt = SolveWithIpopt(*ocp, "euler", N, TerminalMode::kPenalty);
    EXPECT_NEAR(h.objective, ipopt.objective, 1e-8 * ipopt.objective) << "N = " << N;
    const double err = RelativeError(FineEvaluation(*ocp, h, N).Jbar, kLqrJ);
    EXPECT_LT(err, tolerance) << "N = " << N;
    if (previous > 0.0) {
      EXPECT_GT(previous / err, 3.0) << "second order in J";
    }
    previous = err;
    const double costate_err = CostateError(h);
    EXPECT_LT(costate_err, costate_tolerance) << "N = " << N;
    if (previous_costate > 0.0) {
      EXPECT_NEAR(previous_costate / costate_err, 2.0, 0.3) << "first order in p";
    }
    previous_costate = costate_err;
  }
}

}  // namespace
}  // namespace ocpb
