#include "problems/library/classic/dynamic_soaring.h"

#include <memory>
#include <numbers>

namespace ocpb {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kStartSpeed = 150.0;
constexpr double kStartLoopTime = 24.0;

}  // namespace

std::vector<ParameterSpec> DynamicSoaring::ParameterSpecs() {
  return {{"C", {1e-2}, "terminal penalty weight (penalty form)", 0.0, 1e300, true}};
}

DynamicSoaring::DynamicSoaring(const Parameters& params) {
  SetHorizon(0.0, kStartLoopTime);
  SetFreeFinalTime(10.0, 30.0);
  Vec x0(7);
  // Heading -pi: the loop turns it to +pi, inside its bounds [-225, 225] deg, as psi(tf) =
  // psi(0) + 2 pi asks (a start at 0 would end 135 deg past the upper bound).
  x0 << 0.0, 0.0, 0.0, kStartSpeed, 0.0, -std::numbers::pi, 0.08;
  SetInitialState(x0);
  Vec lo(7), hi(7);
  lo << -1500.0, -1000.0, 0.0, 10.0, -75.0 * kDeg, -225.0 * kDeg, 0.0;
  hi << 1500.0, 1000.0, 1000.0, 350.0, 75.0 * kDeg, 225.0 * kDeg, 1.0;
  SetStateBounds(lo, hi);
  // The start's position is fixed; its speed, path angle and heading are decisions.
  Vec lo0 = lo, hi0 = hi;
  lo0.head<3>().setZero();
  hi0.head<3>().setZero();
  SetInitialStateBounds(lo0, hi0);
  SetStaticParameters(Vec::Constant(1, 0.0), Vec::Constant(1, 1.0), Vec::Constant(1, 0.08));
  Eigen::Vector3d periodic(0.0, 0.0, 2.0 * std::numbers::pi);
  SetBoundaryConstraints(periodic, periodic);
  SetControlSet(
      ControlSet::Box(Eigen::Vector2d(0.0, -75.0 * kDeg), Eigen::Vector2d(1.5, 75.0 * kDeg)));
  SetTerminalWeights(Vec::Constant(3, params.Scalar("C")));
}

Vec DynamicSoaring::NominalControl() const {
  // A level turn at the start's speed closing one loop in the start's 24 s: tan(phi) = v
  // psi' / g with psi' = 2 pi / 24, and C_L holding the weight, q S C_L cos(phi) = m g.
  const double turn_rate = 2.0 * std::numbers::pi / kStartLoopTime;
  const double bank = std::atan(kStartSpeed * turn_rate / kGravity);
  const double q = 0.5 * kRho * kStartSpeed * kStartSpeed;
  return Eigen::Vector2d(kMass * kGravity / (q * kArea * std::cos(bank)), bank);
}

ProblemInfo DynamicSoaringProblemInfo() {
  ProblemInfo p;
  p.name = "dynamic-soaring";
  p.description =
      "least wind gradient on which a glider flies a closed periodic loop: a static parameter, "
      "a free start, periodic boundary constraints, free tf (Zhao 2004)";
  p.parameters = DynamicSoaring::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<DynamicSoaring>(params);
  };
  p.default_intervals = 100;
  p.reference_value = DynamicSoaring::kReferenceGradient;
  p.reference_source =
      "YAPSS (S. R. Hall), the test of example dynamic_soaring: beta = 0.0635869566 at relative "
      "tolerance 1e-5";
  p.origin = "Zhao, Optimal Control Applications and Methods 25, 2004; GPOPS-II example";
  p.hamiltonian_note =
      "not applicable: a static parameter, a free initial state, boundary constraints and a "
      "free final time";
  p.tags = {"static-parameters",
            "free-initial-state",
            "boundary-constraints",
            "free-time",
            "mixed-constraint",
            "mayer",
            "aerospace"};
  return p;
}

}  // namespace ocpb
