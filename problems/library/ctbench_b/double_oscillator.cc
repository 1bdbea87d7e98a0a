#include "problems/library/ctbench_b/double_oscillator.h"

#include <limits>
#include <memory>

namespace ocpb {

std::vector<ParameterSpec> DoubleOscillatorOcp::ParameterSpecs() { return {}; }

DoubleOscillatorOcp::DoubleOscillatorOcp(const Parameters&) {
  SetHorizon(0.0, kFinalTime);
  SetInitialState(Eigen::Vector4d(0.0, 0.0, 0.0, 0.0));
  const double inf = std::numeric_limits<double>::infinity();
  SetInitialStateBounds(Eigen::Vector4d(0.0, 0.0, -inf, -inf), Eigen::Vector4d(0.0, 0.0, inf, inf));
  SetControlSet(ControlSet::Box(Vec::Constant(1, -1.0), Vec::Constant(1, 1.0)));
}

ProblemInfo DoubleOscillatorProblemInfo() {
  ProblemInfo p;
  p.name = "double-oscillator";
  p.description =
      "double oscillator (Coudurier, Lepreux, Petit 2018, OptimalControlProblems.jl): forced "
      "mass with a damper modulated by u in [-1, 1], free initial velocities";
  p.parameters = DoubleOscillatorOcp::ParameterSpecs();
  p.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<DoubleOscillatorOcp>(params);
  };
  p.default_intervals = 200;
  p.reference_value = 9.1103486302e-4;
  p.reference_source =
      "computed by OCPBench (no published continuous value): ocpbench solve --problem "
      "double-oscillator --solver ipopt --transcription hermite-simpson --terminal hard --option "
      "tol=1e-12 --N 100/200/400/800 gives 9.110344889e-4, 9.110348396e-4, 9.110348616e-4, "
      "9.110348629e-4 (fourth order; Richardson 9.1103486302e-4), LGR N = 100: 9.110348626e-4; "
      "CTBenchmarks' trapezoid values 9.1033618e-4 (N = 200) ... 9.1102787e-4 (N = 2000) "
      "approach it at second order";
  p.additional_references = {
      {0.0009103361763707912,
       "J",
       "trapezoid",
       200,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), double_oscillator, Ipopt + JuMP, "
       "trapeze, grid_size 200, tol 1e-8"},
      {0.0009109230332518871,
       "J",
       "trapezoid",
       500,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), double_oscillator, Ipopt + JuMP, "
       "trapeze, grid_size 500, tol 1e-8"},
      {0.0009110069041873555,
       "J",
       "trapezoid",
       1000,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), double_oscillator, Ipopt + JuMP, "
       "trapeze, grid_size 1000, tol 1e-8"},
      {0.0009110278733863071,
       "J",
       "trapezoid",
       2000,
       "CTBenchmarks.jl core-ubuntu-latest (2026-01-30), double_oscillator, Ipopt + JuMP, "
       "trapeze, grid_size 2000, tol 1e-8"},
  };
  p.origin =
      "OptimalControlProblems.jl (control-toolbox) double_oscillator, after Coudurier, Lepreux, "
      "Petit, IFAC-PapersOnLine 51(2), 2018";
  p.hamiltonian_note = "not applicable: a free initial state (x3(0), x4(0) are decisions)";
  p.tags = {"free-initial-state"};
  return p;
}

}  // namespace ocpb
