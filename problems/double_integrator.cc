#include "problems/double_integrator.h"

#include <algorithm>
#include <limits>

namespace ocpb {

std::vector<ParameterSpec> DoubleIntegrator::ParameterSpecs(double default_umax) {
  return {
      {"umax", {default_umax}, "control bound |u| <= umax (1e300: unbounded)", 0.0, 1e300, true},
      {"C", {1000.0}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
      {"x0", {-1.0, 0.0}, "initial state (position, velocity)"},
      {"xf", {0.0, 0.0}, "final state (position, velocity)"},
      {"tf", {1.0}, "final time", 0.0, 1e6, true},
  };
}

DoubleIntegrator::DoubleIntegrator(const Parameters& params, std::string name)
    : name_(std::move(name)), umax_(params.Scalar("umax")), xf_(params.Vector("xf")) {
  SetDimensions(2, 1, 2, 0);
  SetHorizon(0.0, params.Scalar("tf"));
  SetInitialState(params.Vector("x0"));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
  if (umax_ < 1e300) SetControlSet(ControlSet::Box(Vec::Constant(1, -umax_), Vec::Constant(1, umax_)));
}

void DoubleIntegrator::MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const {
  // H = p1 x2 + p2 u + u^2/2 is minimized at u = -p2, then clipped to [-umax, umax].
  u[0] = std::clamp(-p[1], -umax_, umax_);
}

}  // namespace ocpb
