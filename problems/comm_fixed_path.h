// Motion and communication co-optimization on a given path (OCPBench problem "comm-fixed-path").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "problems/comm_path2d.h"

namespace ocpb {

/// A planar path q(sigma) parameterized by arc length sigma: a polyline through `waypoints` whose
/// interior corners are rounded by circular arcs of radius `fillet` (0: sharp corners). A corner
/// turning by phi is cut back by fillet tan(phi/2) along both adjacent segments, so the path is C1
/// (unit tangent continuous) and its curvature is piecewise constant (0 on lines, 1/fillet on
/// arcs). Beyond its ends, q continues along the end tangents, so q is defined for every sigma.
class PlanarPath {
 public:
  /// Throws std::invalid_argument unless there are >= 2 waypoints, consecutive waypoints are
  /// distinct, no corner turns back on itself, fillet >= 0, and each corner's cut-back fits in half
  /// of each adjacent segment.
  PlanarPath(const std::vector<Eigen::Vector2d>& waypoints, double fillet);

  double length() const { return length_; }
  const std::vector<Eigen::Vector2d>& waypoints() const { return waypoints_; }
  double fillet() const { return fillet_; }

  /// q(sigma), its unit tangent q'(sigma) and q''(sigma) (either may be null). On an arc,
  /// q'' = -(1/fillet) (q - center); on a line it is 0.
  void Evaluate(double sigma, Eigen::Vector2d* q, Eigen::Vector2d* dq, Eigen::Vector2d* ddq) const;

 private:
  struct Piece {
    bool arc = false;
    double s0 = 0.0, length = 0.0;
    Eigen::Vector2d start = Eigen::Vector2d::Zero();  // line: q = start + (sigma - s0) dir
    Eigen::Vector2d direction = Eigen::Vector2d::Zero();
    Eigen::Vector2d center = Eigen::Vector2d::Zero();  // arc: q = center + r (cos a, sin a),
    double angle0 = 0.0, turn = 1.0;  //      a = angle0 + turn (sigma - s0) / r, turn = +-1
  };
  std::vector<Eigen::Vector2d> waypoints_;
  double fillet_;
  std::vector<Piece> pieces_;
  double length_ = 0.0;
};

/// The fixed-path problem of the paper's predecessor (Ali, Yan, Mostofi, Wardi, 2015), as
/// reconstructed in the OCPBench notes: a robot moves along a given path q(.) from S to D,
///   state   x1 = arc length, x2 = speed, x3 = bits/Hz sent;  x1' = x2, x2' = u, x3' = R,
///           x(0) = (0, 0, 0);
///   control u (scalar acceleration), R (spectral efficiency): |u| <= umax, 0 <= R <= Rmax;
///   cost    J = int_0^tf [(2^R - 1)/K s(q(x1)) + gamma (k1 u^2 + k2 x2^2 + k3 n(x2) + k4 +
///                          k5 n(u) + k6 n(u) n(x2))] dt
///               + C1 (x1(tf) - length)^2 + C2 x2(tf)^2 + C3 (x3(tf) - c)^2,
/// with the power model and smoothing n(.) of CommPowerModel, d s(q(x1))/dx1 = grad s . q' and
/// d2/dx1^2 = q'^T (hess s) q' + grad s . q''. Terminal constraints
/// psi = (x1 - length, x2, x3 - c), weights (C1, C2, C3).
///
/// Default path: S = (20, 40) -> W = (7, 9) -> D = (10, 5), a detour past the base station (5, 5)
/// (W is 4.5 m from it), with the corner at W rounded by a 2 m arc; length 38.405 m. The fillet
/// removes the kink of the polyline, where s(q(x1)) would have a jump in its derivative (fillet = 0
/// keeps the kink, and the derivatives there are one-sided).
/// Hamiltonian minimizer: u* = -sign(p2) r with r = CommPowerModel::AccelerationMagnitude(|p2|,
/// n(x2), umax) (= clip(-p2 / (2 gamma k1), -umax, umax) when k5 = k6 = 0), R* as in CommPath2d.
class CommFixedPath final : public AutoDiffOcp<CommFixedPath, 3, 2, 3, 0>, public CommEnergyModel {
 public:
  struct Options {
    double bits = 150.0;                        ///< c (>= 0)
    double tf = 40.0;                           ///< horizon in s (> 0)
    double umax = 0.5;                          ///< |u| <= umax (> 0)
    double rmax = 6.0;                          ///< 0 <= R <= Rmax (> 0)
    Eigen::Vector3d penalty{10.0, 50.0, 10.0};  ///< C1, C2, C3 (> 0)
    CommPowerModel power;

    bool IsValid(std::string* error) const;
  };

  /// Throws std::invalid_argument (naming the field) on invalid options or a null path/channel.
  CommFixedPath(const Options& options,
                std::shared_ptr<const PlanarPath> path,
                std::shared_ptr<const ChannelQuality> channel);

  std::string name() const override { return "comm-fixed-path"; }
  const Options& options() const { return options_; }
  const PlanarPath& path() const { return *path_; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 2>& u, VecT<T, 3>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0];
    (*f)[2] = u[1];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 3>& x, const VecT<T, 2>& u) const {
    const T s = ChannelAlongPath(x[0]);
    const T acc2 = u[0] * u[0];
    const T speed2 = x[1] * x[1];
    return options_.power.Transmission(u[1], s, inv_k_) + options_.power.Motion(acc2, speed2);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 3>* psi) const {
    (*psi)[0] = x[0] - path_->length();
    (*psi)[1] = x[1];
    (*psi)[2] = x[2] - options_.bits;
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;
  /// gamma k4, as in CommPath2d.
  std::optional<double> RunningCostLowerBound() const override {
    return options_.power.gamma * options_.power.k[3];
  }
  /// The path at constant speed (BaselineAccelerations along the arc length: the shortest
  /// speed-up and braking |u| <= umax allows, ending at its end at rest on the Euler grid) and
  /// the constant rate that sends c bits by tf. Needs a uniform grid spanning [0, tf].
  std::optional<ControlTrajectory> BaselinePlan(const TimeGrid& grid,
                                                std::string* why_not) const override;

  // ---- CommEnergyModel ----
  Eigen::Vector2d Position(ConstVecRef x) const override {
    Eigen::Vector2d q;
    path_->Evaluate(x[0], &q, nullptr, nullptr);
    return q;
  }
  double MotionPower(ConstVecRef x, ConstVecRef u) const override {
    return options_.power.Motion(u[0] * u[0], x[1] * x[1]);
  }
  double TransmitPower(ConstVecRef u, double s) const override {
    return options_.power.Transmission(u[1], s, inv_k_);
  }

  /// s(q(sigma)) as a double or a jet in sigma.
  template <class T>
  T ChannelAlongPath(const T& sigma) const {
    Eigen::Vector2d q, dq, ddq;
    double s = 0.0;
    if constexpr (std::is_same_v<T, double>) {
      path_->Evaluate(sigma, &q, nullptr, nullptr);
      channel_->Evaluate(q, &s, nullptr, nullptr);
      return s;
    } else {
      Eigen::Vector2d g;
      if constexpr (requires { sigma.h; }) {
        Eigen::Matrix2d h;
        path_->Evaluate(sigma.a, &q, &dq, &ddq);
        channel_->Evaluate(q, &s, &g, &h);
        return sigma.Chain(s, g.dot(dq), dq.dot(h * dq) + g.dot(ddq));
      } else {
        path_->Evaluate(sigma.a, &q, &dq, nullptr);
        channel_->Evaluate(q, &s, &g, nullptr);
        return sigma.Chain(s, g.dot(dq), 0.0);
      }
    }
  }

 private:
  Options options_;
  double inv_k_;
  std::shared_ptr<const PlanarPath> path_;
  std::shared_ptr<const ChannelQuality> channel_;
};

/// The registry entry of comm-fixed-path (the parameters of CommParameterSpecs plus W, the
/// waypoint, and fillet, the corner radius).
ProblemInfo CommFixedPathProblemInfo();

}  // namespace ocpb
