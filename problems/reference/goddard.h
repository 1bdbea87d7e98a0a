// The Goddard rocket of COPS ("rocket") as a free-final-time problem (OCPBench problem
// "goddard").
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "problems/reference/scaled_free_time.h"
#include "problems/registry.h"

namespace ocpb {

/// maximize    h(T)  (J = -h(T), T free)
/// subject to  h' = v,  v' = (Th - D(h, v)) / m - g(h),  m' = -Th / c,
///             D = Dc v^2 exp(-hc (h - h0) / h0),  g = g0 (h0 / h)^2,
///             (h, v, m)(0) = (1, 0, 1),  psi = m(T) - mf = 0,  0 <= Th <= Tmax,
/// with COPS' dimensionless constants h0 = m0 = g0 = 1, hc = 500, c = 0.5, mf = 0.6, Dc = 310,
/// Tmax = 3.5 (E. Dolan, J. Moré, T. Munson, "Benchmarking optimization software with COPS 3.0",
/// ANL/MCS-TM-273, 2004, problem `rocket`). The optimal thrust is bang-singular-bang: full thrust,
/// a singular arc where drag and thrust balance, then coasting with Th = 0.
///
/// Posed with time scaling (problems/reference/scaled_free_time.h): u = (v, sigma) with
/// v = sigma Th in the cone 0 <= v <= sigma Tmax (one path constraint; v >= 0 is U's bound),
/// horizon s in [0, 1], clock t as the last state, J = -h(T) at the optimum (sigma = T
/// constant). COPS' state bounds h >= 1, v >= 0, 0.6 <= m <= 1 are left out: on the optimum
/// they hold strictly after t = 0 (h and v grow under full thrust; m decreases monotonically to
/// mf since Th >= 0), where h = 1 and v = 0 are fixed initial values (a constraint active at the
/// fixed initial state is degenerate for an NLP; m >= mf as a path constraint is active along
/// the whole coasting arc and made Ipopt take 153 iterations instead of 49); the tests check
/// them on the solution. The terminal form's penalty weight C (default 1e3) acts on m(T) - mf.
///
/// Reference: COPS reports h(T) = 1.01283 for its trapezoid scheme at nh = 400 with a constant
/// step T/nh (an optimum of that discrete problem); compare at that scheme and grid.
///
/// Hamiltonian method: not applicable. It needs the penalty terminal form, and with
/// C (m(T) - mf)^2 in place of m(T) = mf the problem is unbounded below: burning past mf pays
/// (the rocket equation gives v a gain c ln(m0 / m) without bound as m -> 0, and a negative m
/// turns thrust and drag around). Measured with the cone-penalty reformulation of
/// scaled_free_time.h: at eps = 1 the descent ran to h = 1e152; at eps = 1e4 and 0.01 it stayed
/// near the nominal h = 1.004-1.007 after 2000 iterations. HamiltonianReformulation() is
/// therefore nullptr and the method reports not_applicable.
class Goddard final : public ScaledFreeTimeOcp<Goddard, 4, 1, 1, 1> {
 public:
  static constexpr double kDragHeightScale = 500.0;  // hc
  static constexpr double kExhaustSpeed = 0.5;       // c
  static constexpr double kFinalMass = 0.6;          // mf
  static constexpr double kDragCoefficient = 310.0;  // Dc
  static constexpr double kMaxThrust = 3.5;          // Tmax
  static constexpr double kCopsReferenceCost = -1.01283;
  static constexpr int kCopsIntervals = 400;
  /// Parameters: C (1e3), eps (1e4), sigma_min (0.01), sigma_max (1).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit Goddard(const Parameters& params);

  std::string name() const override { return "goddard"; }

  template <class T>
  void EvalPhysical(const VecT<T, 4>& x, const VecT<T, 1>& u, VecT<T, 4>* f) const {
    const T& h = x[0];
    const T& v = x[1];
    const T& m = x[2];
    const T drag = kDragCoefficient * v * v * exp(-kDragHeightScale * (h - 1.0));
    const T gravity = 1.0 / (h * h);
    (*f)[0] = v;
    (*f)[1] = (u[0] - drag) / m - gravity;
    (*f)[2] = -u[0] / kExhaustSpeed;
  }
  template <class T>
  T EvalPhysicalCost(const VecT<T, 4>& x) const {
    return -x[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 4>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[2] - kFinalMass;
  }
  /// None: the Hamiltonian method is not applicable here (see above).
  std::unique_ptr<Ocp> HamiltonianReformulation(
      const HamiltonianReformulationOptions&) const override {
    return nullptr;
  }
};

/// The registry entry "goddard".
ProblemInfo GoddardProblemInfo();

}  // namespace ocpb
