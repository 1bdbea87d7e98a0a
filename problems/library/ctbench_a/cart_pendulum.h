// The cart-pendulum swing-up of OptimalControlProblems.jl ("cart_pendulum", after the FATROP
// example): OCPBench problem "cart-pendulum".
#pragma once

#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    T  (free final time, T >= 0.1)
/// over the state (x, v, theta, omega), the force Fex in [-5, 5] and a constant decision ddx
/// (a static parameter, unbounded), with the source's dynamics kept as they are:
///   x' = v,  theta' = omega,
///   v' = (m a1 - Fex) / mc + 2 ddx,  a1 = -L sin(theta) omega + (L/2) cos(theta) al + ddx,
///        al = K (-ddx cos(theta) - g sin(theta)),
///   omega' = K (-v' cos(theta) - g sin(theta)),  K = (L m / 2) / (I + m L^2 / 4),
/// with g = 9.81, L = 1, m = 1, I = m L^2 / 12, mc = 0.5;
/// x(0) = 0, theta(0) = 0, omega(0) = 0, v(0) free in [-2, 2]; theta(T) = pi, omega(T) = 0;
/// |x| <= 1, |v| <= 2 (state bounds).
/// This is OptimalControlProblems.jl's JuMP model `cart_pendulum` exactly: there the scalar ddx
/// is a free variable of the NLP (the source's comment says the cart's effective mass J = mc
/// "should be -(m+mcart)"), and v(0) is not fixed. The cost is L = 1 over the free horizon.
class CartPendulum final : public AutoDiffOcp<CartPendulum, 5, 1, 2, 0> {
 public:
  static constexpr double kGravity = 9.81;
  static constexpr double kLength = 1.0;
  static constexpr double kMass = 1.0;
  static constexpr double kCartMass = 0.5;
  static constexpr double kInertia = kMass * kLength * kLength / 12.0;
  static constexpr double kK =
      0.5 * kLength * kMass / (kInertia + 0.25 * kMass * kLength * kLength);
  static constexpr double kPi = 3.14159265358979323846;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit CartPendulum(const Parameters& params);

  std::string name() const override { return "cart-pendulum"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 5>& x, const VecT<T, 1>& u, VecT<T, 5>* f) const {
    const T& theta = x[2];
    const T& omega = x[3];
    const T& ddx = x[4];
    const T s = sin(theta);
    const T c = cos(theta);
    const T al = kK * (-ddx * c - kGravity * s);
    const T a1 = -kLength * s * omega + 0.5 * kLength * c * al + ddx;
    // c = eq - J ddx with eq = -m a1 + Fex - mc ddx and J = mc; v' = -c / J.
    const T eq = -kMass * a1 + u[0] - kCartMass * ddx;
    const T dv = -(eq - kCartMass * ddx) / kCartMass;
    (*f)[0] = x[1];
    (*f)[1] = dv;
    (*f)[2] = omega;
    (*f)[3] = kK * (-dv * c - kGravity * s);
    (*f)[4] = T(0.0);
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 5>&, const VecT<T, 1>&) const {
    return T(1.0);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 5>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[2] - kPi;
    (*psi)[1] = x[3];
  }
  /// Fex = 0.1, the source's start.
  Vec NominalControl() const override { return Vec::Constant(1, 0.1); }
};

/// The registry entry "cart-pendulum".
ProblemInfo CartPendulumProblemInfo();

}  // namespace ocpb
