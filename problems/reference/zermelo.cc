#include "problems/reference/zermelo.h"

namespace ocpb {

std::vector<ParameterSpec> Zermelo::ParameterSpecs() {
  return ScalingParameterSpecs(1e3, 0.5, 20.0);
}

Zermelo::Zermelo(const Parameters& params) {
  // Nominal: head straight for the origin, tf about the distance (|x0| = 3.9) over V = 1.
  const Eigen::Vector2d x0(3.5, -1.8);
  InitializeScaling(params, x0, -x0.normalized(), x0.norm() / kSpeed);
}

ProblemInfo ZermeloProblemInfo() {
  ProblemInfo p;
  p.name = "zermelo";
  p.description =
      "Zermelo navigation in the current -y, (3.5, -1.8) to 0, min tf (time scaling: J = tf)";
  p.parameters = Zermelo::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Zermelo>(params);
  };
  p.default_intervals = 100;
  p.reference_value = Zermelo::kReferenceTime;
  p.reference_source =
      "maximum principle, re-derived (project notes 2.11); Betts 2010 example 10.148: 5.26493205";
  p.hamiltonian_note =
      "free tf by time scaling (sigma = dt/ds a control, eps Var(sigma) in J: exact), angle as "
      "unit vector w in the disc";
  p.tags = {"smooth", "free-time"};
  return p;
}

}  // namespace ocpb
