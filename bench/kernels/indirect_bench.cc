// The indirect method's cost against N: Newton on the trapezoidal maximum-principle BVP, whose
// Jacobian is banded (2nx x 4nx blocks per interval), so a sparse LU should keep each step O(N).
// Counters: Newton steps, CPU seconds per step, and the split into assembly / factorization /
// triangular solves (SolveResult::solver_stats); the warm-started comm-path2d kernel also gives
// the totals of a full solve, descent included. Run in Release, e.g.
//   ocpbench_kernels --benchmark_filter=Indirect --benchmark_out=indirect.json
//                    --benchmark_out_format=json
#include <algorithm>
#include <memory>
#include <string>

#include <benchmark/benchmark.h>

#include "problems/registry.h"
#include "solvers/indirect_newton.h"

namespace ocpb {
namespace {

const char* LinearSolverName(int64_t code) { return code == 0 ? "umfpack" : "klu"; }

void Report(benchmark::State& state, const SolveResult& r) {
  if (r.status != SolveStatus::kConverged) {
    state.SkipWithError((r.solver_status + ": " + r.message).c_str());
    return;
  }
  const double steps = std::max(1, r.iterations);
  state.counters["newton_steps"] = r.iterations;
  state.counters["residual_inf"] = r.history.back().primal_inf;
  state.counters["ms_per_step"] = 1e3 * r.solver_stats.at("newton_cpu_seconds") / steps;
  state.counters["assembly_ms_per_step"] = 1e3 * r.solver_stats.at("assembly_seconds") / steps;
  state.counters["factor_ms_per_step"] = 1e3 * r.solver_stats.at("factorization_seconds") / steps;
  state.counters["solve_ms_per_step"] = 1e3 * r.solver_stats.at("solve_seconds") / steps;
  state.counters["jacobian_nonzeros"] = r.solver_stats.at("jacobian_nonzeros");
}

// The double integrator (penalty form, from u = 0): linear, so one Newton step; this times one
// assembly, one symbolic + numeric factorization and one solve at each N. The bounded variant
// (|u| <= 5, hard form) needs a few semismooth steps.
void BM_IndirectDoubleIntegrator(benchmark::State& state) {
  const bool bounded = state.range(2) != 0;
  const auto ocp = MakeProblem(bounded ? "double-integrator-bounded" : "double-integrator", {}, 0);
  const int N = static_cast<int>(state.range(0));
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
  request.terminal = bounded ? TerminalMode::kHard : TerminalMode::kPenalty;
  request.options.Set("linear_solver", LinearSolverName(state.range(1)));
  const IndirectNewton solver;
  SolveResult r;
  for (auto _ : state) {
    r = solver.Solve(*ocp, request);
    benchmark::DoNotOptimize(r.states.data());
  }
  Report(state, r);
}
BENCHMARK(BM_IndirectDoubleIntegrator)
    ->ArgNames({"N", "klu", "bounded"})
    ->ArgsProduct({{400, 1000, 4000, 10000, 40000}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// Linear interpolation of node values (nx x M+1 on a uniform grid) to a uniform grid of N.
Mat Interpolate(const Mat& values, int N) {
  const int M = static_cast<int>(values.cols()) - 1;
  Mat out(values.rows(), N + 1);
  for (int k = 0; k <= N; ++k) {
    const double s = static_cast<double>(k) * M / N;
    const int i = std::min(static_cast<int>(s), M - 1);
    const double w = s - i;
    out.col(k) = (1.0 - w) * values.col(i) + w * values.col(i + 1);
  }
  return out;
}

// comm-path2d (path-loss channel, paper's scenario, penalty form), from its N = 200 solution
// interpolated to the grid (mesh continuation; that solution comes once from the Hamiltonian
// descent polished by Newton): this times the nonlinear, semismooth Newton finish at each N.
void BM_IndirectCommPath2d(benchmark::State& state) {
  static const std::unique_ptr<Ocp> ocp = MakeProblem("comm-path2d", {"channel=0"}, 1);
  static const SolveResult coarse = [] {
    SolveRequest request;
    request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 200);
    request.options.Set("warm_start", "hamiltonian");
    return IndirectNewton().Solve(*ocp, request);
  }();
  if (coarse.status != SolveStatus::kConverged) {
    state.SkipWithError(("N = 200 start: " + coarse.message).c_str());
    return;
  }
  const int N = static_cast<int>(state.range(0));
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
  request.options.Set("linear_solver", LinearSolverName(state.range(1)));
  const Mat X = Interpolate(coarse.states, N), P = Interpolate(coarse.costates, N);
  const IndirectNewton solver;
  SolveResult r;
  for (auto _ : state) {
    r = solver.SolveFrom(*ocp, request, X, P);
    benchmark::DoNotOptimize(r.states.data());
  }
  Report(state, r);
}
BENCHMARK(BM_IndirectCommPath2d)
    ->ArgNames({"N", "klu"})
    ->ArgsProduct({{400, 1000, 4000, 10000, 40000}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

// comm-path2d as the paper suite runs it (the default channel, the GP prediction's bicubic map,
// seed 1; penalty form; forward Euler): one full solve per N, the Hamiltonian descent's 200
// iterations and Newton from them (costates fitted to the descent's controls), the CPU time split
// into the warm start, the costate fit and Newton's assembly / factorization / triangular solves
// (totals over the solve, in ms). The channel is built once, outside the timing.
void BM_IndirectCommPath2dWarmStarted(benchmark::State& state) {
  static const std::unique_ptr<Ocp> ocp = MakeProblem("comm-path2d", {}, 1);
  const int N = static_cast<int>(state.range(0));
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
  request.options = {{"warm_start", "hamiltonian"}, {"hamiltonian.max_iterations", "200"}};
  const IndirectNewton solver;
  SolveResult r;
  for (auto _ : state) {
    r = solver.Solve(*ocp, request);
    benchmark::DoNotOptimize(r.states.data());
  }
  Report(state, r);
  const auto ms = [&](const char* key) { return 1e3 * r.solver_stats.at(key); };
  state.counters["total_cpu_ms"] = 1e3 * r.cpu_seconds;
  state.counters["warm_start_ms"] = ms("warm_start_cpu_seconds");
  state.counters["costate_fit_ms"] = ms("start_cpu_seconds");
  state.counters["newton_ms"] = ms("newton_cpu_seconds");
  state.counters["assembly_ms"] = ms("assembly_seconds");
  state.counters["factor_ms"] = ms("factorization_seconds");
  state.counters["solve_ms"] = ms("solve_seconds");
}
BENCHMARK(BM_IndirectCommPath2dWarmStarted)
    ->ArgNames({"N"})
    ->Arg(400)
    ->Arg(4000)
    ->Arg(40000)
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ocpb
