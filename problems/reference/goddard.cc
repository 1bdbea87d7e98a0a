#include "problems/reference/goddard.h"

namespace ocpb {

std::vector<ParameterSpec> Goddard::ParameterSpecs() {
  // eps = 1e4: with T about 0.2, eps T^2 = 400 keeps sigma constant to 1e-6 relative (eps = 1:
  // 1e-2 on the trapezoid at nh = 400), so that the trapezoid transcription is COPS' scheme.
  return ScalingParameterSpecs(1e3, 1e4, 0.01, 1.0);
}

Goddard::Goddard(const Parameters& params) {
  // Nominal: full thrust until the fuel is gone, T = (1 - mf) c / Tmax = 0.057. Less thrust
  // does not lift the rocket at first (Tmax / 2 < m g + drag soon), and a start that falls below
  // h = 1 meets drag growing like exp(500 (1 - h)).
  InitializeScaling(params,
                    Eigen::Vector3d(1.0, 0.0, 1.0),
                    {0.0},
                    {kMaxThrust},
                    Vec::Constant(1, kMaxThrust),
                    (1.0 - kFinalMass) * kExhaustSpeed / kMaxThrust);
}

ProblemInfo GoddardProblemInfo() {
  ProblemInfo p;
  p.name = "goddard";
  p.description = "COPS Goddard rocket: max h(T), T free (time scaling: J = -h(T))";
  p.parameters = Goddard::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Goddard>(params);
  };
  p.default_intervals = Goddard::kCopsIntervals;
  p.reference_value = Goddard::kCopsReferenceCost;
  p.reference_source =
      "COPS 3.0 (Dolan, More, Munson 2004) rocket, trapezoid nh = 400: h(T) = 1.01283, an "
      "optimum of that discrete NLP";
  p.reference_scheme = "trapezoid";
  p.reference_intervals = Goddard::kCopsIntervals;
  p.hamiltonian_note =
      "not applicable: the method needs the penalty terminal form, and with C (m(T) - mf)^2 the "
      "rocket problem is unbounded below (burning past mf pays; the descent ran to h = 1e152)";
  p.tags = {"singular-arc", "free-time", "control-constrained", "mayer", "aerospace"};
  return p;
}

}  // namespace ocpb
