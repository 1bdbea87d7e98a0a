#include "transcriptions/mesh_error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace ocpb {
namespace {

// 5-point Gauss-Legendre rule on [-1, 1]: exact for polynomials of degree 9.
constexpr std::array<double, 5> kGaussNodes = {
    -0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
constexpr std::array<double, 5> kGaussWeights = {0.2369268850561891,
                                                 0.4786286704993665,
                                                 0.5688888888888889,
                                                 0.4786286704993665,
                                                 0.2369268850561891};

// The node derivatives f_k = f(t_k, x_k, u(t_k)) (nx x nodes): the slopes both interpolants use.
Mat NodeDerivatives(const Ocp& ocp,
                    const TimeGrid& nodes,
                    const Mat& node_states,
                    const ControlTrajectory& controls) {
  Mat F(ocp.nx(), nodes.size());
  Vec u(ocp.nu());
  for (int k = 0; k < nodes.size(); ++k) {
    // At tf the left limit: the control of the last interval (continuous for both schemes).
    const auto side =
        k + 1 == nodes.size() ? ControlTrajectory::Side::kLeft : ControlTrajectory::Side::kRight;
    controls.Evaluate(nodes.t(k), side, u);
    ocp.Dynamics(nodes.t(k), node_states.col(k), u, F.col(k));
  }
  return F;
}

}  // namespace

void InterpolateState(CollocationInterpolant scheme,
                      const TimeGrid& nodes,
                      const Mat& X,
                      const Mat& F,
                      int k,
                      double s,
                      VecRef x,
                      VecRef xdot) {
  const double h = nodes.h(k);
  if (scheme == CollocationInterpolant::kTrapezoid) {
    x = X.col(k) + h * (s * F.col(k) + 0.5 * s * s * (F.col(k + 1) - F.col(k)));
    xdot = F.col(k) + s * (F.col(k + 1) - F.col(k));
    return;
  }
  // Cubic Hermite basis on [0, 1] and its derivatives with respect to s.
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
  const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  const double d00 = 6 * s2 - 6 * s, d10 = 3 * s2 - 4 * s + 1;
  const double d01 = -6 * s2 + 6 * s, d11 = 3 * s2 - 2 * s;
  x = h00 * X.col(k) + h10 * h * F.col(k) + h01 * X.col(k + 1) + h11 * h * F.col(k + 1);
  xdot = (d00 * X.col(k) + d01 * X.col(k + 1)) / h + d10 * F.col(k) + d11 * F.col(k + 1);
}

int DefectEstimateOrder(CollocationInterpolant scheme) {
  return scheme == CollocationInterpolant::kTrapezoid ? 3 : 4;
}

Vec IntervalDefectErrors(const Ocp& ocp,
                         CollocationInterpolant scheme,
                         const TimeGrid& nodes,
                         const Mat& node_states,
                         const ControlTrajectory& controls) {
  const int nx = ocp.nx(), N = nodes.intervals();
  const Mat F = NodeDerivatives(ocp, nodes, node_states, controls);
  // Betts' weights: 1 + the largest magnitude of each state component over the mesh.
  const Vec inv_weight = (1.0 + node_states.cwiseAbs().rowwise().maxCoeff().array()).inverse();
  // The pieces between collocation points, as fractions of the interval.
  const std::vector<double> breaks = scheme == CollocationInterpolant::kTrapezoid
                                         ? std::vector<double>{0.0, 1.0}
                                         : std::vector<double>{0.0, 0.5, 1.0};
  Vec eta(N);
  Vec x(nx), xdot(nx), f(nx), u(ocp.nu()), integral(nx);
  for (int k = 0; k < N; ++k) {
    const double h = nodes.h(k);
    integral.setZero();
    for (size_t p = 0; p + 1 < breaks.size(); ++p) {
      const double half = 0.5 * (breaks[p + 1] - breaks[p]);
      const double mid = 0.5 * (breaks[p + 1] + breaks[p]);
      for (size_t q = 0; q < kGaussNodes.size(); ++q) {
        const double s = mid + half * kGaussNodes[q];
        const double t = nodes.t(k) + s * h;
        InterpolateState(scheme, nodes, node_states, F, k, s, x, xdot);
        controls.Evaluate(t, ControlTrajectory::Side::kRight, u);
        ocp.Dynamics(t, x, u, f);
        integral += (kGaussWeights[q] * half * h) * (xdot - f).cwiseAbs();
      }
    }
    eta[k] = integral.allFinite() ? integral.cwiseProduct(inv_weight).maxCoeff()
                                  : std::numeric_limits<double>::quiet_NaN();
  }
  return eta;
}

ControlTrajectory StateInterpolant(const Ocp& ocp,
                                   CollocationInterpolant scheme,
                                   const TimeGrid& nodes,
                                   const Mat& node_states,
                                   const ControlTrajectory& controls) {
  const Mat F = NodeDerivatives(ocp, nodes, node_states, controls);
  const Mat X = node_states;
  const TimeGrid g = nodes;
  auto fn = [scheme, g, X, F](double t, ControlTrajectory::Side side, VecRef x) {
    int k = g.Locate(t);
    if (side == ControlTrajectory::Side::kLeft && k > 0 && t <= g.t(k)) --k;
    const double s = std::clamp((t - g.t(k)) / g.h(k), 0.0, 1.0);
    Vec xdot(X.rows());
    InterpolateState(scheme, g, X, F, k, s, x, xdot);
  };
  return ControlTrajectory::Custom(
      static_cast<int>(X.rows()),
      g,
      fn,
      scheme == CollocationInterpolant::kTrapezoid
          ? "trapezoid state interpolant: quadratic with slopes f_k, f_k+1"
          : "Hermite-Simpson state interpolant: cubic Hermite through (x_k, f_k), (x_k+1, f_k+1)");
}

}  // namespace ocpb
