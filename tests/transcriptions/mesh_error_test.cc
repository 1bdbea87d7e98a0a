// The mesh error estimate (transcriptions/mesh_error.h): the interpolants' derivatives against
// finite differences, the estimate against closed-form integrals, and its order of decrease
// under uniform halving at Ipopt's solutions of a smooth problem (Hager's).
#include "transcriptions/mesh_error.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/autodiff_ocp.h"
#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

/// x' = t^power (u unused but for the cost), x(0) = 0 on [0, 1]: the interpolants are exact for
/// low powers, and their defects are closed-form polynomials for the next one.
class PowerOfTimeOcp final : public AutoDiffOcp<PowerOfTimeOcp, 1, 1> {
 public:
  explicit PowerOfTimeOcp(int power) : power_(power) {
    SetHorizon(0.0, 1.0);
    SetInitialState(Vec::Zero(1));
  }
  std::string name() const override { return "power-of-time"; }
  template <class T>
  void EvalDynamics(double t, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = 0.0 * u[0] + std::pow(t, power_);
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
  // The exact state t^(power + 1) / (power + 1) at the nodes of `grid`.
  Mat ExactStates(const TimeGrid& grid) const {
    Mat X(1, grid.size());
    for (int k = 0; k < grid.size(); ++k) X(0, k) = std::pow(grid.t(k), power_ + 1) / (power_ + 1);
    return X;
  }

 private:
  int power_;
};

const TimeGrid kUneven = TimeGrid::FromPoints({0.0, 0.1, 0.35, 0.5, 0.8, 1.0});

TEST(MeshError, InterpolantDerivativeMatchesFiniteDifferences) {
  Mat X(2, kUneven.size()), F(2, kUneven.size());
  for (int k = 0; k < kUneven.size(); ++k) {
    X.col(k) << std::sin(3.0 * k), std::cos(2.0 * k + 1.0);
    F.col(k) << 1.5 * std::cos(k + 0.3), -0.7 * k;
  }
  const double delta = 1e-6;
  for (const auto scheme :
       {CollocationInterpolant::kTrapezoid, CollocationInterpolant::kHermiteSimpson}) {
    for (int k = 0; k < kUneven.intervals(); ++k) {
      for (const double s : {0.1, 0.37, 0.5, 0.9}) {
        Vec x(2), xdot(2), xp(2), xm(2), unused(2);
        InterpolateState(scheme, kUneven, X, F, k, s, x, xdot);
        InterpolateState(scheme, kUneven, X, F, k, s + delta, xp, unused);
        InterpolateState(scheme, kUneven, X, F, k, s - delta, xm, unused);
        const Vec fd = (xp - xm) / (2.0 * delta * kUneven.h(k));
        EXPECT_LT((fd - xdot).cwiseAbs().maxCoeff(), 1e-6 * (1.0 + xdot.cwiseAbs().maxCoeff()))
            << "scheme " << static_cast<int>(scheme) << " k " << k << " s " << s;
      }
      // Both interpolants start at x_k with slope f_k and end with slope f_k+1.
      Vec x(2), xdot(2);
      InterpolateState(scheme, kUneven, X, F, k, 0.0, x, xdot);
      EXPECT_LT((x - X.col(k)).norm(), 1e-14);
      EXPECT_LT((xdot - F.col(k)).norm(), 1e-13);
      InterpolateState(scheme, kUneven, X, F, k, 1.0, x, xdot);
      EXPECT_LT((xdot - F.col(k + 1)).norm(), 1e-12);
      if (scheme == CollocationInterpolant::kHermiteSimpson) {
        EXPECT_LT((x - X.col(k + 1)).norm(), 1e-14);
      }
    }
  }
}

// Exact interpolants give no error; the next power gives the closed-form integral of
// |interpolation error| (trapezoid: (t - a)(b - t) for t^2, integral h^3 / 6; Hermite-Simpson:
// |(t - a)(t - m)(t - b)| for t^3, integral h^4 / 32), divided by 1 + max |x_k|.
TEST(MeshError, EstimateIsTheScaledIntegralOfTheDefect) {
  struct Case {
    CollocationInterpolant scheme;
    int exact_power, next_power;
    double exponent, denominator;
  };
  for (const Case& c : {Case{CollocationInterpolant::kTrapezoid, 1, 2, 3.0, 6.0},
                        Case{CollocationInterpolant::kHermiteSimpson, 2, 3, 4.0, 32.0}}) {
    const PowerOfTimeOcp exact(c.exact_power);
    const ControlTrajectory u = ControlTrajectory::Constant(kUneven, Vec::Zero(1));
    const Vec zero = IntervalDefectErrors(exact, c.scheme, kUneven, exact.ExactStates(kUneven), u);
    ASSERT_EQ(zero.size(), kUneven.intervals());
    EXPECT_LT(zero.maxCoeff(), 1e-15);

    const PowerOfTimeOcp next(c.next_power);
    const Mat X = next.ExactStates(kUneven);
    const Vec eta = IntervalDefectErrors(next, c.scheme, kUneven, X, u);
    const double scale = 1.0 + X.cwiseAbs().maxCoeff();
    for (int k = 0; k < kUneven.intervals(); ++k) {
      const double expected = std::pow(kUneven.h(k), c.exponent) / c.denominator / scale;
      EXPECT_NEAR(eta[k], expected, 1e-12 * expected) << "interval " << k;
    }
  }
}

// The largest estimate at Ipopt's solutions of Hager's problem (smooth, x* and u* known) on
// N = 10, 20, 40, 80 uniform intervals: the least-squares slope of log(max estimate) against
// log(h) is the order DefectEstimateOrder states (3 trapezoid, 4 Hermite-Simpson).
TEST(MeshError, LargestEstimateDecreasesAtTheSchemesOrderUnderHalving) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("hager", {}, 1);
  const std::unique_ptr<Solver> ipopt = FindSolver("ipopt").make();
  for (const auto& [name, scheme] : std::vector<std::pair<std::string, CollocationInterpolant>>{
           {"trapezoid", CollocationInterpolant::kTrapezoid},
           {"hermite-simpson", CollocationInterpolant::kHermiteSimpson}}) {
    std::vector<double> log_h, log_error;
    for (const int N : {10, 20, 40, 80}) {
      SolveRequest request;
      request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
      request.terminal = TerminalMode::kHard;
      request.transcription = name;
      // One mesh, never refined: the history's row is the estimate on this uniform grid.
      request.transcription_options.Set("mesh_tolerance", 1e-300);
      request.transcription_options.Set("mesh_max_iterations", 1);
      request.options = {{"tol", "1e-12"}};
      const SolveResult r = ipopt->Solve(*ocp, request);
      ASSERT_EQ(r.status, SolveStatus::kConverged) << name << " N " << N << ": " << r.message;
      ASSERT_EQ(r.mesh_history.size(), 1u);
      log_h.push_back(std::log(request.grid.h(0)));
      log_error.push_back(std::log(r.mesh_history[0].max_error));
    }
    double mh = 0, me = 0;
    for (size_t i = 0; i < log_h.size(); ++i) {
      mh += log_h[i] / log_h.size();
      me += log_error[i] / log_h.size();
    }
    double num = 0, den = 0;
    for (size_t i = 0; i < log_h.size(); ++i) {
      num += (log_h[i] - mh) * (log_error[i] - me);
      den += (log_h[i] - mh) * (log_h[i] - mh);
    }
    const double slope = num / den;
    EXPECT_NEAR(slope, DefectEstimateOrder(scheme), 0.2) << name;
  }
}

}  // namespace
}  // namespace ocpb
