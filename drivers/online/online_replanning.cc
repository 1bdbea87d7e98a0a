#include "drivers/online/online_replanning.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <stdexcept>

#include "core/control_trajectory.h"
#include "core/evaluator.h"
#include "core/invalid.h"
#include "core/timer.h"
#include "problems/channel/measurement_sampling.h"
#include "problems/comm_true_energy.h"
#include "solvers/registry.h"

namespace ocpb {

const char* ToString(MeasurementPlacement placement) {
  switch (placement) {
    case MeasurementPlacement::kRandom:
      return "random";
    case MeasurementPlacement::kAlongPath:
      return "path";
    case MeasurementPlacement::kAlongPlan:
      return "plan";
  }
  return "?";
}

MeasurementPlacement MeasurementPlacementFromString(const std::string& name) {
  for (MeasurementPlacement p : {MeasurementPlacement::kRandom,
                                 MeasurementPlacement::kAlongPath,
                                 MeasurementPlacement::kAlongPlan}) {
    if (name == ToString(p)) return p;
  }
  throw std::invalid_argument("placement: unknown '" + name + "' (valid: random, path, plan)");
}

bool OnlineReplanningOptions::IsValid(std::string* error) const {
  if (!(update_period > 0.0) || !std::isfinite(update_period)) {
    return Invalid(error, "update_period: must be finite and > 0 (s)");
  }
  if (initial_measurements < 3) return Invalid(error, "initial_measurements: must be >= 3");
  if (measurements_per_update < 1) return Invalid(error, "measurements_per_update: must be >= 1");
  if (intervals < 1) return Invalid(error, "N: must be >= 1");
  if (solver.empty()) return Invalid(error, "solver: required");
  return true;
}

namespace {

Vec TerminalResidual(const CommPath2d::Options& o, const Vec& x) {
  Vec psi(5);
  psi << x[0] - o.destination[0], x[1] - o.destination[1], x[2], x[3], x[4] - o.bits;
  return psi;
}

double Penalty(const CommPath2d::Options& o, const Vec& psi) {
  const double w[5] = {o.penalty[0], o.penalty[0], o.penalty[1], o.penalty[1], o.penalty[2]};
  double p = 0.0;
  for (int i = 0; i < 5; ++i) p += w[i] * psi[i] * psi[i];
  return p;
}

}  // namespace

namespace {

// The checks of RunOnlineReplanning; returns the steps between updates.
int CheckScenario(const CommPath2d::Options& problem,
                  const OnlineChannel* channel,
                  const OnlineReplanningOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  if (!problem.IsValid(&error)) throw std::invalid_argument("comm-path2d: " + error);
  if (problem.t0 != 0.0) throw std::invalid_argument("t0: the online scenario starts at t0 = 0");
  if (channel == nullptr || channel->num_measurements() != 0) {
    throw std::invalid_argument("online: the channel must be fresh (no measurements yet)");
  }
  const double h = problem.tf / options.intervals;
  const double steps_real = options.update_period / h;
  const int period_steps = static_cast<int>(std::lround(steps_real));
  if (period_steps < 1 || std::abs(steps_real - period_steps) > 1e-6 * std::max(1.0, steps_real)) {
    throw std::invalid_argument("update_period: must be a positive multiple of the step tf/N = " +
                                std::to_string(h) + " s");
  }
  const SolverInfo& sinfo = FindSolver(options.solver);
  if (sinfo.uses_transcription && options.transcription.empty()) {
    throw std::invalid_argument("solver '" + options.solver + "' needs a transcription");
  }
  if (!sinfo.uses_transcription && !options.transcription.empty()) {
    throw std::invalid_argument("solver '" + options.solver + "' takes no transcription");
  }
  return period_steps;
}

// The run in progress: the scenario, the channel, and what has been driven so far.
struct Replanning {
  const CommPath2d::Options& problem;
  OnlineChannel& channel;
  std::uint64_t seed;
  const OnlineReplanningOptions& options;
  const Solver& solver;
  OnlineResult& r;
  Vec x;         // the robot's state now
  Mat previous;  // 3 x N: the latest plan's controls, at global step indices
};

// Step 1: this cycle's measurements and the channel update (re-estimation, re-prediction around
// the robot, its destination and the rest of its current plan).
void UpdateChannel(Replanning& run, int cycle, int k0, OnlineCycle* c) {
  const OnlineReplanningOptions& options = run.options;
  MeasurementSet more;
  if (cycle == 0 || options.placement == MeasurementPlacement::kRandom) {
    c->measurement_stream = OnlineMeasurementStream(cycle);
    more = run.channel.DrawRandom(
        cycle == 0 ? options.initial_measurements : options.measurements_per_update,
        run.seed,
        c->measurement_stream);
  } else {
    // Driven: the executed states since the last update. Planned: the last plan's states from
    // now (its column steps_executed is the robot's state) to tf. Both are at equal time steps,
    // so evenly spaced indices are evenly spaced times.
    std::vector<Eigen::Vector2d> path;
    const OnlineCycle& last = run.r.cycles.back();
    if (options.placement == MeasurementPlacement::kAlongPath) {
      for (int k = last.first_step; k <= k0; ++k) path.emplace_back(run.r.X(0, k), run.r.X(1, k));
    } else {
      for (int j = last.steps_executed; j < last.plan_states.cols(); ++j) {
        path.emplace_back(last.plan_states(0, j), last.plan_states(1, j));
      }
    }
    more = MeasureAlongPath(run.channel.truth(), path, options.measurements_per_update);
  }
  std::vector<Eigen::Vector2d> focus;
  if (cycle > 0) {
    const OnlineCycle& last = run.r.cycles.back();
    focus.emplace_back(run.problem.destination);
    for (int j = last.steps_executed; j < last.plan_states.cols(); ++j) {
      focus.emplace_back(last.plan_states(0, j), last.plan_states(1, j));
    }
  }
  const int before = run.channel.num_measurements();
  c->predict = run.channel.Update(more, cycle > 0 ? &focus : nullptr);
  c->map_grid = run.channel.map_grid();
  c->new_measurements = run.channel.num_measurements() - before;
  c->measurements = run.channel.num_measurements();
  c->estimated = run.channel.estimated();
}

// The cost-to-go problem from the robot's state at c.t0 over the current prediction.
CommPath2d CostToGo(const Replanning& run, const OnlineCycle& c) {
  const Vec& x = run.x;
  CommPath2d::Options o = run.problem;
  o.t0 = c.t0;
  o.start = x.head<2>();
  o.v0 = x.segment<2>(2);
  o.bits_sent = x[4];
  if (!x.head<2>().allFinite() || x.head<2>().minCoeff() < 0.0) {
    throw std::runtime_error("online: the robot left the workspace at t = " + std::to_string(c.t0));
  }
  o.workspace = std::max(o.workspace, x.head<2>().maxCoeff());  // a slight overshoot is fine
  return CommPath2d(o, run.channel.map());
}

// Step 2: solves the cost-to-go on the remaining n intervals (warm-started from the rest of the
// previous plan after cycle 0) and returns the controls the robot will drive: the solution, or,
// when the solver returned none that is finite, the rest of the previous plan (the default
// start at cycle 0). Fills the cycle's solve fields and the plan's predicted states.
Mat Replan(Replanning& run, const CommPath2d& ocp, int cycle, int n, OnlineCycle* c) {
  SolveRequest request;
  request.grid = TimeGrid::Uniform(c->t0, run.problem.tf, n);
  request.terminal = TerminalMode::kPenalty;
  request.transcription = run.options.transcription;
  request.transcription_options = run.options.transcription_options;
  request.options = cycle == 0 ? run.options.offline_options : run.options.replan_options;
  if (cycle > 0) {
    request.initial_guess =
        ControlTrajectory::PiecewiseConstant(request.grid, run.previous.rightCols(n));
  }
  SolveResult result;
  const Stopwatch watch;
  try {
    result = run.solver.Solve(ocp, request);
  } catch (const std::invalid_argument&) {
    throw;  // invalid options: the caller's input
  } catch (const std::exception& e) {
    result = SolveResult();
    result.status = SolveStatus::kError;
    result.solver_status = "exception";
    result.message = e.what();
  }
  c->solve_seconds = watch.cpu();
  c->iterations = result.iterations;
  c->status = result.status;
  c->solver_status = result.solver_status;
  auto fallback = [&]() -> Mat {
    return cycle > 0 ? Mat(run.previous.rightCols(n))
                     : DefaultInitialGuess(ocp, request.grid).SampleIntervals(request.grid);
  };
  Mat plan = result.controls.nu() == 3 ? result.controls.SampleIntervals(request.grid) : fallback();
  if (result.status == SolveStatus::kNumericalFailure ||
      result.status == SolveStatus::kInfeasible || result.status == SolveStatus::kError ||
      result.status == SolveStatus::kInvalidInput || !plan.allFinite()) {
    run.r.all_solved = false;
    if (!plan.allFinite()) plan = fallback();
  }
  const Evaluation ev = Evaluate(ocp,
                                 ControlTrajectory::PiecewiseConstant(request.grid, plan),
                                 request.grid,
                                 Integrator::kEuler);
  c->planned_energy = ev.Jbar;
  c->planned_J = ev.J;
  c->plan_times = request.grid.points();
  c->plan_states = ev.X;
  return plan;
}

// The offline plan (cycle 0's) executed to tf on the same realization (ExecuteCommPlan: the
// one mechanism that prices plans on the true channel, offline records' judge included).
void ExecuteOffline(Replanning& run, const CommPath2d& ocp, const Mat& plan, double solve_seconds) {
  OnlineResult& r = run.r;
  const CommExecution e = ExecuteCommPlan(ocp, *run.channel.true_quality(), r.grid, plan, run.x);
  r.offline_U = plan;
  r.offline_X = e.X;
  r.offline_energy_true = e.energy_true;
  r.offline_transmit_energy_true = e.transmit_energy_true;
  r.offline_energy_predicted = e.energy_planned;
  r.offline_terminal_residual = e.terminal_residual;
  r.offline_terminal_violation = e.terminal_violation;
  r.offline_J_true = e.J_true;
  r.offline_solve_seconds = solve_seconds;
}

// Step 3: drives `steps` steps of the plan from global step k0 (ExecuteCommPlan on the grid's
// steps k0 .. k0 + steps).
void Execute(
    Replanning& run, const CommPath2d& ocp, const Mat& plan, int k0, int steps, OnlineCycle* c) {
  OnlineResult& r = run.r;
  const std::vector<double>& t = r.grid.points();
  const TimeGrid segment =
      TimeGrid::FromPoints(std::vector<double>(t.begin() + k0, t.begin() + k0 + steps + 1));
  const CommExecution e =
      ExecuteCommPlan(ocp, *run.channel.true_quality(), segment, plan.leftCols(steps), run.x);
  for (int j = 0; j < steps; ++j) {
    r.U.col(k0 + j) = plan.col(j);
    r.X.col(k0 + j + 1) = e.X.col(j + 1);
    r.step_energy_true.push_back(e.step_energy_true[j]);
    r.step_energy_predicted.push_back(e.step_energy_planned[j]);
    c->segment_energy_true += e.step_energy_true[j];
    c->segment_energy_predicted += e.step_energy_planned[j];
  }
  r.transmit_energy_true += e.transmit_energy_true;
  run.x = e.X.col(steps);
  c->steps_executed = steps;
}

}  // namespace

OnlineResult RunOnlineReplanning(const CommPath2d::Options& problem,
                                 OnlineChannel* channel,
                                 std::uint64_t seed,
                                 const OnlineReplanningOptions& options) {
  const int period_steps = CheckScenario(problem, channel, options);
  const std::unique_ptr<Solver> solver = FindSolver(options.solver).make();
  const int N = options.intervals;
  OnlineResult r;
  r.grid = TimeGrid::Uniform(0.0, problem.tf, N);
  r.X = Mat::Zero(5, N + 1);
  r.U = Mat::Zero(3, N);
  Replanning run{problem, *channel, seed, options, *solver, r, Vec(5), Mat::Zero(3, N)};
  run.x << problem.start, problem.v0, problem.bits_sent;
  r.X.col(0) = run.x;
  for (int cycle = 0, k0 = 0; k0 < N; ++cycle) {
    OnlineCycle c;
    c.first_step = k0;
    c.t0 = r.grid.t(k0);
    UpdateChannel(run, cycle, k0, &c);
    const CommPath2d ocp = CostToGo(run, c);
    const int n = N - k0;
    const Mat plan = Replan(run, ocp, cycle, n, &c);
    run.previous.rightCols(n) = plan;
    if (cycle == 0) ExecuteOffline(run, ocp, plan, c.solve_seconds);
    const int steps = std::min(period_steps, n);
    Execute(run, ocp, plan, k0, steps, &c);
    k0 += steps;
    r.cycles.push_back(std::move(c));
  }
  for (const OnlineCycle& c : r.cycles) {
    r.energy_true += c.segment_energy_true;
    r.energy_predicted += c.segment_energy_predicted;
  }
  r.terminal_residual = TerminalResidual(problem, run.x);
  r.terminal_violation = r.terminal_residual.cwiseAbs().maxCoeff();
  r.J_true = r.energy_true + Penalty(problem, r.terminal_residual);
  return r;
}

}  // namespace ocpb
