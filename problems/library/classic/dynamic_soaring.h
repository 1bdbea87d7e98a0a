// Dynamic soaring (OCPBench problem "dynamic-soaring"): the least wind shear on which a glider
// can fly a closed loop forever (Zhao 2004; the GPOPS-II example).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize the wind gradient beta (a static parameter: the wind is W = beta h, ft/s) for which
/// a glider flies a closed, repeatable loop: states x, y, h (ft), airspeed v (ft/s), flight path
/// angle gamma and heading psi (rad), controls lift coefficient C_L and bank angle phi (rad):
///   x' = v cos(gamma) sin(psi) + beta h,  y' = v cos(gamma) cos(psi),  h' = v sin(gamma),
///   v' = -D / m - g sin(gamma) - beta h' cos(gamma) sin(psi),
///   gamma' = (L cos(phi) - m g cos(gamma) + m beta h' sin(gamma) sin(psi)) / (m v),
///   psi' = (L sin(phi) - m beta h' cos(psi)) / (m v cos(gamma)),
///   L = q S C_L, D = q S (C_D0 + K C_L^2), q = rho v^2 / 2,
/// with g = 32.2, rho = 0.002378, m = 5.6, S = 45.09703, C_D0 = 0.00873, K = 0.045; the loop
/// starts and ends at the origin, (x, y, h)(0) = (x, y, h)(tf) = 0 (terminal constraints), with
/// v, gamma and psi free at t = 0 and periodic: v(tf) = v(0), gamma(tf) = gamma(0), psi(tf) =
/// psi(0) + 2 pi (boundary constraints); tf free in [10, 30] s. Bounds: C_L in [0, 1.5], phi
/// in [-75, 75] deg, load factor n = q S C_L / (m g) <= 5 (a path constraint; its lower bound
/// -2 of the sources cannot be active with C_L >= 0), x in [-1500, 1500], y in [-1000, 1000],
/// h in [0, 1000], v in [10, 350], gamma in [-75, 75] deg, psi in [-225, 225] deg, beta in
/// [0, 1].
///
/// Y. J. Zhao, "Optimal patterns of glider dynamic soaring", Optimal Control Applications and
/// Methods 25, 2004; the GPOPS-II example dynamicSoaring; YAPSS's example dynamic_soaring (the
/// same constants and bounds), whose test asserts beta = 0.0635869566 to 1e-5.
class DynamicSoaring final : public AutoDiffOcp<DynamicSoaring, 7, 2, 3, 1> {
 public:
  static constexpr double kGravity = 32.2;
  static constexpr double kRho = 0.002378;
  static constexpr double kMass = 5.6;
  static constexpr double kArea = 45.09703;
  static constexpr double kCd0 = 0.00873;
  static constexpr double kInducedDrag = 0.045;
  static constexpr double kMaxLoadFactor = 5.0;
  static constexpr double kReferenceGradient = 0.0635869566;
  /// Parameters: C (terminal penalty weight, 1e-2 per ft^2).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit DynamicSoaring(const Parameters& params);

  std::string name() const override { return "dynamic-soaring"; }
  /// A banked turn at the start's 150 ft/s: one loop in about 24 s.
  Vec NominalControl() const override;

  template <class T>
  void EvalDynamics(double, const VecT<T, 7>& x, const VecT<T, 2>& u, VecT<T, 7>* f) const {
    const T& h = x[2];
    const T& v = x[3];
    const T& beta = x[6];
    const T q = 0.5 * kRho * v * v;
    const T lift = q * kArea * u[0];
    const T drag = q * kArea * (kCd0 + kInducedDrag * u[0] * u[0]);
    const T cg = cos(x[4]), sg = sin(x[4]), cp = cos(x[5]), sp = sin(x[5]);
    const T h_dot = v * sg;
    const T wind_dot = beta * h_dot;
    (*f)[0] = v * cg * sp + beta * h;
    (*f)[1] = v * cg * cp;
    (*f)[2] = h_dot;
    (*f)[3] = -drag / kMass - kGravity * sg - wind_dot * cg * sp;
    (*f)[4] = (lift * cos(u[1]) - kMass * kGravity * cg + kMass * wind_dot * sg * sp) / (kMass * v);
    (*f)[5] = (lift * sin(u[1]) - kMass * wind_dot * cp) / (kMass * v * cg);
    (*f)[6] = T(0.0);
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 7>& x) const {
    return x[6];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 7>& x, VecT<T, 3>* psi) const {
    (*psi)[0] = x[0];
    (*psi)[1] = x[1];
    (*psi)[2] = x[2];
  }
  template <class T>
  void EvalBoundaryConstraints(const VecT<T, 7>& x0,
                               const VecT<T, 7>& xf,
                               VecT<T, Eigen::Dynamic>* b) const {
    (*b)[0] = xf[3] - x0[3];
    (*b)[1] = xf[4] - x0[4];
    (*b)[2] = xf[5] - x0[5];
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 7>& x, const VecT<T, 2>& u, VecT<T, 1>* c) const {
    (*c)[0] = 0.5 * kRho * kArea / (kMass * kGravity) * u[0] * x[3] * x[3] - kMaxLoadFactor;
  }
};

/// The registry entry "dynamic-soaring".
ProblemInfo DynamicSoaringProblemInfo();

}  // namespace ocpb
