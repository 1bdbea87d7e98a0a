// riccati-ip against Ipopt + MUMPS on the same NLP, Euler's or the trapezoid's (hard terminal
// form, the same start, tol 1e-8): whole solves through the registered solvers, at N = 100, 400,
// 1600 and 6400.
// Results and command: solvers/README-riccati-ip.md.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

struct BenchProblem {
  const char* name;
  std::vector<std::string> settings;
};

const std::vector<BenchProblem>& BenchProblems() {
  static const std::vector<BenchProblem> problems = {
      {"lqr", {}},
      {"bryson-denham", {}},
      {"vanderpol", {}},
      {"robot-arm", {}},
      {"goddard", {}},
      {"catmix", {}},
      {"comm-path2d", {}},  // the paper's problem, the registry's defaults
  };
  return problems;
}

const char* const kSolverNames[] = {"ipopt", "riccati-ip"};
const char* const kSchemes[] = {"euler", "trapezoid"};

void BM_RiccatiIpVsIpopt(benchmark::State& state) {
  const BenchProblem& p = BenchProblems()[state.range(0)];
  std::unique_ptr<Ocp> ocp;
  try {
    ocp = MakeProblem(p.name, p.settings, 1);
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), static_cast<int>(state.range(1)));
  request.terminal = TerminalMode::kHard;
  request.transcription = kSchemes[state.range(3)];
  const std::string solver_name = kSolverNames[state.range(2)];
  const auto solver = FindSolver(solver_name).make();
  SolveResult r;
  for (auto _ : state) r = solver->Solve(*ocp, request);
  state.counters["success"] = IsSuccess(r.status) ? 1 : 0;
  state.counters["iterations"] = r.iterations;
  state.counters["objective"] = r.objective;
  state.counters["solver_cpu_s"] = r.cpu_seconds;
  if (r.iterations > 0) state.counters["cpu_s_per_iteration"] = r.cpu_seconds / r.iterations;
  const auto stat = [&](const char* key) {
    const auto it = r.solver_stats.find(key);
    return it == r.solver_stats.end() ? -1.0 : it->second;
  };
  if (solver_name == "riccati-ip") {
    state.counters["kkt_cpu_s"] = stat("riccati_ip_kkt_cpu_seconds");
    state.counters["callback_cpu_s"] = stat("riccati_ip_callback_cpu_seconds");
    state.counters["regularizations"] = stat("riccati_ip_regularizations");
  }
  state.SetLabel(std::string(p.name) + " " + solver_name + " " + request.transcription + " " +
                 r.solver_status);
}
BENCHMARK(BM_RiccatiIpVsIpopt)
    ->ArgNames({"problem", "N", "solver", "scheme"})
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6}, {100, 400, 1600, 6400}, {0, 1}, {0, 1}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace ocpb
