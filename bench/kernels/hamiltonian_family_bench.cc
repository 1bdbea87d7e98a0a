// The Hamiltonian family against Ipopt + Euler on the hard terminal form of the paper's problem
// (comm-path2d, N = 400) as the weight of motion gamma falls from the paper's 1e-2 to 1e-5:
// the issue-19 measurement, both methods in one run so that their CPU times compare.
//
//   ocpbench_kernels --benchmark_filter=HardForm
//
// Arguments: g (gamma = 10^-g), seed (channel realization). Each benchmark iteration is one
// whole solve (Iterations(1): a solve takes 0.05-10 s); the channel (the paper's, bicubic map)
// is built once per seed outside the timed region. Counters: J (Euler J without penalty, by the
// common evaluator), terminal (terminal violation, evaluator), cpu_s (the solve's own CPU
// time), converged (1 or 0), and for the family descent_iterations, newton_iterations,
// newton_attempts and its grid sequence's coarse_newton_iterations, fine_newton_iterations and
// coarse_fallback; for Ipopt iterations. The table of the issue-19 figures from a JSON run:
// bench/kernels/hardform_ratios.py.
#include <map>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "core/evaluator.h"
#include "problems/registry.h"
#include "solvers/hamiltonian_family.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

const Ocp* Problem(int g, int seed) {
  static std::map<std::pair<int, int>, std::unique_ptr<Ocp>> cache;
  auto& slot = cache[{g, seed}];
  if (!slot) {
    slot = MakeProblem("comm-path2d", {"gamma=1e-" + std::to_string(g)}, seed);
  }
  return slot.get();
}

void Report(benchmark::State& state, const Ocp& ocp, const SolveResult& r) {
  const Evaluation ev = Evaluate(ocp, r.controls, r.state_grid, Integrator::kEuler);
  state.counters["J"] = ev.Jbar;
  state.counters["terminal"] = ev.terminal_violation;
  state.counters["cpu_s"] = r.cpu_seconds;
  state.counters["converged"] = IsSuccess(r.status) ? 1.0 : 0.0;
  for (const char* key : {"descent_iterations",
                          "newton_iterations",
                          "newton_attempts",
                          "coarse_newton_iterations",
                          "fine_newton_iterations",
                          "coarse_fallback"}) {
    const auto it = r.solver_stats.find(key);
    if (it != r.solver_stats.end()) state.counters[key] = it->second;
  }
  state.counters["iterations"] = r.iterations;
  state.SetLabel(r.solver_status);
}

SolveRequest HardRequest(const Ocp& ocp) {
  SolveRequest r;
  r.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), 400);
  r.terminal = TerminalMode::kHard;
  return r;
}

void BM_HardFormFamilyPolish(benchmark::State& state) {
  const Ocp& ocp = *Problem(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const HamiltonianFamily solver(HamiltonianFamily::Preset::kPolish);
  const SolveRequest request = HardRequest(ocp);
  SolveResult r;
  for (auto _ : state) {
    r = solver.Solve(ocp, request);
    benchmark::DoNotOptimize(r.history.data());
  }
  Report(state, ocp, r);
}

// The same with the constant-costate start (polish_constant_costate_start, off by default), so
// that both starts compare in one run.
void BM_HardFormFamilyPolishConstantCostate(benchmark::State& state) {
  const Ocp& ocp = *Problem(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const HamiltonianFamily solver(HamiltonianFamily::Preset::kPolish);
  SolveRequest request = HardRequest(ocp);
  request.options = {{"polish_constant_costate_start", "true"}};
  SolveResult r;
  for (auto _ : state) {
    r = solver.Solve(ocp, request);
    benchmark::DoNotOptimize(r.history.data());
  }
  Report(state, ocp, r);
}

void BM_HardFormIpoptEuler(benchmark::State& state) {
  const Ocp& ocp = *Problem(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  SolveRequest request = HardRequest(ocp);
  request.transcription = "euler";
  const std::unique_ptr<Solver> solver = FindSolver("ipopt").make();
  SolveResult r;
  for (auto _ : state) {
    r = solver->Solve(ocp, request);
    benchmark::DoNotOptimize(r.history.data());
  }
  Report(state, ocp, r);
}

void Arguments(benchmark::internal::Benchmark* b) {
  b->ArgNames({"g", "seed"});
  for (int g = 2; g <= 5; ++g) {
    for (int seed = 1; seed <= 5; ++seed) b->Args({g, seed});
  }
  b->Iterations(1)->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_HardFormFamilyPolish)->Apply(Arguments);
BENCHMARK(BM_HardFormFamilyPolishConstantCostate)->Apply(Arguments);
BENCHMARK(BM_HardFormIpoptEuler)->Apply(Arguments);

}  // namespace
}  // namespace ocpb
