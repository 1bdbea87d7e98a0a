#include "drivers/online/online_scenario.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/option_binding.h"
#include "problems/channel/channel_memory.h"
#include "problems/channel/measurement_sampling.h"
#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

const OptionBinding<OnlineScenarioSettings>& Binding() {
  static const OptionBinding<OnlineScenarioSettings> table = [] {
    using S = OnlineScenarioSettings;
    OptionBinding<S> t("online");
    t.Number("update_period",
             &S::update_period,
             "s between channel updates (a multiple of the step tf/N)",
             OptionBounds::Above(0));
    t.Integer("initial_measurements",
              &S::initial_measurements,
              "measurements known at t0 = 0",
              OptionBounds::AtLeast(3));
    t.Integer("measurements_per_update",
              &S::measurements_per_update,
              "new measurements at each update",
              OptionBounds::AtLeast(1));
    t.Text("placement",
           &S::placement,
           "where new measurements are taken: at random, along the path driven since the last "
           "update, along the rest of the plan",
           {"random", "path", "plan"});
    t.Number("map_resolution",
             &S::map_resolution,
             "grid of the re-predicted s map, m (>= truth_resolution)",
             OptionBounds::Above(0));
    t.OptionalNumber("truth_resolution",
                     &S::truth_resolution,
                     "grid of the simulated channel, m",
                     OptionBounds::Above(0),
                     "the problem's grid_step");
    t.OptionalNumber("workspace",
                     &S::workspace,
                     "side of the simulated square workspace, m",
                     OptionBounds::Above(0),
                     "the problem's workspace");
    t.Integer("refresh",
              &S::refresh,
              "1: refresh the prediction at every update; 0: never (a control experiment)",
              OptionBounds::Closed(0, 1));
    t.Number("region_margin",
             &S::region_margin,
             "re-predict only around the robot, D and its plan, grown by this margin, m (0: "
             "everywhere)",
             OptionBounds::AtLeast(0));
    t.Number("smap_resolution",
             &S::smap_resolution,
             "grid of the s maps in the record, m",
             OptionBounds::Above(0));
    t.Text("estimator",
           &S::estimator,
           "channel parameter estimator (empty: the problem's)",
           {"binned", "ml", "reml"});
    return t;
  }();
  return table;
}

[[noreturn]] void Refuse(const std::string& what) { throw std::invalid_argument(what); }

std::string Num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// The solver and its options for the plan at t0 = 0 and for the re-plans: the re-plans take the
// solver's replan_defaults (a warm start near the optimum), then the case's options, then its
// replan_options.
void ResolveMethod(const OnlineScenarioRequest& in, OnlineReplanningOptions* r) {
  const SolverInfo& sinfo = FindSolver(in.solver);
  r->solver = in.solver;
  r->transcription = in.transcription;
  if (sinfo.uses_transcription && r->transcription.empty()) r->transcription = "euler";
  if (!sinfo.uses_transcription && !r->transcription.empty()) {
    Refuse("solver '" + in.solver + "' takes no transcription");
  }
  if (sinfo.uses_transcription) {
    r->transcription_options =
        FindTranscription(r->transcription).options.Resolve(in.transcription_options);
  } else if (!in.transcription_options.empty()) {
    Refuse("solver '" + in.solver + "' takes no transcription options");
  }
  r->offline_options = sinfo.options.Resolve(in.options);
  OptionMap replan = sinfo.options.Resolve(sinfo.replan_defaults);
  for (const auto& [k, v] : r->offline_options) replan.Set(k, v);
  try {
    for (const auto& [k, v] : sinfo.options.Resolve(in.replan_options)) replan.Set(k, v);
  } catch (const std::invalid_argument& e) {
    Refuse(std::string("replan_options: ") + e.what());
  }
  r->replan_options = replan;
  if (sinfo.check_options) {
    sinfo.check_options(r->offline_options);
    try {
      sinfo.check_options(r->replan_options);
    } catch (const std::invalid_argument& e) {
      Refuse(std::string("replan_options: ") + e.what());
    }
  }
}

// The channel of the scenario: the problem's channel parameters over the settings' grids.
void ResolveChannel(const Parameters& p, const OnlineScenarioSettings& s, OnlineScenario* out) {
  const double workspace = s.workspace.value_or(p.Scalar("workspace"));
  const double truth_h = s.truth_resolution.value_or(p.Scalar("grid_step"));
  if (workspace / truth_h > 5000.0 || workspace / truth_h < 8.0) {
    Refuse("online.workspace, online.truth_resolution: need 8 to 5000 cells per side (got " +
           Num(workspace) + " m at " + Num(truth_h) + " m)");
  }
  out->problem.workspace = workspace;
  OnlineChannelOptions& c = out->channel;
  c.truth.k_pl = p.Scalar("K_PL");
  c.truth.n_pl = p.Scalar("n_PL");
  c.truth.xi = p.Scalar("xi");
  c.truth.eta = p.Scalar("eta");
  c.truth.rho = p.Scalar("rho");
  c.truth.base_station = p.Vector("base");
  c.truth.distance_floor = p.Scalar("distance_floor");
  c.simulation.multipath.rician_k = p.Scalar("rician_K");
  c.predictor.units.noise_dbm = p.Scalar("N0_dBm");
  c.estimate = p.Integer("estimate") == 1;
  c.simulation.grid = GridSpec::Workspace(workspace, workspace, truth_h);
  if (!c.simulation.grid.Contains(c.truth.base_station)) {
    Refuse("base: (" + Num(c.truth.base_station.x()) + ", " + Num(c.truth.base_station.y()) +
           ") lies outside the workspace [0, " + Num(workspace) + "]^2");
  }
  c.map_resolution = s.map_resolution;
  if (!(c.map_resolution >= truth_h) || workspace / c.map_resolution < 4.0) {
    Refuse("online.map_resolution: must be >= truth_resolution and give >= 4 cells per side");
  }
  c.region_margin = s.region_margin;
  c.estimation.method = s.estimator.empty() ? EstimationMethodFromCode(p.Integer("estimator"))
                                            : EstimationMethodFromString(s.estimator);
  c.refresh = s.refresh == 1;
  std::string error;
  if (!c.IsValid(&error)) Refuse("online: " + error);
  out->smap_resolution = s.smap_resolution;
  if (!(s.smap_resolution >= truth_h) || workspace / s.smap_resolution < 2.0) {
    Refuse("online.smap_resolution: must be >= truth_resolution");
  }
}

// The update period must fall on the grid, and every measurement needs its own truth cell.
void CheckSchedule(const OnlineScenario& s) {
  const OnlineReplanningOptions& r = s.replanning;
  const double h = s.problem.tf / r.intervals;
  const double steps = r.update_period / h;
  if (std::abs(steps - std::round(steps)) > 1e-6 * std::max(1.0, steps) || std::round(steps) < 1) {
    Refuse("online.update_period: " + Num(r.update_period) +
           " s is not a positive multiple of the step tf/N = " + Num(h) + " s");
  }
  const GridSpec& g = s.channel.simulation.grid;
  // The cells a measurement may be drawn from (beyond the distance floor of the base station).
  const double cells = static_cast<double>(EligibleMeasurementPoints(g, s.channel.truth));
  const double updates = std::ceil(r.intervals / std::round(steps)) - 1;
  const double needed = r.initial_measurements + updates * r.measurements_per_update;
  if (2 * needed > cells) {
    Refuse("online: " + Num(needed) + " measurements in all need at least " + Num(2 * needed) +
           " truth cells beyond the base station's distance floor (have " + Num(cells) + ")");
  }
  // The simulated truth and the re-predicted map, and the GP of every measurement so far.
  const double map_side = s.problem.workspace / s.channel.map_resolution + 1.0;
  CheckChannelMemory(needed,
                     "online.initial_measurements, online.measurements_per_update",
                     static_cast<double>(g.num_points()) + map_side * map_side,
                     "online.truth_resolution");
}

}  // namespace

const OptionSchema& OnlineScenarioSchema() { return Binding().schema(); }

OnlineScenario ResolveOnlineScenario(const OnlineScenarioRequest& in) {
  if (in.problem != "comm-path2d") {
    Refuse("problem: online re-planning is defined for comm-path2d only, got '" + in.problem + "'");
  }
  const OnlineScenarioSettings settings = Binding().Apply(in.settings, OnlineScenarioSettings());
  OnlineScenario s;
  const ProblemInfo& pinfo = FindProblem("comm-path2d");
  s.params = Parameters(pinfo.parameters);
  for (const std::string& a : in.set) {
    const std::string name = a.substr(0, a.find('='));
    if (name == "samples" || name == "channel" || name == "t0") {
      Refuse("set " + name +
             ": not used by online re-planning (the channel is the GP map of the measurements "
             "so far; the run starts at t0 = 0; see --initial-measurements)");
    }
    s.params.SetFromString(a);
  }
  s.problem = CommPath2dOptionsFromParameters(s.params);

  OnlineReplanningOptions& r = s.replanning;
  r.update_period = settings.update_period;
  r.initial_measurements = settings.initial_measurements;
  r.measurements_per_update = settings.measurements_per_update;
  r.placement = MeasurementPlacementFromString(settings.placement);
  r.intervals = in.intervals > 0 ? in.intervals : pinfo.default_intervals;
  ResolveMethod(in, &r);
  std::string error;
  if (!r.IsValid(&error)) Refuse("online." + error);

  ResolveChannel(s.params, settings, &s);
  // The initial state and the problem's own rules, checked now (before a channel is simulated).
  if (!s.problem.IsValid(&error)) Refuse("comm-path2d: " + error);
  if (s.problem.t0 != 0.0) Refuse("t0: the online scenario starts at 0");
  CheckSchedule(s);

  OnlineScenarioSettings effective = settings;
  effective.workspace = s.problem.workspace;
  effective.truth_resolution = settings.truth_resolution.value_or(s.params.Scalar("grid_step"));
  effective.estimator = ToString(s.channel.estimation.method);
  s.settings = Binding().Values(effective);
  return s;
}

}  // namespace ocpb
