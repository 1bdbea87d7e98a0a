// Tumor anti-angiogenesis (Ledzewicz and Schaettler) in Betts' form (OCPBench problem
// "tumor-antiangiogenesis").
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    J = p(T)                      over u and the final time T (free),
/// subject to  p' = -xi p ln(p / q),
///             q' = q (b - (mu + d p^(2/3) + G u)),
///             y' = u,
///             (p, q, y)(0) = (pbar / 2, qbar / 4, 0),  0 <= u <= a,
///             0.01 <= p <= pbar,  0.01 <= q <= qbar,  0 <= y <= A     (state bounds),
/// with xi = 0.084, G = 0.15, b = 5.85, mu = 0.02, d = 0.00873, a = 75, A = 15 and
/// pbar = qbar = ((b - mu) / d)^(3/2). p is the tumour volume, q the carrying capacity of the
/// vasculature, u the angiogenic inhibitor dose rate and y the total dose used (A = 15 available).
/// J. T. Betts, "Practical Methods for Optimal Control and Estimation Using Nonlinear
/// Programming", 2nd ed., SIAM 2010, example 10.141 (section 8.17; after U. Ledzewicz and
/// H. Schaettler): J* = 7571.6712 at T* = 1.1961336. The GPOPS-II paper (Patterson and Rao, ACM
/// TOMS 2014) solves the same problem (p(T) = 7571.67158). The optimal dose is bang-singular-bang:
/// u = a, a singular arc, then u = 0; the whole supply is used (y(T) = A: the bound is active at
/// the end).
///
/// Hamiltonian method: not applicable (free final time, state bounds, H linear in u).
class TumorAntiangiogenesis final : public AutoDiffOcp<TumorAntiangiogenesis, 3, 1, 0, 0> {
 public:
  static constexpr double kXi = 0.084;
  static constexpr double kG = 0.15;
  static constexpr double kB = 5.85;
  static constexpr double kMu = 0.02;
  static constexpr double kD = 0.00873;
  static constexpr double kMaxDose = 75.0;    // a
  static constexpr double kTotalDose = 15.0;  // A
  static constexpr double kReferenceCost = 7571.6712;
  static constexpr double kReferenceTime = 1.1961336;
  /// pbar = qbar.
  static double Capacity() { return std::pow((kB - kMu) / kD, 1.5); }
  /// Parameters: tf (nominal final time, 1), tf_min (0.01), tf_max (5).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit TumorAntiangiogenesis(const Parameters& params);

  std::string name() const override { return "tumor-antiangiogenesis"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 1>& u, VecT<T, 3>* f) const {
    const T& p = x[0];
    const T& q = x[1];
    (*f)[0] = -kXi * p * log(p / q);
    (*f)[1] = q * (kB - (kMu + kD * pow(p, 2.0 / 3.0) + kG * u[0]));
    (*f)[2] = u[0];
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 3>& x) const {
    return x[0];
  }
  /// u = A / T at the nominal T: spreads the whole supply over the horizon.
  Vec NominalControl() const override { return Vec::Constant(1, nominal_dose_); }

 private:
  double nominal_dose_ = 15.0;
};

/// The registry entry "tumor-antiangiogenesis".
ProblemInfo TumorAntiangiogenesisProblemInfo();

}  // namespace ocpb
