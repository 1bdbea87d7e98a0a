#include "problems/reference/brachistochrone.h"

namespace ocpb {

std::vector<ParameterSpec> Brachistochrone::ParameterSpecs() {
  return ScalingParameterSpecs(1e3, 0.1, 5.0);
}

Brachistochrone::Brachistochrone(const Parameters& params) {
  // Nominal: 45 degrees down, tf about 1 s.
  InitializeScaling(params, Eigen::Vector3d::Zero(), Eigen::Vector2d(M_SQRT1_2, M_SQRT1_2), 1.0);
}

ProblemInfo BrachistochroneProblemInfo() {
  ProblemInfo p;
  p.name = "brachistochrone";
  p.description = "brachistochrone to (2, 2), min tf (time scaling, J = tf, w = (sin, cos) th)";
  p.parameters = Brachistochrone::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Brachistochrone>(params);
  };
  p.default_intervals = 100;
  p.reference_value = Brachistochrone::kReferenceTime;
  p.reference_source =
      "cycloid through (2, 2): tf* = sqrt(k/g) phi_f (project notes 2.10; Bryson & Ho 1975; "
      "PSOPT brac1: 0.8247591)";
  p.hamiltonian_note =
      "free tf by time scaling (sigma = dt/ds a control, eps Var(sigma) in J: exact), angle as "
      "unit vector w in the disc";
  p.tags = {"smooth", "free-time"};
  return p;
}

}  // namespace ocpb
