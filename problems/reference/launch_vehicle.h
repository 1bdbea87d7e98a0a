// The multiple-stage launch vehicle of Benson (2004) as posed in the GPOPS-II examples (OCPBench
// problem "launch-vehicle"): four phases with dropped masses, a reference for MultiPhaseOcp.
#pragma once

#include <cmath>
#include <memory>
#include <numbers>
#include <string>

#include "core/autodiff_ocp.h"
#include "core/multi_phase_ocp.h"
#include "problems/registry.h"

namespace ocpb {

/// A Delta III-like rocket climbs from Cape Canaveral (latitude 28.5 deg) into a geosynchronous
/// transfer orbit, maximizing the mass it delivers (J = -m(tF)). States: position r and velocity
/// v in an Earth-centred inertial frame, and the mass m; control: the thrust direction u, |u| = 1.
///
///   r' = v,  v' = -mu r / |r|^3 + (T_i u + D) / m,  m' = -mdot_i,
///   D = -1/2 C_D S rho |v_rel| v_rel,  v_rel = v - omega_E x r,  rho = rho0 exp(-(|r| - Re) / H),
///
/// four phases, joined with r and v continuous and the dry mass of what burnt out dropped:
///   1. 6 solid boosters and stage 1, 75.2 s;    drop 6 booster casings (6 x 2280 kg)
///   2. 3 solid boosters and stage 1, 75.2 s;    drop 3 booster casings (3 x 2280 kg)
///   3. stage 1 alone, 110.6 s (to t = 261 s);   drop stage 1's dry mass (8830 kg)
///   4. stage 2 with the payload, a free duration of at most 700 s (its burn time),
/// each T_i and mdot_i summed over the engines burning; an engine burns its propellant at a
/// constant rate over its burn time (boosters 75.2 s, stage 1 261 s, stage 2 700 s; the Isp
/// this implies, T / (g0 mdot) = 283.33364, 301.68776 and 467.21311 s, is the sources'). At tF the
/// orbit has a = 24361.14 km, e = 0.7308, i = 28.5 deg, Omega = 269.8 deg, omega = 130.5 deg (the
/// true anomaly is free), written smoothly as 5 conditions: the angular momentum r x v equals the
/// target orbit's (3: p = a (1 - e^2), i, Omega), and the eccentricity vector (v x h) / mu -
/// r / |r| has the target's components along its periapsis direction P (= e) and along h x P
/// (= 0) (2: e, omega).
///
/// Constants: mu = 3.986012e14 m^3/s^2, Re = 6378145 m, omega_E = 7.29211585e-5 rad/s,
/// rho0 = 1.225 kg/m^3, H = 7200 m, C_D = 0.5, S = 4 pi m^2; booster: 19290 kg (17010
/// propellant), 628500 N; stage 1: 104380 kg (95550), 1083100 N; stage 2: 19300 kg (16820),
/// 110094 N; payload 4164 kg; nine boosters at lift-off: m(0) = 301454 kg.
///
/// Units, so that every quantity is of order one: length Re, time sqrt(Re^3 / mu) (806.8 s),
/// speed sqrt(mu / Re), mass 1000 kg (so J is minus the delivered mass in tonnes). Control
/// |u| = 1 is posed as |u|^2 <= 1 with u in [-1, 1]^3: thrust is fixed in every phase, and a
/// shorter u would spend the same propellant for less impulse, so the bound is active at the
/// optimum (a test checks it on a solution).
///
/// The problem of GPOPS-II's example "launch" and PSOPT's example "launch" (after D. A. Benson's
/// PhD thesis, MIT, 2004); both pose |u|^2 = 1 as an equality path constraint.
///
/// Reference: m(tF) = 7529.712287 kg, the converged value YAPSS's test of its example
/// delta_iii_ascent asserts to 1e-8 relative (S. R. Hall, YAPSS, github.com/stevenrhall/yapss,
/// tests of src/yapss/examples/delta_iii_ascent.py); PSOPT prints -7.529661e+03 and tF =
/// 924.1413 s for its coarse pseudospectral grid (examples/launch/launch.txt).
struct LaunchVehicleConstants {
  static constexpr double kMu = 3.986012e14;
  static constexpr double kRe = 6378145.0;
  static constexpr double kOmegaEarth = 7.29211585e-5;
  static constexpr double kRho0 = 1.225;
  static constexpr double kScaleHeight = 7200.0;
  static constexpr double kDragCoefficient = 0.5;
  static constexpr double kArea = 4.0 * std::numbers::pi;
  static constexpr double kLatitudeDeg = 28.5;

  static constexpr double kBoosterMass = 19290.0, kBoosterPropellant = 17010.0;
  static constexpr double kBoosterThrust = 628500.0;
  static constexpr double kStage1Mass = 104380.0, kStage1Propellant = 95550.0;
  static constexpr double kStage1Thrust = 1083100.0;
  static constexpr double kStage2Mass = 19300.0, kStage2Propellant = 16820.0;
  static constexpr double kStage2Thrust = 110094.0;
  static constexpr double kPayload = 4164.0;
  static constexpr int kBoosters = 9;
  /// The phases' ends in seconds: boosters 1-6 burn out, boosters 7-9, stage 1; stage 2 burns
  /// at most 700 s.
  static constexpr double kPhaseEnds[3] = {75.2, 150.4, 261.0};
  static constexpr double kStage2BurnTime = 700.0;

  static constexpr double kSemiMajorAxis = 24361140.0;  // m
  static constexpr double kEccentricity = 0.7308;
  static constexpr double kInclinationDeg = 28.5;
  static constexpr double kNodeDeg = 269.8;
  static constexpr double kPeriapsisDeg = 130.5;

  static constexpr double kReferenceFinalMass = 7529.712287;  // kg

  // Units.
  static double TimeUnit() { return std::sqrt(kRe * kRe * kRe / kMu); }
  static double SpeedUnit() { return std::sqrt(kMu / kRe); }
  static double AccelerationUnit() { return kMu / (kRe * kRe); }
  static constexpr double kMassUnit = 1000.0;
};

/// One phase: thrust `thrust` (N) and mass flow `mass_flow` (kg/s) of the engines burning;
/// kFinal: the last phase, with the orbit conditions and the cost -m at its end.
template <bool kFinal>
class LaunchVehiclePhase final
    : public AutoDiffOcp<LaunchVehiclePhase<kFinal>, 7, 3, kFinal ? 5 : 0, 1>,
      private LaunchVehicleConstants {
 public:
  /// `name`, the engines' thrust (N) and mass flow (kg/s), the nominal duration (s), the start
  /// state in scaled units (a guess for phases after the first), and the constant thrust
  /// direction methods start from.
  LaunchVehiclePhase(std::string name,
                     double thrust,
                     double mass_flow,
                     double duration,
                     const Vec& x0,
                     const Vec& nominal_direction);

  std::string name() const override { return name_; }
  Vec NominalControl() const override { return nominal_direction_; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 7>& x, const VecT<T, 3>& u, VecT<T, 7>* f) const {
    const T rr = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
    const T r = sqrt(rr);
    const T gravity = 1.0 / (rr * r);
    // The air moves with the Earth: v_rel = v - w x r, w = (0, 0, omega).
    const T wx = x[3] + omega_ * x[1];
    const T wy = x[4] - omega_ * x[0];
    const T wz = x[5];
    // |v_rel|, smoothed by 1e-8 (1e-4 m/s) so that its derivatives are finite at lift-off,
    // where the rocket rests in the air (v_rel = 0).
    const T speed = sqrt(wx * wx + wy * wy + wz * wz + 1e-16);
    const T drag = drag_ * exp(-(r - 1.0) * density_decay_) * speed / x[6];
    const T thrust = thrust_ / x[6];
    for (int i = 0; i < 3; ++i) (*f)[i] = x[3 + i];
    (*f)[3] = -gravity * x[0] + thrust * u[0] - drag * wx;
    (*f)[4] = -gravity * x[1] + thrust * u[1] - drag * wy;
    (*f)[5] = -gravity * x[2] + thrust * u[2] - drag * wz;
    (*f)[6] = T(-mass_flow_);
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 7>&, const VecT<T, 3>& u, VecT<T, 1>* c) const {
    (*c)[0] = u[0] * u[0] + u[1] * u[1] + u[2] * u[2] - 1.0;
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 7>& x) const {
    if constexpr (kFinal) return -x[6];
    return T(0.0);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 7>& x, VecT<T, kFinal ? 5 : 0>* psi) const {
    if constexpr (kFinal) {
      const T hx = x[1] * x[5] - x[2] * x[4];
      const T hy = x[2] * x[3] - x[0] * x[5];
      const T hz = x[0] * x[4] - x[1] * x[3];
      const T r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
      // e = v x h - r / |r| (mu = 1 in these units).
      const T ex = x[4] * hz - x[5] * hy - x[0] / r;
      const T ey = x[5] * hx - x[3] * hz - x[1] / r;
      const T ez = x[3] * hy - x[4] * hx - x[2] / r;
      (*psi)[0] = hx - h_target_[0];
      (*psi)[1] = hy - h_target_[1];
      (*psi)[2] = hz - h_target_[2];
      (*psi)[3] = ex * periapsis_[0] + ey * periapsis_[1] + ez * periapsis_[2] - kEccentricity;
      (*psi)[4] = ex * normal_[0] + ey * normal_[1] + ez * normal_[2];
    }
  }

 private:
  std::string name_;
  Vec nominal_direction_;
  double omega_ = 0.0;          // Earth's rate in scaled units
  double drag_ = 0.0;           // 1/2 C_D S rho0 (scaled), per unit mass
  double density_decay_ = 0.0;  // Re / H
  double thrust_ = 0.0;         // scaled
  double mass_flow_ = 0.0;      // scaled
  double h_target_[3] = {0.0, 0.0, 0.0};
  double periapsis_[3] = {0.0, 0.0, 0.0};
  double normal_[3] = {0.0, 0.0, 0.0};  // h x P, unit
};

/// The four phases with their links, started from a simulated ascent (each phase's start is
/// the end of the previous one's simulation under its nominal thrust direction, so the first
/// iterate is continuous and only the orbit conditions are off).
std::unique_ptr<MultiPhaseOcp> MakeLaunchVehicle();

/// The registry entry "launch-vehicle".
ProblemInfo LaunchVehicleProblemInfo();

}  // namespace ocpb
