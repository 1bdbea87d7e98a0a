// One online re-planning cycle (paper Section IV) on the paper's setting: at t0 = 10 s, 100 new
// random measurements join the 100 of t0 = 0; the parameters are re-estimated, s re-predicted on
// the 0.5 m map around the rest of the path (region margin 10 m), and J_{t0} re-solved from the
// robot's state over the remaining 300 intervals, warm-started from the rest of the plan the
// same solver made at t0 = 0 (the `ocpbench online` defaults). The paper reports about 2 s per
// cycle.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <string>

#include "core/timer.h"
#include "drivers/online/online_replanning.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

struct CycleSetup {
  std::unique_ptr<OnlineChannel> channel;  // after the t0 = 0 update
  MeasurementSet more;                     // the measurements of the update at t0 = 10 s
  CommPath2d::Options problem;             // J_{t0} at t0 = 10 s
  Mat guess;                               // 3 x 300: the rest of the t0 = 0 plan
  std::vector<Eigen::Vector2d> focus;      // D and the rest of the plan's path (region of map)
};

// The state after the first 10 s of the offline plan (seed 1) made by the solver being timed
// (the Hamiltonian descent, or Ipopt on its transcription with the options of the t0 = 0 plan),
// so that each re-plan is warm-started from its own solver's plan, as in `ocpbench online`.
const CycleSetup& Setup(const std::string& solver_name, const std::string& transcription) {
  static std::map<std::string, CycleSetup> cache;
  const std::string key = solver_name + "/" + transcription;
  if (const auto it = cache.find(key); it != cache.end()) return it->second;
  CycleSetup c;
  c.channel = std::make_unique<OnlineChannel>(1);
  c.channel->Update(c.channel->DrawRandom(100, 1, OnlineMeasurementStream(0)));
  const CommPath2d::Options paper;
  const CommPath2d ocp(paper, c.channel->map());
  SolveRequest request;
  request.grid = TimeGrid::Uniform(0.0, 40.0, 400);
  request.transcription = transcription;
  const SolveResult plan = FindSolver(solver_name).make()->Solve(ocp, request);
  const Mat U = plan.controls.SampleIntervals(request.grid);
  Vec x = ocp.x0(), xk = x;
  c.focus.push_back(paper.destination);
  for (int k = 0; k < 400; ++k) {
    if (k == 100) x = xk;
    if (k >= 100) c.focus.push_back(xk.head<2>());
    Vec f(5);
    ocp.Dynamics(0.0, xk, U.col(k), f);
    xk += 0.1 * f;
  }
  c.focus.push_back(xk.head<2>());
  c.more = c.channel->DrawRandom(100, 1, OnlineMeasurementStream(1));
  c.problem = paper;
  c.problem.t0 = 10.0;
  c.problem.start = x.head<2>();
  c.problem.v0 = x.segment<2>(2);
  c.problem.bits_sent = x[4];
  c.guess = U.rightCols(300);
  return cache.emplace(key, std::move(c)).first->second;
}

void BM_OnlineCycle(benchmark::State& state,
                    std::string solver_name,
                    std::string transcription,
                    std::map<std::string, std::string> options) {
  const CycleSetup& s = Setup(solver_name, transcription);
  const std::unique_ptr<Solver> solver = FindSolver(solver_name).make();
  SolveRequest request;
  request.grid = TimeGrid::Uniform(10.0, 40.0, 300);
  request.transcription = transcription;
  request.options = options;
  request.initial_guess = ControlTrajectory::PiecewiseConstant(request.grid, s.guess);
  double predict = 0.0, solve = 0.0, iterations = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    OnlineChannel channel = *s.channel;  // the state before this update
    state.ResumeTiming();
    const Stopwatch p;
    channel.Update(s.more, &s.focus);
    predict += p.cpu();
    const Stopwatch q;
    const CommPath2d ocp(s.problem, channel.map());
    const SolveResult r = solver->Solve(ocp, request);
    solve += q.cpu();
    iterations += r.iterations;
    benchmark::DoNotOptimize(r.objective);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["predict_ms"] = 1e3 * predict / n;
  state.counters["solve_ms"] = 1e3 * solve / n;
  state.counters["solver_iterations"] = iterations / n;
}
BENCHMARK_CAPTURE(BM_OnlineCycle,
                  hamiltonian_50it,
                  std::string("hamiltonian"),
                  std::string(),
                  std::map<std::string, std::string>{{"max_iterations", "50"}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_OnlineCycle,
                  ipopt_euler,
                  std::string("ipopt"),
                  std::string("euler"),
                  std::map<std::string, std::string>{{"mu_init", "1e-4"}})
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
}  // namespace ocpb
