#include "problems/reference/coupled_ends.h"

#include <memory>

namespace ocpb {

std::vector<ParameterSpec> CoupledEnds::ParameterSpecs() {
  return {{"d_max", {0.8}, "upper bound of x(1) - x(0) (active for d_max < 1)", 0.0, 1.0, true}};
}

CoupledEnds::CoupledEnds(const Parameters& params) : d_max_(params.Scalar("d_max")) {
  SetHorizon(0.0, 1.0);
  SetInitialState(Vec::Zero(1));
  SetInitialStateBounds(Vec::Constant(1, -10.0), Vec::Constant(1, 10.0));
  SetBoundaryConstraints(Vec::Zero(1), Vec::Constant(1, d_max_));
}

double CoupledEnds::OptimalCost() const {
  const double x0 = OptimalInitialState(), d = d_max_;
  return 0.5 * x0 * x0 + 0.5 * d * d + 0.5 * (x0 + d - 3.0) * (x0 + d - 3.0);
}

ProblemInfo CoupledEndsProblemInfo() {
  ProblemInfo p;
  p.name = "coupled-ends";
  p.description =
      "a boundary constraint 0 <= x(1) - x(0) <= 0.8 coupling a free x(0) with x(1), active at "
      "the optimum";
  p.parameters = CoupledEnds::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<CoupledEnds>(params);
  };
  p.default_intervals = 50;
  p.reference_value = CoupledEnds(Parameters(CoupledEnds::ParameterSpecs())).OptimalCost();
  p.reference_source = "analytic J* = 1.53 (derived in problems/reference/coupled_ends.h)";
  p.hamiltonian_note =
      "not applicable: a boundary constraint b(x(t0), x(tf)) (the family's descent and polish "
      "have no rows for it; they take the free initial state alone)";
  p.reference_costate = [](double) {
    return Vec::Constant(1,
                         -CoupledEnds(Parameters(CoupledEnds::ParameterSpecs())).OptimalControl());
  };
  p.tags = {"free-initial-state", "boundary-constraints"};
  return p;
}

}  // namespace ocpb
