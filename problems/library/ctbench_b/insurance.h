// The insurance problem of BOCOP / OptimalControlProblems.jl (OCPBench problem "insurance").
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// maximize    int_0^10 U fx dt   (J = -int_0^10 U fx dt)
/// subject to  I' = (1 - gamma t v'(m) / dUdR) h,  m' = h,  x3' = (1 + sigma) I fx,
///             R = w - P + I - m - eps(t),  H = h0 - gamma t (1 - v(m)),
///             U = 1 - exp(-s R) + H,  dUdR = s exp(-s R),
///             v(m) = m^(alpha/2) / (1 + m^(alpha/2)),  fx(t) = lambda exp(-lambda t) +
///             exp(-lambda tf) / tf,  eps(t) = k t / (tf - t + 1),
///             (I, m, x3)(0) = (0, 0.001, 0),  P = x3(10)  (P a static parameter, P >= 0),
///             0 <= h <= 25,  0 <= I <= 1.5,  0 <= m <= 1.5,
///             R >= 0,  H >= 0,  U >= 0,  dUdR >= 0.001   (path constraints),
/// with gamma = 0.2, lambda = 0.25, h0 = 1.5, w = 1, s = 10, k = 0, sigma = 0, alpha = 4.
///
/// The problem "insurance" of OptimalControlProblems.jl (control-toolbox; JuMP model
/// ext/JuMPModels/insurance.jl), after the BOCOP example (an optimal insurance contract: the
/// insured's indemnity I and medical expense m over a loss size t, premium P). The JuMP model
/// carries R, H, U, dUdR as extra control variables tied by equality constraints at every node;
/// here they are the functions of (t, x, P) those equalities define, which gives the same
/// discrete NLP once the equalities are eliminated. With alpha = 4, v = m^2 / (1 + m^2) and
/// v' = 2 m / (1 + m^2)^2. State: x = (I, m, x3, P), P static.
class InsuranceOcp final : public AutoDiffOcp<InsuranceOcp, 4, 1, 1, 4> {
 public:
  static constexpr double kGamma = 0.2;
  static constexpr double kLambda = 0.25;
  static constexpr double kH0 = 1.5;
  static constexpr double kW = 1.0;
  static constexpr double kS = 10.0;
  static constexpr double kK = 0.0;
  static constexpr double kSigma = 0.0;
  static constexpr double kFinalTime = 10.0;
  static constexpr double kStateUpper = 1.5;
  static constexpr double kControlUpper = 25.0;
  static constexpr double kMarginalUtilityLower = 0.001;
  /// Parameters: C (terminal penalty weight, default 1e4).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit InsuranceOcp(const Parameters& params);

  std::string name() const override { return "insurance"; }

  static double Density(double t) {
    return kLambda * std::exp(-kLambda * t) + std::exp(-kLambda * kFinalTime) / kFinalTime;
  }
  static double Epsilon(double t) { return kK * t / (kFinalTime - t + 1.0); }
  template <class T>
  static T Wealth(double t, const VecT<T, 4>& x) {  // R
    return kW - x[3] + x[0] - x[1] - Epsilon(t);
  }
  template <class T>
  static T Health(double t, const VecT<T, 4>& x) {  // H
    const T m2 = x[1] * x[1];
    return kH0 - kGamma * t * (1.0 - m2 / (1.0 + m2));
  }

  template <class T>
  void EvalDynamics(double t, const VecT<T, 4>& x, const VecT<T, 1>& u, VecT<T, 4>* f) const {
    const T m2 = x[1] * x[1];
    const T vprime = 2.0 * x[1] / ((1.0 + m2) * (1.0 + m2));
    const T dudr = kS * exp(-kS * Wealth(t, x));
    (*f)[0] = (1.0 - kGamma * t * vprime / dudr) * u[0];
    (*f)[1] = u[0];
    (*f)[2] = (1.0 + kSigma) * x[0] * Density(t);
    (*f)[3] = T(0.0);
  }
  template <class T>
  T EvalRunningCost(double t, const VecT<T, 4>& x, const VecT<T, 1>&) const {
    const T utility = 1.0 - exp(-kS * Wealth(t, x)) + Health(t, x);
    return -utility * Density(t);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 4>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[3] - x[2];
  }
  template <class T>
  void EvalPathConstraints(double t, const VecT<T, 4>& x, const VecT<T, 1>&, VecT<T, 4>* c) const {
    const T r = Wealth(t, x);
    const T h = Health(t, x);
    (*c)[0] = -r;
    (*c)[1] = -h;
    (*c)[2] = -(1.0 - exp(-kS * r) + h);
    (*c)[3] = kMarginalUtilityLower - kS * exp(-kS * r);
  }
  /// The JuMP model's start h = 0.1.
  Vec NominalControl() const override { return Vec::Constant(1, 0.1); }
};

/// The registry entry "insurance".
ProblemInfo InsuranceProblemInfo();

}  // namespace ocpb
