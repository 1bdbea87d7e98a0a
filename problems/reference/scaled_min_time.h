// Free final time by time scaling: the shared form of the minimum-time reference problems
// ("brachistochrone", "zermelo", "steering").
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/reference/time_scaling.h"

namespace ocpb {

/// A minimum-time problem with a steering-angle control,
///
///   minimize tf  subject to  y' = f0(y) + B(y) w,  w = (cos th, sin th) (or sin, cos),
///                            y(0) = y0,  psi(y(tf)) = 0,
///
/// has a free final time, which the core (fixed horizon) does not. It is posed on s in [0, 1]
/// with the time dilation sigma = dt/ds > 0 as a control, the scaled heading v = sigma w as two
/// more, and the physical time tau as the last state (a clock):
///
///   minimize    J = tau(1) - eps tau(1)^2 + eps int_0^1 sigma^2 ds
///   subject to  dy/ds = sigma f0(y) + B(y) v,  dtau/ds = sigma,  tau(0) = 0,
///               c = |v|^2 - sigma^2 <= 0                           (path constraint: |w| <= 1),
///               u = (v1, v2, sigma) in U = {|v| <= sigma_max} x [sigma_min, sigma_max].
///
/// Three documented changes make this a problem of the core (reference-problems notes, fits C
/// and R):
///  - The angle becomes the unit vector w, relaxed to the disc |w| <= 1: for minimum time the
///    optimal w lies on the circle wherever the switching vector s = B(y)^T p is nonzero (a
///    shorter w only slows the state down), so the relaxation is exact.
///  - The controls are (v, sigma), not (w, sigma): the dynamics are then linear in u and the cone
///    |v| <= sigma is convex, so the Hamiltonian is convex in u. With (w, sigma) it is bilinear,
///    and the pointwise minimizer's direction need not descend (measured: the Armijo search
///    failed at the first iteration on the brachistochrone).
///  - sigma(s) may vary: any positive profile with the same path is the same physical motion, so
///    with cost tau(1) alone the problem has a continuum of optima (degenerate in sigma's
///    profile: Ipopt then needed 300-900 iterations, and collocation schemes let sigma oscillate
///    between nodes). The eps terms remove it exactly: with T = tau(1) = int sigma,
///    J = T + eps (int sigma^2 - T^2) = T + eps Var(sigma) >= T, with equality exactly when sigma
///    is constant (= tf). So every optimum has sigma = tf constant and J = tf, the minimum time,
///    in both terminal forms, for any eps >= 0 (eps = 0 is the degenerate problem as stated).
///
/// Hamiltonian: H = sigma a + s^T v + eps sigma^2 with a = p^T f0 + p_tau, p_tau = 1 - 2 eps tau(1)
/// (constant) and s = B^T p; f0 and s come from three evaluations of the physical dynamics. Its
/// minimizer under the cone: v* = -r s/|s| with r = sigma*, sigma* = clip((|s| - a) / (2 eps),
/// sigma_min, sigma_max). The Hamiltonian method cannot take the path constraint;
/// HamiltonianReformulation() returns ScaledMinTimePenalty (below): the cone as the penalty
/// rho max(0, |v| - sigma)^2 (convex), with its own exact minimizer, and eps = 1 when eps = 0.
///
/// `Derived` has state dimension NX (the physical state, then the clock at index NX - 1) and
/// provides
///   template <class T> void EvalPhysical(const VecT<T, NX>& x, const T& w1, const T& w2,
///                                        VecT<T, NX>* f) const;  // f0 + B w in f[0 .. NX-2]
///   template <class T> void EvalTerminalConstraints(const VecT<T, NX>& x,
///                                                   VecT<T, NPSI>* psi) const;
/// and calls InitializeScaling() from its constructor. The records' J is tf (plus eps times the
/// variance of sigma, zero at any constant sigma); their time axis is s, their last state is t,
/// and the heading is w = v / sigma.
template <class Derived, int NX, int NPSI>
class ScaledMinTimeOcp : public AutoDiffOcp<Derived, NX, 3, NPSI, 1> {
 public:
  /// Parameters shared by every scaled minimum-time problem, with the problem's defaults
  /// (eps = 1).
  static std::vector<ParameterSpec> ScalingParameterSpecs(double C,
                                                          double sigma_min,
                                                          double sigma_max) {
    return TimeScalingParameterSpecs(C, 1.0, sigma_min, sigma_max, "rho max(0, |v| - sigma)^2");
  }

  double eps() const { return eps_; }
  double rho() const { return rho_; }
  double sigma_min() const { return sigma_min_; }
  double sigma_max() const { return sigma_max_; }

  template <class T>
  void EvalDynamics(double, const VecT<T, NX>& x, const VecT<T, 3>& u, VecT<T, NX>* f) const {
    // sigma f0 + B v = Phys(v) + (sigma - 1) Phys(0), Phys being affine in its heading.
    VecT<T, NX> f0;
    Physical(x, T(0.0), T(0.0), &f0);
    Physical(x, u[0], u[1], f);
    for (int i = 0; i < NX; ++i) (*f)[i] += (u[2] - 1.0) * f0[i];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, NX>&, const VecT<T, 3>& u) const {
    return eps_ * u[2] * u[2];
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, NX>& x) const {
    return x[NX - 1] - eps_ * x[NX - 1] * x[NX - 1];
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, NX>&, const VecT<T, 3>& u, VecT<T, 1>* c) const {
    (*c)[0] = u[0] * u[0] + u[1] * u[1] - u[2] * u[2];
  }

  /// H's drift a = p^T f0 (clock included) and switching vector s = B^T p at (x, p).
  void HamiltonianCoefficients(ConstVecRef x, ConstVecRef p, double* a, double s[2]) const {
    const VecT<double, NX> xs(x);
    VecT<double, NX> f0, f1, f2;
    Physical(xs, 0.0, 0.0, &f0);
    Physical(xs, 1.0, 0.0, &f1);
    Physical(xs, 0.0, 1.0, &f2);
    *a = p.dot(f0);
    s[0] = p.dot(f1 - f0);
    s[1] = p.dot(f2 - f0);
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  /// The exact minimizer of H over U and the cone |v| <= sigma (see above); eps = 0 gives the
  /// bang-bang sigma_min (a > |s|) or sigma_max.
  void MinimizeHamiltonian(double, ConstVecRef x, ConstVecRef p, VecRef u) const override {
    double a, s[2];
    HamiltonianCoefficients(x, p, &a, s);
    const double norm = std::hypot(s[0], s[1]);
    double sigma;
    if (eps_ > 0.0) {
      sigma = std::clamp((norm - a) / (2.0 * eps_), sigma_min_, sigma_max_);
    } else {
      sigma = a - norm > 0.0 ? sigma_min_ : sigma_max_;
    }
    u[0] = norm > 0.0 ? -sigma * s[0] / norm : 0.0;
    u[1] = norm > 0.0 ? -sigma * s[1] / norm : 0.0;
    u[2] = sigma;
  }

  /// The start every method uses without an initial guess: the problem's nominal heading and
  /// time dilation (u = 0 would not steer: v = 0 leaves the physical input out).
  Vec NominalControl() const override {
    return Eigen::Vector3d(
        nominal_sigma_ * nominal_w_[0], nominal_sigma_ * nominal_w_[1], nominal_sigma_);
  }

  std::unique_ptr<Ocp> HamiltonianReformulation(
      const HamiltonianReformulationOptions& options) const override;

 protected:
  /// Reads C, eps, rho and the sigma bounds, and sets the horizon [0, 1], the initial state
  /// (y0, 0), the terminal weights, U and the nominal control (a rough guess of the heading w and
  /// of tf). Throws std::invalid_argument when sigma_min >= sigma_max.
  void InitializeScaling(const Parameters& params,
                         const Vec& y0,
                         const Eigen::Vector2d& nominal_w,
                         double nominal_sigma) {
    const TimeScalingSettings settings = TimeScalingSettings::Read(params, derived().name());
    eps_ = settings.eps;
    rho_ = settings.rho;
    sigma_min_ = settings.sigma_min;
    sigma_max_ = settings.sigma_max;
    nominal_w_ = nominal_w;
    nominal_sigma_ = nominal_sigma;
    this->SetDimensions(NX, 3, NPSI, 1);
    this->SetHorizon(0.0, 1.0);
    Vec x0 = Vec::Zero(NX);
    x0.head(NX - 1) = y0;
    this->SetInitialState(x0);
    this->SetTerminalWeights(Vec::Constant(NPSI, params.Scalar("C")));
    ControlSet set;
    set.AddBall(2, sigma_max_);
    set.AddBox(Vec::Constant(1, sigma_min_), Vec::Constant(1, sigma_max_));
    this->SetControlSet(set);
  }

 private:
  template <class D, int N, int P>
  friend class ScaledMinTimePenalty;

  const Derived& derived() const { return static_cast<const Derived&>(*this); }
  /// The unscaled dynamics: the problem's f0 + B w, and the clock's 1.
  template <class T>
  void Physical(const VecT<T, NX>& x, const T& w1, const T& w2, VecT<T, NX>* f) const {
    derived().EvalPhysical(x, w1, w2, f);
    (*f)[NX - 1] = T(1.0);
  }

  double eps_ = 1.0;
  double rho_ = 1e4;
  double sigma_min_ = 0.0;
  double sigma_max_ = 1.0;
  Eigen::Vector2d nominal_w_ = Eigen::Vector2d::Zero();
  double nominal_sigma_ = 1.0;
};

/// The Hamiltonian method's form of a ScaledMinTimeOcp P: the cone |v| <= sigma as the exterior
/// penalty rho max(0, |v| - sigma)^2 in L (convex in u, like the cone; zero set the same as P's
/// c <= 0 since sigma > 0), no path constraints, everything else P's. The penalty lets |v|
/// exceed sigma by at most |s| / (2 rho), so the optimum is faster than P's by O(1/rho); its
/// controls are judged on P (the evaluator reports the cone's violation as the path violation).
///
/// Exact minimizer of H = a sigma + s^T v + eps sigma^2 + rho max(0, |v| - sigma)^2 over U: with
/// v = -r s/|s|, minimizing over r first leaves the convex h(sigma) with the piecewise-linear
/// increasing derivative h' = a - |s| + 2 eps sigma (sigma <= sb = sigma_max - |s|/(2 rho), where
/// r = sigma + |s|/(2 rho)) and h' = a + 2 eps sigma - 2 rho (sigma_max - sigma) (above, r =
/// sigma_max). sigma* is its root clipped to [sigma_min, sigma_max], r = min(sigma* + |s|/(2 rho),
/// sigma_max).
template <class Derived, int NX, int NPSI>
class ScaledMinTimePenalty final
    : public AutoDiffOcp<ScaledMinTimePenalty<Derived, NX, NPSI>, NX, 3, NPSI, 0> {
 public:
  ScaledMinTimePenalty(const Derived& problem, double rho, double eps) : problem_(problem) {
    CheckReformulationWeights(problem.name(), rho, eps);
    problem_.eps_ = eps;
    rho_ = rho;
    this->SetDimensions(NX, 3, NPSI, 0);
    this->SetHorizon(problem.t0(), problem.tf());
    this->SetInitialState(problem.x0());
    this->SetTerminalWeights(problem.terminal_weights());
    this->SetControlSet(problem.control_set());
  }

  std::string name() const override { return problem_.name() + "+penalty"; }
  double rho() const { return rho_; }
  double eps() const { return problem_.eps_; }

  template <class T>
  void EvalDynamics(double t, const VecT<T, NX>& x, const VecT<T, 3>& u, VecT<T, NX>* f) const {
    problem_.EvalDynamics(t, x, u, f);
  }
  template <class T>
  T EvalRunningCost(double t, const VecT<T, NX>& x, const VecT<T, 3>& u) const {
    T L = problem_.EvalRunningCost(t, x, u);
    const T norm2 = u[0] * u[0] + u[1] * u[1];
    // Active only where |v| > sigma >= sigma_min > 0, so the square root is smooth there.
    if (ValueOf(norm2) > ValueOf(u[2]) * ValueOf(u[2])) {
      const T excess = sqrt(norm2) - u[2];
      L += rho_ * excess * excess;
    }
    return L;
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, NX>& x) const {
    return problem_.EvalTerminalCost(x);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, NX>& x, VecT<T, NPSI>* psi) const {
    problem_.EvalTerminalConstraints(x, psi);
  }

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double, ConstVecRef x, ConstVecRef p, VecRef u) const override {
    double a, s[2];
    problem_.HamiltonianCoefficients(x, p, &a, s);
    const double norm = std::hypot(s[0], s[1]);
    const double eps = problem_.eps_;
    const double smax = problem_.sigma_max_;
    const double sb = smax - norm / (2.0 * rho_);
    const double root_low = (norm - a) / (2.0 * eps);
    const double root =
        root_low <= sb ? root_low : (2.0 * rho_ * smax - a) / (2.0 * eps + 2.0 * rho_);
    const double sigma = std::clamp(root, problem_.sigma_min_, smax);
    const double r = std::min(sigma + norm / (2.0 * rho_), smax);
    u[0] = norm > 0.0 ? -r * s[0] / norm : 0.0;
    u[1] = norm > 0.0 ? -r * s[1] / norm : 0.0;
    u[2] = sigma;
  }
  Vec NominalControl() const override { return problem_.NominalControl(); }

 private:
  Derived problem_;
  double rho_ = 1e4;
};

template <class Derived, int NX, int NPSI>
std::unique_ptr<Ocp> ScaledMinTimeOcp<Derived, NX, NPSI>::HamiltonianReformulation(
    const HamiltonianReformulationOptions& options) const {
  const double eps = eps_ > 0.0 ? eps_ : options.regularization.value_or(1.0);
  return std::make_unique<ScaledMinTimePenalty<Derived, NX, NPSI>>(
      derived(), options.path_penalty.value_or(rho_), eps);
}

}  // namespace ocpb
