// The hanging chain of COPS 3.0 / OptimalControlProblems.jl (OCPBench problem "chain").
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = x2(1)                                   (Mayer: the potential energy)
/// subject to  x1' = u,  x2' = x1 sqrt(1 + u^2),  x3' = sqrt(1 + u^2),
///             x(0) = (a, 0, 0),  psi = (x1(1) - b, x3(1) - L) = 0,  u unbounded,
/// with a = 1, b = 3, L = 4.
///
/// The shape x1(t) of a chain of length L hanging between (0, a) and (1, b) minimizes its
/// potential energy int x1 sqrt(1 + x1'^2) dt; x3 is the length used. COPS 3.0 problem `chain`
/// (E. Dolan, J. Moré, T. Munson, ANL/MCS-TM-273, 2004, after H. H. Goldstine, "A History of
/// the Calculus of Variations", 1980) as posed by OptimalControlProblems.jl (control-toolbox;
/// JuMP model ext/JuMPModels/chain.jl, parameters ext/MetaData/chain.jl).
///
/// The optimum is the catenary x1(t) = c cosh((t - m)/c) + d, whose (c, m, d) solve the three
/// conditions x1(0) = a, x1(1) = b and c (sinh s1 - sinh s0) = L, s0 = -m/c, s1 = (1 - m)/c.
/// Then sqrt(1 + x1'^2) = cosh s and
///   J* = c^2 ((s1 - s0)/2 + (sinh 2 s1 - sinh 2 s0)/4) + d L.
/// (c, m, d) below were solved to 30 digits (mpmath findroot); the test checks the three
/// conditions at them to 1e-12. J* = 5.068480110993416.
class HangingChainOcp final : public AutoDiffOcp<HangingChainOcp, 3, 1, 2, 0> {
 public:
  static constexpr double kLeftHeight = 1.0;   // a
  static constexpr double kRightHeight = 3.0;  // b
  static constexpr double kLength = 4.0;       // L
  /// Parameters: C (terminal penalty weight, default 1e4).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit HangingChainOcp(const Parameters& params);

  std::string name() const override { return "chain"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 1>& u, VecT<T, 3>* f) const {
    const T s = sqrt(1.0 + u[0] * u[0]);
    (*f)[0] = u[0];
    (*f)[1] = x[0] * s;
    (*f)[2] = s;
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 3>& x) const {
    return x[1];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] - kRightHeight;
    (*psi)[1] = x[2] - kLength;
  }
  /// The straight segment from a to b: u = b - a.
  Vec NominalControl() const override { return Vec::Constant(1, kRightHeight - kLeftHeight); }

  /// The optimal catenary's constants (c, m, d) and its energy J* (the formula above).
  static constexpr double kCatenaryC = 0.163697529524833556;
  static constexpr double kCatenaryM = 0.410079941219703574;
  static constexpr double kCatenaryD = -0.00891243584600064864;
  static double CatenaryOptimum();
};

/// The registry entry "chain".
ProblemInfo HangingChainProblemInfo();

}  // namespace ocpb
