// Kernels of the core: one forward simulation and one adjoint sweep of the discrete problem.
#include <benchmark/benchmark.h>

#include "core/discrete_ocp.h"
#include "problems/registry.h"

namespace ocpb {
namespace {

void BM_DoubleIntegratorSimulateAndAdjoint(benchmark::State& state) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const int N = static_cast<int>(state.range(0));
  const Integrator integrator = state.range(1) == 0 ? Integrator::kEuler : Integrator::kRk4;
  const DiscreteOcp docp(*ocp, TimeGrid::Uniform(0.0, 1.0, N), integrator, TerminalMode::kPenalty);
  const Mat U = Mat::Constant(1, N, 0.5);
  Mat X, Lambda, G;
  for (auto _ : state) {
    benchmark::DoNotOptimize(docp.Simulate(U, &X));
    docp.Adjoint(U, X, &Lambda, &G);
    benchmark::DoNotOptimize(G.data());
  }
  state.SetComplexityN(N);
}
BENCHMARK(BM_DoubleIntegratorSimulateAndAdjoint)
    ->ArgNames({"N", "rk4"})
    ->ArgsProduct({{400, 4000, 40000}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace ocpb
