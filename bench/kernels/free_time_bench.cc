// Free final time, three ways on the same problems: the indirect Newton method (T unknown,
// H(T) = 0) and Ipopt with T as the NLP's last variable on the trapezoid and Hermite-Simpson
// transcriptions. CPU time of one full solve against N, with T's error against the reference as
// a counter. On brachistochrone-free-time Newton needs a start near the solution's costates:
// it is timed with warm_start = ipopt, Ipopt's trapezoid solve included. Run in Release, e.g.
//   ocpbench_kernels --benchmark_filter=FreeFinalTime --benchmark_out=free_time.json
//                    --benchmark_out_format=json
#include <cmath>
#include <string>

#include <benchmark/benchmark.h>

#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

// range(0): N; range(1): 0 double-integrator-free-time, 1 brachistochrone-free-time;
// range(2): 0 indirect-newton, 1 ipopt + trapezoid, 2 ipopt + hermite-simpson.
void BM_FreeFinalTime(benchmark::State& state) {
  const bool brachistochrone = state.range(1) != 0;
  const std::string name =
      brachistochrone ? "brachistochrone-free-time" : "double-integrator-free-time";
  const ProblemInfo& info = FindProblem(name);
  const auto ocp = MakeProblem(name, {}, 0);
  const int N = static_cast<int>(state.range(0));
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
  request.terminal = TerminalMode::kHard;
  std::string solver = "indirect-newton";
  if (state.range(2) == 0) {
    if (brachistochrone) request.options.Set("warm_start", "ipopt");
  } else {
    solver = "ipopt";
    request.transcription = state.range(2) == 1 ? "trapezoid" : "hermite-simpson";
  }
  const auto method = FindSolver(solver).make();
  SolveResult r;
  for (auto _ : state) {
    r = method->Solve(*ocp, request);
    benchmark::DoNotOptimize(r.states.data());
  }
  if (!IsSuccess(r.status)) {
    state.SkipWithError((r.solver_status + ": " + r.message).c_str());
    return;
  }
  // J = T for the brachistochrone; for the double integrator T* = 18^(1/4).
  const double T_star = brachistochrone ? *info.reference_value : std::pow(18.0, 0.25);
  state.counters["iterations"] = r.iterations;
  state.counters["T_error"] = std::abs(r.state_grid.tf() - T_star);
}
BENCHMARK(BM_FreeFinalTime)
    ->ArgNames({"N", "brachistochrone", "method"})
    ->ArgsProduct({{100, 1000, 4000}, {0, 1}, {0, 1, 2}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ocpb
