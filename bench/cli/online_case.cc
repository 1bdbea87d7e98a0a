#include "bench/cli/online_case.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>

#include "bench/cli/case_runner.h"
#include "bench/cli/json_values.h"
#include "core/memory_budget.h"
#include "drivers/online/online_scenario.h"
#include "problems/registry.h"
#include "solvers/registry.h"
#include "transcriptions/registry.h"

namespace ocpb {
namespace {

using nlohmann::json;

OnlineScenario Resolve(const CaseSpec& spec) {
  return ResolveOnlineCaseScenario(spec, ResolveMethodOptions(spec));
}

json ChannelJson(const ChannelParameters& p) {
  return json{{"K_PL", p.k_pl}, {"n_PL", p.n_pl}, {"xi", p.xi}, {"eta", p.eta}, {"rho", p.rho}};
}

std::string AggregateStatus(const OnlineResult& r) {
  std::vector<SolveStatus> statuses;
  for (const OnlineCycle& c : r.cycles) statuses.push_back(c.status);
  return WorstCycleStatus(statuses);
}

json CycleJson(const OnlineCycle& c, bool keep_trajectory) {
  json cj{
      {"t0", c.t0},
      {"first_step", c.first_step},
      {"steps_executed", c.steps_executed},
      {"predict_seconds", c.predict.total()},
      {"estimate_seconds", c.predict.estimate_seconds},
      {"factor_seconds", c.predict.factor_seconds},
      {"grid_seconds", c.predict.grid_seconds},
      {"map_seconds", c.predict.map_seconds},
      {"estimation_failed", c.predict.estimation_failed},
      {"map_region", {c.map_grid.x_min, c.map_grid.y_min, c.map_grid.x_max(), c.map_grid.y_max()}},
      {"solve_seconds", c.solve_seconds},
      {"iterations", c.iterations},
      {"status", ToString(c.status)},
      {"solver_status", c.solver_status},
      {"new_measurements", c.new_measurements},
      {"measurements", c.measurements},
      {"measurement_stream", c.measurement_stream},
      {"estimated", ChannelJson(c.estimated)},
      {"planned_energy", JsonNumber(c.planned_energy)},
      {"planned_J", JsonNumber(c.planned_J)},
      {"segment_energy_true", JsonNumber(c.segment_energy_true)},
      {"segment_energy_predicted", JsonNumber(c.segment_energy_predicted)}};
  if (keep_trajectory) cj["plan"] = json{{"t", c.plan_times}, {"x", JsonRows(c.plan_states, 2)}};
  return cj;
}

// Executed and offline paths, the measurements by cycle, and the true and final predicted maps.
void KeepTrajectories(const OnlineScenario& s,
                      const OnlineResult& r,
                      const OnlineChannel& channel,
                      Record* rec) {
  OnlineOutcome& o = *rec->online;
  const json t = r.grid.points();
  o.executed = json{{"t", t}, {"x", JsonRows(r.X, 5)}, {"u", JsonRows(r.U, 3)}};
  o.offline = json{{"t", t}, {"x", JsonRows(r.offline_X, 5)}, {"u", JsonRows(r.offline_U, 3)}};
  json mx = json::array(), my = json::array(), mc = json::array();
  const MeasurementSet& m = channel.measurements();
  size_t k = 0;
  for (size_t ci = 0; ci < r.cycles.size(); ++ci) {
    for (int j = 0; j < r.cycles[ci].new_measurements; ++j, ++k) {
      mx.push_back(m.positions[k].x());
      my.push_back(m.positions[k].y());
      mc.push_back(ci);
    }
  }
  o.measurements = json{{"x", mx}, {"y", my}, {"cycle", mc}};
  std::vector<double> x, y;
  Eigen::MatrixXd predicted, truth;
  channel.SampleLog10(s.smap_resolution, &x, &y, &predicted, &truth);
  rec->s_map = json{{"x", x},
                    {"y", y},
                    {"log10_s", JsonRows(truth)},
                    {"log10_s_predicted", JsonRows(predicted)},
                    {"what",
                     "log10_s: the true channel's 1/CNR (W); log10_s_predicted: the last "
                     "prediction's E[1/CNR]"}};
}

void FillOutcome(const OnlineResult& r, Record* rec) {
  OnlineOutcome& o = *rec->online;
  o.energy_true = r.energy_true;
  o.energy_predicted = r.energy_predicted;
  o.transmit_energy_true = r.transmit_energy_true;
  o.offline_transmit_energy_true = r.offline_transmit_energy_true;
  o.transmit_energy_ratio = r.transmit_energy_true / r.offline_transmit_energy_true;
  o.J_true = r.J_true;
  o.offline_energy_true = r.offline_energy_true;
  o.offline_energy_predicted = r.offline_energy_predicted;
  o.offline_J_true = r.offline_J_true;
  o.offline_terminal_violation = r.offline_terminal_violation;
  o.offline_terminal_residual.assign(
      r.offline_terminal_residual.data(),
      r.offline_terminal_residual.data() + r.offline_terminal_residual.size());
  o.offline_solve_seconds = r.offline_solve_seconds;
  o.energy_ratio = r.energy_true / r.offline_energy_true;
  rec->terminal_violation = r.terminal_violation;
  rec->terminal_residual.assign(r.terminal_residual.data(),
                                r.terminal_residual.data() + r.terminal_residual.size());
  const Vec last = r.X.col(r.X.cols() - 1);
  rec->final_state.assign(last.data(), last.data() + last.size());
  // For the suite summary's columns: J and Jbar of what was executed, on the true channel.
  rec->J = r.J_true;
  rec->Jbar = r.energy_true;
}

}  // namespace

std::string WorstCycleStatus(const std::vector<SolveStatus>& cycles) {
  for (SolveStatus c : cycles) {
    if (IsFailure(c)) return ToString(c);
  }
  for (SolveStatus c : cycles) {
    if (!IsSuccess(c)) return ToString(c);
  }
  for (SolveStatus c : cycles) {
    if (c != SolveStatus::kConverged) return ToString(c);
  }
  return ToString(SolveStatus::kConverged);
}

OnlineScenario ResolveOnlineCaseScenario(const CaseSpec& spec, const MethodOptions& options) {
  OnlineScenarioRequest request;
  request.problem = spec.problem;
  request.set = spec.set;
  request.settings = spec.online;
  request.solver = spec.solver;
  request.transcription = spec.transcription;
  request.transcription_options = options.transcription;
  request.options = options.solver;
  request.replan_options = spec.replan_options;
  request.intervals = spec.intervals;
  return ResolveOnlineScenario(request);
}

CaseEstimate ValidateOnlineCase(const CaseSpec& spec) {
  return CheckOnlineCase(spec, Resolve(spec));
}

CaseEstimate CheckOnlineCase(const CaseSpec& spec, const OnlineScenario& s) {
  // The re-plans solve comm-path2d over the scenario's own channel: its dimensions (from the
  // path-loss channel, which needs no measurements), for the transcription's own rules.
  Parameters dims = s.params;
  dims.Set("channel", {0.0});
  const std::unique_ptr<Ocp> ocp = FindProblem(spec.problem).make_for_checks(dims, spec.seed);
  CaseSpec planned = spec;
  planned.transcription = s.replanning.transcription;
  CheckTranscriptionFits(planned, ocp->nx(), ocp->nu());
  // The plan's grid and every re-plan's (the rest of it, the same step tf / N) span the
  // horizon: the check `solve` and `run` make.
  CheckHorizonSteps(ocp->t0(), ocp->tf(), s.replanning.intervals, "N");
  CaseEstimate estimate;
  // The solves' own memory (every re-plan solves on the same grid), before any channel is
  // simulated or plan solved.
  const std::string& transcription = s.replanning.transcription;
  const double m =
      transcription.empty()
          ? 1.0
          : FindTranscription(transcription).PointsPerInterval(s.replanning.transcription_options);
  estimate.memory_bytes = EstimateMethodMemoryBytes(
      s.replanning.solver, m, ocp->nx(), ocp->nu(), s.replanning.intervals);
  CheckMemoryEstimate(
      estimate.memory_bytes,
      "N",
      fmt::format("{} intervals (nx = {}, nu = {}, {})",
                  s.replanning.intervals,
                  ocp->nx(),
                  ocp->nu(),
                  s.replanning.solver + (transcription.empty() ? "" : " + " + transcription)));
  // `run` holds each record's SummaryPart (the cycles, paths and maps are dropped once the
  // line is written): the fields and the resolved settings.
  estimate.record_bytes = 8192.0;
  return estimate;
}

Record RunOnlineCase(const CaseSpec& spec) { return RunOnlineCase(spec, Resolve(spec)); }

Record RunOnlineCase(const CaseSpec& spec, const OnlineScenario& s) {
  OnlineChannel channel(spec.seed, s.channel);
  OnlineResult r;
  std::string failure;
  try {
    r = RunOnlineReplanning(s.problem, &channel, spec.seed, s.replanning);
  } catch (const std::invalid_argument&) {
    throw;  // the caller's input
  } catch (const std::exception& e) {
    failure = e.what();  // e.g. the robot left the workspace: recorded, a suite goes on
  }

  Record rec = CaseIdentityRecord(spec);
  rec.parameters = s.params.values();
  rec.uses_seed = true;
  rec.transcription = s.replanning.transcription;
  rec.N = s.replanning.intervals;
  rec.terminal = ToString(TerminalMode::kPenalty);
  rec.integrator = ToString(Integrator::kEuler);
  rec.evaluated_with = ToString(Integrator::kEuler);
  rec.options = s.replanning.offline_options.ToText();
  for (const auto& [k, v] : s.replanning.offline_options)
    rec.solver_options[k] = JsonOptionValue(v);
  for (const auto& [k, v] : s.replanning.transcription_options) {
    rec.transcription_options[k] = JsonOptionValue(v);
  }
  rec.online = OnlineOutcome();
  for (const auto& [k, v] : s.settings) rec.online->settings[k] = JsonOptionValue(v);
  rec.online->replan_options = s.replanning.replan_options.ToText();
  if (!failure.empty()) {
    rec.status = ToString(SolveStatus::kError);
    rec.solver_status = "exception";
    rec.message = failure;
    return rec;
  }
  rec.status = AggregateStatus(r);
  rec.solver_status = "";
  rec.message = fmt::format("{} cycles; energy on the true channel: online {:.6g}, offline {:.6g}",
                            r.cycles.size(),
                            r.energy_true,
                            r.offline_energy_true);
  double cpu = 0.0;
  int iterations = 0;
  for (const OnlineCycle& c : r.cycles) {
    rec.online->cycles.push_back(CycleJson(c, spec.keep_trajectory));
    cpu += c.predict.total() + c.solve_seconds;
    iterations += std::max(c.iterations, 0);
  }
  FillOutcome(r, &rec);
  rec.iterations = iterations;
  rec.cpu_seconds = cpu;
  rec.repeats = 1;
  if (spec.keep_trajectory) KeepTrajectories(s, r, channel, &rec);
  return rec;
}

}  // namespace ocpb
