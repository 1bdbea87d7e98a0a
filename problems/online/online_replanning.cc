#include "problems/online/online_replanning.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <stdexcept>

#include "core/control_trajectory.h"
#include "core/evaluator.h"
#include "core/timer.h"
#include "problems/channel/measurement_sampling.h"
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
  auto fail = [error](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (!(update_period > 0.0) || !std::isfinite(update_period)) {
    return fail("update_period: must be finite and > 0 (s)");
  }
  if (initial_measurements < 3) return fail("initial_measurements: must be >= 3");
  if (measurements_per_update < 1) return fail("measurements_per_update: must be >= 1");
  if (intervals < 1) return fail("N: must be >= 1");
  if (solver.empty()) return fail("solver: required");
  return true;
}

namespace {

struct StepCost {
  double true_energy = 0.0;
  double true_transmit = 0.0;  // the transmission part of true_energy
  double predicted_energy = 0.0;
};

// One executed step from x with u on the problem's Euler model; costs on the true channel and on
// the problem's (predicted) channel.
StepCost Step(
    const CommPath2d& ocp, const OnlineChannel& channel, double t, double h, const Vec& u, Vec* x) {
  const CommPowerModel& power = ocp.options().power;
  const double acc2 = u[0] * u[0] + u[1] * u[1];
  const double speed2 = (*x)[2] * (*x)[2] + (*x)[3] * (*x)[3];
  const double s_true = channel.TrueQuality(Eigen::Vector2d((*x)[0], (*x)[1]));
  StepCost c;
  c.true_transmit = h * power.Transmission(u[2], s_true, 1.0 / power.K());
  c.true_energy = h * power.Motion(acc2, speed2) + c.true_transmit;
  c.predicted_energy = h * ocp.RunningCost(t, *x, u);
  Vec f(5);
  ocp.Dynamics(t, *x, u, f);
  *x += h * f;
  return c;
}

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

OnlineResult RunOnlineReplanning(const CommPath2d::Options& problem,
                                 OnlineChannel* channel,
                                 std::uint64_t seed,
                                 const OnlineReplanningOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  if (!problem.IsValid(&error)) throw std::invalid_argument("comm-path2d: " + error);
  if (problem.t0 != 0.0) throw std::invalid_argument("t0: the online scenario starts at t0 = 0");
  if (channel == nullptr || channel->num_measurements() != 0) {
    throw std::invalid_argument("online: the channel must be fresh (no measurements yet)");
  }
  const int N = options.intervals;
  const double tf = problem.tf;
  const double h = tf / N;
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
  const std::unique_ptr<Solver> solver = sinfo.make();

  OnlineResult r;
  r.grid = TimeGrid::Uniform(0.0, tf, N);
  r.X = Mat::Zero(5, N + 1);
  r.U = Mat::Zero(3, N);
  Vec x(5);
  x << problem.start, problem.v0, problem.bits_sent;
  r.X.col(0) = x;
  Mat previous;  // 3 x N: the latest plan's controls, at global step indices
  int k0 = 0;
  for (int cycle = 0; k0 < N; ++cycle) {
    OnlineCycle c;
    c.first_step = k0;
    c.t0 = r.grid.t(k0);
    // 1. Channel update.
    MeasurementSet more;
    if (cycle == 0 || options.placement == MeasurementPlacement::kRandom) {
      c.measurement_stream = OnlineMeasurementStream(cycle);
      more = channel->DrawRandom(
          cycle == 0 ? options.initial_measurements : options.measurements_per_update,
          seed,
          c.measurement_stream);
    } else {
      // Driven: the executed states since the last update. Planned: the last plan's states
      // from now (its column steps_executed is the robot's state) to tf. Both are at equal time
      // steps, so evenly spaced indices are evenly spaced times.
      std::vector<Eigen::Vector2d> path;
      const OnlineCycle& last = r.cycles.back();
      if (options.placement == MeasurementPlacement::kAlongPath) {
        for (int k = last.first_step; k <= k0; ++k) path.emplace_back(r.X(0, k), r.X(1, k));
      } else {
        for (int j = last.steps_executed; j < last.plan_states.cols(); ++j) {
          path.emplace_back(last.plan_states(0, j), last.plan_states(1, j));
        }
      }
      more = MeasureAlongPath(channel->truth(), path, options.measurements_per_update);
    }
    // The map must cover the robot, its destination and the rest of its current plan.
    std::vector<Eigen::Vector2d> focus;
    if (cycle > 0) {
      const OnlineCycle& last = r.cycles.back();
      focus.emplace_back(problem.destination);
      for (int j = last.steps_executed; j < last.plan_states.cols(); ++j) {
        focus.emplace_back(last.plan_states(0, j), last.plan_states(1, j));
      }
    }
    const int before = channel->num_measurements();
    c.predict = channel->Update(more, cycle > 0 ? &focus : nullptr);
    c.map_grid = channel->map_grid();
    c.new_measurements = channel->num_measurements() - before;
    c.measurements = channel->num_measurements();
    c.estimated = channel->estimated();

    // 2. The cost-to-go problem from the current state.
    CommPath2d::Options o = problem;
    o.t0 = c.t0;
    o.start = x.head<2>();
    o.v0 = x.segment<2>(2);
    o.bits_sent = x[4];
    if (!x.head<2>().allFinite() || x.head<2>().minCoeff() < 0.0) {
      throw std::runtime_error("online: the robot left the workspace at t = " +
                               std::to_string(c.t0));
    }
    o.workspace = std::max(o.workspace, x.head<2>().maxCoeff());  // a slight overshoot is fine
    const CommPath2d ocp(o, channel->map());
    const int n = N - k0;
    SolveRequest request;
    request.grid = TimeGrid::Uniform(c.t0, tf, n);
    request.terminal = TerminalMode::kPenalty;
    request.transcription = options.transcription;
    request.options = cycle == 0 ? options.offline_options : options.replan_options;
    if (cycle > 0) {
      request.initial_guess =
          ControlTrajectory::PiecewiseConstant(request.grid, previous.rightCols(n));
    }
    SolveResult result;
    const Stopwatch watch;
    try {
      result = solver->Solve(ocp, request);
    } catch (const std::invalid_argument&) {
      throw;  // invalid options: the caller's input
    } catch (const std::exception& e) {
      result = SolveResult();
      result.status = SolveStatus::kError;
      result.solver_status = "exception";
      result.message = e.what();
    }
    c.solve_seconds = watch.cpu();
    c.iterations = result.iterations;
    c.status = result.status;
    c.solver_status = result.solver_status;
    Mat plan;
    if (result.controls.nu() == 3) {
      plan = result.controls.SampleIntervals(request.grid);
    } else if (cycle > 0) {
      plan = previous.rightCols(n);  // nothing new: keep driving the last plan
    } else {
      plan = DefaultInitialGuess(ocp, request.grid).SampleIntervals(request.grid);
    }
    if (result.status == SolveStatus::kNumericalFailure ||
        result.status == SolveStatus::kInfeasible || result.status == SolveStatus::kError ||
        result.status == SolveStatus::kInvalidInput || !plan.allFinite()) {
      r.all_solved = false;
      if (!plan.allFinite()) {
        plan = cycle > 0 ? Mat(previous.rightCols(n))
                         : DefaultInitialGuess(ocp, request.grid).SampleIntervals(request.grid);
      }
    }
    const Evaluation ev = Evaluate(ocp,
                                   ControlTrajectory::PiecewiseConstant(request.grid, plan),
                                   request.grid,
                                   Integrator::kEuler);
    c.planned_energy = ev.Jbar;
    c.planned_J = ev.J;
    c.plan_times = request.grid.points();
    c.plan_states = ev.X;
    if (previous.size() == 0) previous = Mat::Zero(3, N);
    previous.rightCols(n) = plan;

    if (cycle == 0) {
      // The offline plan: executed to tf on the same realization.
      r.offline_U = plan;
      r.offline_X = Mat::Zero(5, N + 1);
      Vec xo = x;
      r.offline_X.col(0) = xo;
      for (int k = 0; k < N; ++k) {
        const StepCost sc = Step(ocp, *channel, r.grid.t(k), h, plan.col(k), &xo);
        r.offline_energy_true += sc.true_energy;
        r.offline_transmit_energy_true += sc.true_transmit;
        r.offline_energy_predicted += sc.predicted_energy;
        r.offline_X.col(k + 1) = xo;
      }
      r.offline_terminal_residual = TerminalResidual(problem, xo);
      r.offline_terminal_violation = r.offline_terminal_residual.cwiseAbs().maxCoeff();
      r.offline_J_true = r.offline_energy_true + Penalty(problem, r.offline_terminal_residual);
      r.offline_solve_seconds = c.solve_seconds;
    }

    // 3. Execute until the next update.
    const int steps = std::min(period_steps, n);
    for (int j = 0; j < steps; ++j) {
      const int k = k0 + j;
      const StepCost sc = Step(ocp, *channel, r.grid.t(k), h, plan.col(j), &x);
      r.U.col(k) = plan.col(j);
      r.X.col(k + 1) = x;
      r.step_energy_true.push_back(sc.true_energy);
      r.transmit_energy_true += sc.true_transmit;
      r.step_energy_predicted.push_back(sc.predicted_energy);
      c.segment_energy_true += sc.true_energy;
      c.segment_energy_predicted += sc.predicted_energy;
    }
    c.steps_executed = steps;
    k0 += steps;
    r.cycles.push_back(std::move(c));
  }
  for (const OnlineCycle& c : r.cycles) {
    r.energy_true += c.segment_energy_true;
    r.energy_predicted += c.segment_energy_predicted;
  }
  r.terminal_residual = TerminalResidual(problem, x);
  r.terminal_violation = r.terminal_residual.cwiseAbs().maxCoeff();
  r.J_true = r.energy_true + Penalty(problem, r.terminal_residual);
  return r;
}

}  // namespace ocpb
