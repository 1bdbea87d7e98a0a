#include "problems/library/classic/hypersensitive.h"

#include <cmath>
#include <memory>

namespace ocpb {

double Hypersensitive::InfiniteHorizonCost() {
  auto antiderivative = [](double w) { return (w * std::sqrt(w * w + 1.0) + std::asinh(w)) / 4.0; };
  const double leave = 2.0 * (antiderivative(1.0) - 0.25);                 // V(1)
  const double arrive = 2.0 * (antiderivative(2.25) + 2.25 * 2.25 / 4.0);  // W(1.5)
  return leave + arrive;
}

std::vector<ParameterSpec> Hypersensitive::ParameterSpecs() {
  return {
      {"tf", {10000.0}, "final time (the reference holds for tf >= 40)", 0.0, 1e6, true},
      {"C", {1000.0}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
  };
}

Hypersensitive::Hypersensitive(const Parameters& params) {
  SetHorizon(0.0, params.Scalar("tf"));
  SetInitialState(Vec::Constant(1, 1.0));
  SetTerminalWeights(Vec::Constant(1, params.Scalar("C")));
}

ProblemInfo HypersensitiveProblemInfo() {
  ProblemInfo p;
  p.name = "hypersensitive";
  p.description =
      "Rao-Mease hypersensitive problem (Betts' form): y' = -y^3 + u, 1 -> 1.5, int y^2 + u^2 "
      "over tf = 10000";
  p.parameters = Hypersensitive::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<Hypersensitive>(params);
  };
  p.default_intervals = 1000;
  p.reference_value = Hypersensitive::InfiniteHorizonCost();
  p.reference_source =
      "analytic long-horizon limit (Hamilton-Jacobi, see hypersensitive.h): J = 6.72411380988600 "
      "(any tf >= 40, error O(exp(-tf))); Betts 2010 example 10.7 reports J* = 6.7241";
  p.origin = "Betts 2010 example 10.7 (Rao & Mease); GPOPS-II and PSOPT hypersensitive examples";
  p.tags = {"stiff", "smooth"};
  return p;
}

}  // namespace ocpb
