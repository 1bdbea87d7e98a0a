// Small problems with known answers used by the transcription tests.
#pragma once

#include <cmath>
#include <limits>

#include "core/autodiff_ocp.h"

namespace ocpb::testing {

/// Scalar linear-quadratic regulator with a non-polynomial optimum:
///   minimize 1/2 int_0^1 (x^2 + u^2) dt,  x' = u,  x(0) = 1.
/// Riccati P(t) = tanh(1 - t): x*(t) = cosh(1 - t)/cosh(1), p*(t) = sinh(1 - t)/cosh(1),
/// u* = -p*, J* = tanh(1)/2.
class ScalarLqOcp final : public AutoDiffOcp<ScalarLqOcp, 1, 1> {
 public:
  ScalarLqOcp() {
    SetDimensions(1, 1, 0, 0);
    SetHorizon(0.0, 1.0);
    SetInitialState(Vec::Ones(1));
  }
  std::string name() const override { return "scalar-lq"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>& x, const VecT<T, 1>& u) const {
    return 0.5 * (x[0] * x[0] + u[0] * u[0]);
  }
  static double OptimalCost() { return 0.5 * std::tanh(1.0); }
  static double State(double t) { return std::cosh(1.0 - t) / std::cosh(1.0); }
  static double Costate(double t) { return std::sinh(1.0 - t) / std::cosh(1.0); }
};

/// A nonlinear problem with a ball-and-box control set, two path constraints and one terminal
/// constraint (nx = 2, nu = 3), on [0, 2]:
///   x1' = x2 + u1 cos(x1) + t u3,   x2' = -sin(x1) + u2 u3 + x2 u1^2,
///   L = |u|^2 + x1^2 u3 + exp(0.3 x2),  phi = x1^2 + x2,  psi = x1 + x2 - 1,
///   c = (x1^2 + u3 - 2, x2 - u1 - 1),  U = {|(u1, u2) - (0.2, -0.1)| <= 1} x [-0.5, 2].
class BallTestOcp final : public AutoDiffOcp<BallTestOcp, 2, 3, 1, 2> {
 public:
  BallTestOcp() {
    SetDimensions(2, 3, 1, 2);
    SetHorizon(0.0, 2.0);
    Vec x0(2);
    x0 << 0.5, -0.3;
    SetInitialState(x0);
    SetTerminalWeights(Vec::Constant(1, 5.0));
    ControlSet set;
    Vec center(2);
    center << 0.2, -0.1;
    set.AddBall(center, 1.0);
    set.AddBox(Vec::Constant(1, -0.5), Vec::Constant(1, 2.0));
    SetControlSet(set);
  }
  std::string name() const override { return "ball-test"; }
  template <class T>
  void EvalDynamics(double t, const VecT<T, 2>& x, const VecT<T, 3>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1] + u[0] * cos(x[0]) + t * u[2];
    (*f)[1] = -sin(x[0]) + u[1] * u[2] + x[1] * u[0] * u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& x, const VecT<T, 3>& u) const {
    return u[0] * u[0] + u[1] * u[1] + u[2] * u[2] + x[0] * x[0] * u[2] + exp(0.3 * x[1]);
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 2>& x) const {
    return x[0] * x[0] + x[1];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[0] + x[1] - 1.0;
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 2>& x, const VecT<T, 3>& u, VecT<T, 2>* c) const {
    (*c)[0] = x[0] * x[0] + u[2] - 2.0;
    (*c)[1] = x[1] - u[0] - 1.0;
  }
};

/// Nonlinear boundary constraints coupling a partly free x(t0) with x(tf), an initial cost, and
/// state bounds, for the transcriptions' derivative tests (no known optimum):
///   x1' = x2, x2' = u - x1^3/4, x(0) = (0.3, -0.2) with x1(0) in [-1, 1] free,
///   b = (x1(0) x2(tf), sin(x2(0)) + x1(tf)^2 x2(tf)) in [0, 0] x [-inf, 1],
///   phi0 = x1(0)^4 / 4 + x1(0) x2(0), L = u^2, x in [-2, 2] x [-inf, 3].
class BoundaryTestOcp final : public AutoDiffOcp<BoundaryTestOcp, 2, 1> {
 public:
  BoundaryTestOcp() {
    const double inf = std::numeric_limits<double>::infinity();
    SetHorizon(0.0, 1.0);
    SetInitialState(Vec2(0.3, -0.2));
    SetInitialStateBounds(Vec2(-1.0, -0.2), Vec2(1.0, -0.2));
    SetStateBounds(Vec2(-2.0, -inf), Vec2(2.0, 3.0));
    SetBoundaryConstraints(Vec2(0.0, -inf), Vec2(0.0, 1.0));
  }
  std::string name() const override { return "boundary-test"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0] - 0.25 * x[0] * x[0] * x[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
  template <class T>
  T EvalInitialCost(const VecT<T, 2>& x0) const {
    return 0.25 * x0[0] * x0[0] * x0[0] * x0[0] + x0[0] * x0[1];
  }
  template <class T>
  void EvalBoundaryConstraints(const VecT<T, 2>& x0,
                               const VecT<T, 2>& xf,
                               VecT<T, Eigen::Dynamic>* b) const {
    (*b)[0] = x0[0] * xf[1];
    (*b)[1] = sin(x0[1]) + xf[0] * xf[0] * xf[1];
  }

 private:
  static Vec Vec2(double a, double b) {
    Vec v(2);
    v << a, b;
    return v;
  }
};

/// A nonlinear (bilinear dynamics) problem with a known optimum, on [0, 1]:
///   minimize int (u^2/2 + x^2) dt,  x' = x u / 2,  x(0) = sqrt(2)/sin(d),
///   psi = x(1) - sqrt(2)/sin(1 + d) = 0  (hard form),  d = pi/3.
/// With x = exp(y/2) it is y' = u, L = u^2/2 + exp(y), whose Euler-Lagrange equation y'' = exp(y)
/// has the solution y = log(2/sin^2(t + d)). Hence x*(t) = sqrt(2)/sin(t + d),
/// u*(t) = -2 cot(t + d), p*(t) = -2 u*/x* = 2 sqrt(2) cos(t + d) (H = p^T f + L),
/// J* = 4 (cot d - cot(1 + d)) - 2.
class BilinearTestOcp final : public AutoDiffOcp<BilinearTestOcp, 1, 1, 1, 0> {
 public:
  static constexpr double kD = 1.0471975511965976;  // pi/3
  BilinearTestOcp() {
    SetDimensions(1, 1, 1, 0);
    SetHorizon(0.0, 1.0);
    SetInitialState(Vec::Constant(1, State(0.0)));
    SetTerminalWeights(Vec::Constant(1, 100.0));
  }
  std::string name() const override { return "bilinear-test"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>& x, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = 0.5 * x[0] * u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>& x, const VecT<T, 1>& u) const {
    return 0.5 * u[0] * u[0] + x[0] * x[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 1>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[0] - State(1.0);
  }
  static double State(double t) { return std::sqrt(2.0) / std::sin(t + kD); }
  static double Control(double t) { return -2.0 / std::tan(t + kD); }
  static double Costate(double t) { return 2.0 * std::sqrt(2.0) * std::cos(t + kD); }
  static double OptimalCost() {
    return 4.0 * (1.0 / std::tan(kD) - 1.0 / std::tan(1.0 + kD)) - 2.0;
  }
};

}  // namespace ocpb::testing
