#include "problems/reference/launch_vehicle.h"

#include <Eigen/Geometry>
#include <array>
#include <numbers>
#include <utility>
#include <vector>

namespace ocpb {
namespace {

using Constants = LaunchVehicleConstants;
constexpr double kDegree = std::numbers::pi / 180.0;

// The target orbit's unit angular momentum, periapsis direction P and h x P.
struct OrbitFrame {
  Eigen::Vector3d h_unit, periapsis, normal;
};

OrbitFrame TargetOrbitFrame() {
  const double i = Constants::kInclinationDeg * kDegree;
  const double node = Constants::kNodeDeg * kDegree;
  const double w = Constants::kPeriapsisDeg * kDegree;
  OrbitFrame frame;
  frame.h_unit =
      Eigen::Vector3d(std::sin(i) * std::sin(node), -std::sin(i) * std::cos(node), std::cos(i));
  frame.periapsis =
      Eigen::Vector3d(std::cos(node) * std::cos(w) - std::sin(node) * std::sin(w) * std::cos(i),
                      std::sin(node) * std::cos(w) + std::cos(node) * std::sin(w) * std::cos(i),
                      std::sin(w) * std::sin(i));
  frame.normal = frame.h_unit.cross(frame.periapsis);
  return frame;
}

// The engines of each phase: thrust (N) and mass flow (kg/s). Each engine burns its propellant
// at a constant rate over its burn time (what Isp = T / (g0 mdot) states).
struct Engines {
  double thrust = 0.0;
  double mass_flow = 0.0;
};

Engines Burning(int boosters, bool stage1, bool stage2) {
  Engines e;
  auto add = [&e](int count, double thrust, double propellant, double burn_time) {
    e.thrust += count * thrust;
    e.mass_flow += count * propellant / burn_time;
  };
  add(boosters, Constants::kBoosterThrust, Constants::kBoosterPropellant, Constants::kPhaseEnds[0]);
  if (stage1) {
    add(1, Constants::kStage1Thrust, Constants::kStage1Propellant, Constants::kPhaseEnds[2]);
  }
  if (stage2) {
    add(1, Constants::kStage2Thrust, Constants::kStage2Propellant, Constants::kStage2BurnTime);
  }
  return e;
}

// A thrust direction `elevation` above the local horizontal, in the target orbit's plane
// (downrange), at position r.
Vec DirectionAt(const Eigen::Vector3d& r, double elevation) {
  const Eigen::Vector3d up = r.normalized();
  const Eigen::Vector3d downrange = TargetOrbitFrame().h_unit.cross(up).normalized();
  const Eigen::Vector3d d = std::cos(elevation) * downrange + std::sin(elevation) * up;
  return Vec(d);
}

// RK4 over a phase's nominal duration under its nominal control: where the next phase starts.
template <class Phase>
Vec SimulatedEnd(const Phase& phase) {
  const int steps = 400;
  const double h = (phase.tf() - phase.t0()) / steps;
  const Vec u = phase.NominalControl();
  Vec x = phase.x0();
  Vec k1(7), k2(7), k3(7), k4(7);
  for (int s = 0; s < steps; ++s) {
    phase.Dynamics(0.0, x, u, k1);
    phase.Dynamics(0.0, x + 0.5 * h * k1, u, k2);
    phase.Dynamics(0.0, x + 0.5 * h * k2, u, k3);
    phase.Dynamics(0.0, x + h * k3, u, k4);
    x += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  }
  return x;
}

}  // namespace

template <bool kFinal>
LaunchVehiclePhase<kFinal>::LaunchVehiclePhase(std::string name,
                                               double thrust,
                                               double mass_flow,
                                               double duration,
                                               const Vec& x0,
                                               const Vec& nominal_direction)
    : name_(std::move(name)), nominal_direction_(nominal_direction) {
  const double time_unit = TimeUnit();
  omega_ = kOmegaEarth * time_unit;
  drag_ = 0.5 * kDragCoefficient * kArea * kRho0 * SpeedUnit() * SpeedUnit() /
          (kMassUnit * AccelerationUnit());
  density_decay_ = kRe / kScaleHeight;
  thrust_ = thrust / (kMassUnit * AccelerationUnit());
  mass_flow_ = mass_flow * time_unit / kMassUnit;
  const OrbitFrame frame = TargetOrbitFrame();
  const double a = kSemiMajorAxis / kRe;
  const double h = std::sqrt(a * (1.0 - kEccentricity * kEccentricity));
  for (int i = 0; i < 3; ++i) {
    h_target_[i] = h * frame.h_unit[i];
    periapsis_[i] = frame.periapsis[i];
    normal_[i] = frame.normal[i];
  }
  this->SetHorizon(0.0, duration / time_unit);
  this->SetInitialState(x0);
  this->SetControlSet(ControlSet::Box(Vec::Constant(3, -1.0), Vec::Constant(3, 1.0)));
  if constexpr (kFinal) this->SetTerminalWeights(Vec::Constant(5, 1e3));
}

// The constructor is defined here, not in the header: the two phase kinds are made here.
template class LaunchVehiclePhase<false>;
template class LaunchVehiclePhase<true>;

std::unique_ptr<MultiPhaseOcp> MakeLaunchVehicle() {
  const double time_unit = Constants::TimeUnit();
  const double lat = Constants::kLatitudeDeg * kDegree;
  const Eigen::Vector3d r0(std::cos(lat), 0.0, std::sin(lat));
  const double omega = Constants::kOmegaEarth * time_unit;
  const Eigen::Vector3d v0 = Eigen::Vector3d(0.0, 0.0, omega).cross(r0);
  const double casing = Constants::kBoosterMass - Constants::kBoosterPropellant;
  const double m0 = Constants::kBoosters * Constants::kBoosterMass + Constants::kStage1Mass +
                    Constants::kStage2Mass + Constants::kPayload;
  const std::array<Engines, 4> engines = {Burning(6, true, false),
                                          Burning(3, true, false),
                                          Burning(0, true, false),
                                          Burning(0, false, true)};
  const std::array<double, 4> durations = {Constants::kPhaseEnds[0],
                                           Constants::kPhaseEnds[1] - Constants::kPhaseEnds[0],
                                           Constants::kPhaseEnds[2] - Constants::kPhaseEnds[1],
                                           Constants::kStage2BurnTime};
  // Mass dropped after phases 1-3 (tonnes): six casings, three casings, stage 1's dry mass.
  const std::array<double, 3> dropped = {
      6.0 * casing / Constants::kMassUnit,
      3.0 * casing / Constants::kMassUnit,
      (Constants::kStage1Mass - Constants::kStage1Propellant) / Constants::kMassUnit};
  // The start: a pitch programme of one constant direction per phase, from steep to level.
  const std::array<double, 4> elevation = {80.0 * kDegree, 45.0 * kDegree, 20.0 * kDegree, 0.0};
  const char* names[4] = {"boosters-6", "boosters-3", "stage-1", "stage-2"};

  std::vector<PhaseSpec> phases;
  Vec x(7);
  x << r0, v0, m0 / Constants::kMassUnit;
  for (int k = 0; k < 4; ++k) {
    const Vec direction = DirectionAt(x.head<3>(), elevation[k]);
    if (k < 3) {
      auto phase = std::make_shared<LaunchVehiclePhase<false>>(
          names[k], engines[k].thrust, engines[k].mass_flow, durations[k], x, direction);
      x = SimulatedEnd(*phase);
      x[6] -= dropped[k];
      const double d = durations[k] / time_unit;
      phases.push_back({phase, d, d});
    } else {
      // Stage 2 starts from a nominal 600 s burn; it may burn 1 s to all its 700 s.
      auto phase = std::make_shared<LaunchVehiclePhase<true>>(
          names[k], engines[k].thrust, engines[k].mass_flow, 600.0, x, direction);
      phases.push_back({phase, 1.0 / time_unit, durations[k] / time_unit});
    }
  }
  Vec jump(7);
  std::vector<std::vector<PhaseLink>> links;
  for (int k = 0; k < 3; ++k) {
    jump.setZero();
    jump[6] = -dropped[k];
    links.push_back(MultiPhaseOcp::Continuity(7, jump));
  }
  return std::make_unique<MultiPhaseOcp>("launch-vehicle", std::move(phases), std::move(links));
}

ProblemInfo LaunchVehicleProblemInfo() {
  ProblemInfo p;
  p.name = "launch-vehicle";
  p.description =
      "multiple-stage launch vehicle to a geosynchronous transfer orbit, max delivered mass: four "
      "phases with dropped masses, stage 2's burn free (GPOPS-II example, Benson 2004)";
  p.make = [](const Parameters&, std::uint64_t) -> std::unique_ptr<Ocp> {
    return MakeLaunchVehicle();
  };
  p.default_intervals = 20;
  p.reference_value = -LaunchVehicleConstants::kReferenceFinalMass / Constants::kMassUnit;
  p.reference_source =
      "YAPSS (S. R. Hall), the test of example delta_iii_ascent: J = -7529.712287 kg at relative "
      "tolerance 1e-8 (here in tonnes)";
  p.origin =
      "GPOPS-II and PSOPT examples 'launch' (Delta III ascent), after D. A. Benson, PhD thesis, "
      "MIT, 2004";
  p.hamiltonian_note =
      "not applicable: several phases, and a path constraint on the thrust direction";
  p.tags = {"multi-phase", "free-time", "mayer", "aerospace"};
  return p;
}

}  // namespace ocpb
