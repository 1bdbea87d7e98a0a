// The robot arm of COPS ("robot") as a minimum-time problem (OCPBench problem "robot-arm").
#pragma once

#include <string>
#include <vector>

#include "problems/reference/scaled_free_time.h"
#include "problems/registry.h"

namespace ocpb {

/// minimize    T
/// subject to  rho'' = u_rho / L,  theta'' = u_theta / I_theta,  phi'' = u_phi / I_phi,
///             I_theta = ((L - rho)^3 + rho^3) sin(phi)^2 / 3,  I_phi = ((L - rho)^3 + rho^3) / 3,
///             (rho, theta, phi)(0) = (4.5, 0, pi/4),  (rho, theta, phi)(T) = (4.5, 2 pi/3, pi/4),
///             all rates zero at both ends,  u in [-1, 1]^3,  L = 5
/// (E. Dolan, J. Moré, T. Munson, "Benchmarking optimization software with COPS 3.0",
/// ANL/MCS-TM-273, 2004, problem `robot`). State order (rho, theta, phi, rho', theta', phi', t).
/// The optimal controls are bang-bang.
///
/// Posed with time scaling (problems/reference/scaled_free_time.h): u = (v, sigma) with
/// v = sigma (u_rho, u_theta, u_phi) in the cone |v_i| <= sigma (six path constraints), horizon
/// s in [0, 1], clock t as the last state, J = T at the optimum (sigma = T constant). COPS' state
/// bounds 0 <= rho <= L, |theta| <= pi, 0 <= phi <= pi are inactive on the optimum (measured at
/// nh = 200: rho in [3.46, 4.5], theta in [0, 2 pi/3], phi in [0.54, pi/4]) and are left out;
/// the tests check them on the solution. The penalty form weighs the six terminal residuals with C
/// (default 1e3).
///
/// Reference: COPS reports T = 9.14138 for its trapezoid scheme at nh = 200 with a constant step
/// T/nh (an optimum of that discrete problem); compare at that scheme and grid.
///
/// Hamiltonian method: through the cone-penalty reformulation (scaled_free_time.h); H is linear
/// in v apart from the penalty (bang-bang).
class RobotArm final : public ScaledFreeTimeOcp<RobotArm, 7, 3, 6, 6> {
 public:
  static constexpr double kLength = 5.0;
  static constexpr double kCopsReferenceTime = 9.14138;
  static constexpr int kCopsIntervals = 200;
  /// Parameters: C (1e3), eps (100), sigma_min (1), sigma_max (30).
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit RobotArm(const Parameters& params);

  std::string name() const override { return "robot-arm"; }

  template <class T>
  void EvalPhysical(const VecT<T, 7>& x, const VecT<T, 3>& u, VecT<T, 7>* f) const {
    const T& rho = x[0];
    const T& phi = x[2];
    const T arm = kLength - rho;
    const T i_phi = (arm * arm * arm + rho * rho * rho) / 3.0;
    const T sin_phi = sin(phi);
    const T i_theta = i_phi * sin_phi * sin_phi;
    (*f)[0] = x[3];
    (*f)[1] = x[4];
    (*f)[2] = x[5];
    (*f)[3] = u[0] / kLength;
    (*f)[4] = u[1] / i_theta;
    (*f)[5] = u[2] / i_phi;
  }
  template <class T>
  T EvalPhysicalCost(const VecT<T, 7>& x) const {
    return x[6];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 7>& x, VecT<T, 6>* psi) const {
    (*psi)[0] = x[0] - 4.5;
    (*psi)[1] = x[1] - 2.0 * M_PI / 3.0;
    (*psi)[2] = x[2] - M_PI / 4.0;
    (*psi)[3] = x[3];
    (*psi)[4] = x[4];
    (*psi)[5] = x[5];
  }
};

/// The registry entry "robot-arm".
ProblemInfo RobotArmProblemInfo();

}  // namespace ocpb
