// The space shuttle reentry of Betts (2010) as posed by OptimalControlProblems.jl
// ("space_shuttle", after the JuMP tutorial, without the heating limit): OCPBench problem
// "space-shuttle".
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/parameters.h"
#include "problems/registry.h"

namespace ocpb {

/// maximize    theta(T)  (J = -theta(T), T free in [1750, 2250] s)
/// over the state (h, phi, theta, v, gamma, psi) with h in 1e5 ft and v in 1e4 ft/s (the
/// source's scaled_h and scaled_v) and the controls (alpha, beta) in rad:
///   h' = v sin(gamma) / 10,                      (in 1e5 ft / s, V = 1e4 v ft/s, H = 1e5 h ft)
///   phi' = V / r cos(gamma) sin(psi) / cos(theta),
///   theta' = V / r cos(gamma) cos(psi),
///   v' = (-D / m - g sin(gamma)) / 1e4,
///   gamma' = L / (m V) cos(beta) + cos(gamma) (V / r - g / V),
///   psi' = L sin(beta) / (m V cos(gamma)) + V / (r cos(theta)) cos(gamma) sin(psi) sin(theta),
/// with r = Re + H, g = mu / r^2, rho = rho0 exp(-H / hr), D = cD S rho V^2 / 2,
/// L = cL S rho V^2 / 2, cL = a0 + a1 a, cD = b0 + b1 a + b2 a^2, a = alpha in degrees,
/// m = 203000 / 32.174 slug, rho0 = 0.002378, hr = 23800, Re = 20902900, mu = 0.14076539e17,
/// S = 2690, a0 = -0.20704, a1 = 0.029244, b0 = 0.07854, b1 = -0.61592e-2, b2 = 0.621408e-3;
/// (h, phi, theta, v, gamma, psi)(0) = (2.6, 0, 0, 2.56, -1 deg, 90 deg),
/// (h, v, gamma)(T) = (0.8, 0.25, -5 deg) (psi), state bounds h >= 0, |phi| <= 2 pi,
/// |theta| <= 89 deg, v >= 1e-4, |gamma| <= 89 deg, |psi| <= 2 pi, and
/// -90 deg <= alpha <= 90 deg, -89 deg <= beta <= 1 deg (Betts 2010, example 6.1, without the
/// heating constraint; OptimalControlProblems.jl's JuMP model `space_shuttle`).
class SpaceShuttle final : public AutoDiffOcp<SpaceShuttle, 6, 2, 3, 0> {
 public:
  static constexpr double kMass = 203000.0 / 32.174;
  static constexpr double kRho0 = 0.002378;
  static constexpr double kHr = 23800.0;
  static constexpr double kRe = 20902900.0;
  static constexpr double kMu = 0.14076539e17;
  static constexpr double kArea = 2690.0;
  static constexpr double kA0 = -0.20704;
  static constexpr double kA1 = 0.029244;
  static constexpr double kB0 = 0.07854;
  static constexpr double kB1 = -0.61592e-2;
  static constexpr double kB2 = 0.621408e-3;
  static constexpr double kDeg = 3.14159265358979323846 / 180.0;
  static std::vector<ParameterSpec> ParameterSpecs();
  explicit SpaceShuttle(const Parameters& params);

  std::string name() const override { return "space-shuttle"; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 6>& x, const VecT<T, 2>& u, VecT<T, 6>* f) const {
    const T H = 1e5 * x[0];
    const T& theta = x[2];
    const T V = 1e4 * x[3];
    const T& gamma = x[4];
    const T& psi = x[5];
    const T a = u[0] / kDeg;
    const T cl = kA0 + kA1 * a;
    const T cd = kB0 + kB1 * a + kB2 * a * a;
    const T rho = kRho0 * exp(-H / kHr);
    const T drag = 0.5 * cd * kArea * rho * V * V;
    const T lift = 0.5 * cl * kArea * rho * V * V;
    const T r = kRe + H;
    const T g = kMu / (r * r);
    (*f)[0] = V * sin(gamma) / 1e5;
    (*f)[1] = (V / r) * cos(gamma) * sin(psi) / cos(theta);
    (*f)[2] = (V / r) * cos(gamma) * cos(psi);
    (*f)[3] = (-(drag / kMass) - g * sin(gamma)) / 1e4;
    (*f)[4] = (lift / (kMass * V)) * cos(u[1]) + cos(gamma) * ((V / r) - (g / V));
    (*f)[5] = (1.0 / (kMass * V * cos(gamma))) * lift * sin(u[1]) +
              (V / (r * cos(theta))) * cos(gamma) * sin(psi) * sin(theta);
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 6>& x) const {
    return -x[2];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 6>& x, VecT<T, 3>* psi) const {
    (*psi)[0] = x[0] - 0.8;
    (*psi)[1] = x[3] - 0.25;
    (*psi)[2] = x[4] + 5.0 * kDeg;
  }
};

/// The registry entry "space-shuttle".
ProblemInfo SpaceShuttleProblemInfo();

}  // namespace ocpb
