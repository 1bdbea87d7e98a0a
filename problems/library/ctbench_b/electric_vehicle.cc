#include "problems/library/ctbench_b/electric_vehicle.h"

#include <memory>

namespace ocpb {

std::vector<ParameterSpec> ElectricVehicleOcp::ParameterSpecs() {
  return {
      {"C", {1e4}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
  };
}

ElectricVehicleOcp::ElectricVehicleOcp(const Parameters& params) {
  SetHorizon(0.0, 1.0);
  SetInitialState(Eigen::Vector2d(0.0, 0.0));
  SetTerminalWeights(Vec::Constant(2, params.Scalar("C")));
}

ProblemInfo ElectricVehicleProblemInfo() {
  ProblemInfo p;
  p.name = "electric-vehicle";
  p.description =
      "electric vehicle (Petit & Sciarretta 2011, OptimalControlProblems.jl): min int u v + u^2 "
      "over 10 units of a sloped road in unit time";
  p.parameters = ElectricVehicleOcp::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<ElectricVehicleOcp>(params);
  };
  p.default_intervals = 200;
  p.reference_value = 1228.580289886;
  p.reference_source =
      "computed by OCPBench (no published continuous value): ocpbench solve --problem "
      "electric-vehicle --solver ipopt --transcription hermite-simpson --terminal hard --option "
      "tol=1e-12 --N 100/200/400/800 gives 1228.5802932537, 1228.5802900963, 1228.5802898990, "
      "1228.5802898866 (fourth order; Richardson 1228.5802898858), LGR N = 100: 1228.5802898846; "
      "CTBenchmarks' trapezoid values 1228.69888 (N = 200) ... 1228.58148 (N = 2000) approach it "
      "at second order";
  p.additional_references = {
      {1228.6988798308512,
       "J",
       "trapezoid",
       200,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), electric_vehicle, Ipopt + JuMP, "
       "trapeze, grid_size 200, tol 1e-8"},
      {1228.5992844813138,
       "J",
       "trapezoid",
       500,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), electric_vehicle, Ipopt + JuMP, "
       "trapeze, grid_size 500, tol 1e-8"},
      {1228.585040269533,
       "J",
       "trapezoid",
       1000,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), electric_vehicle, Ipopt + JuMP, "
       "trapeze, grid_size 1000, tol 1e-8"},
      {1228.581477701003,
       "J",
       "trapezoid",
       2000,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), electric_vehicle, Ipopt + JuMP, "
       "trapeze, grid_size 2000, tol 1e-8"},
  };
  p.origin =
      "OptimalControlProblems.jl (control-toolbox) electric_vehicle, after Petit & Sciarretta, "
      "IFAC Proc. Vol. 44(1), 2011";
  p.hamiltonian_note =
      "not applicable: no closed-form minimizer is implemented (H = p1 v + p2 (u - ...) + u v + "
      "u^2 is quadratic in u, but the problem provides none)";
  p.tags = {"smooth"};
  return p;
}

}  // namespace ocpb
