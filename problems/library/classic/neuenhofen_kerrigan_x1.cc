#include "problems/library/classic/neuenhofen_kerrigan_x1.h"

#include <memory>

namespace ocpb {

NeuenhofenKerriganX1::NeuenhofenKerriganX1(const Parameters&) {
  SetHorizon(0.0, std::numbers::pi / 2.0);
  SetInitialState(Vec::Zero(1));
  ControlSet set;
  set.AddBox(Vec::Constant(1, -1.5), Vec::Constant(1, 1.0));
  SetControlSet(set);
}

ProblemInfo NeuenhofenKerriganX1ProblemInfo() {
  ProblemInfo p;
  p.name = "neuenhofen-kerrigan-x1";
  p.description =
      "Neuenhofen-Kerrigan X1: int y^2 + cos(t) u, y' = y^2/2 + u on [0, pi/2]; singular on the "
      "whole horizon, closed-form optimum";
  p.parameters = NeuenhofenKerriganX1::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<NeuenhofenKerriganX1>(params);
  };
  p.default_intervals = 100;
  p.reference_value = NeuenhofenKerriganX1::kReferenceCost;
  p.reference_source =
      "analytic (Neuenhofen & Kerrigan, CDC 2020, example X1; PSOPT example x1): "
      "y* = -sin t/(2 - cos t), J* = -0.256996962561";
  p.origin = "Neuenhofen & Kerrigan 2020; PSOPT example x1";
  p.hamiltonian_note = "not applicable: H is linear in u and the optimum is singular throughout";
  p.tags = {"singular-arc"};
  return p;
}

}  // namespace ocpb
