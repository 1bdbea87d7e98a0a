#include "bench/cli/resolved_case.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "bench/cli/online_case.h"
#include "bench/cli/output_place.h"
#include "core/memory_budget.h"
#include "transcriptions/registry.h"

namespace ocpb {
namespace {

std::string Bytes(double b) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB"};
  int i = 0;
  while (b >= 1000.0 && i < 5) {
    b /= 1000.0;
    ++i;
  }
  return fmt::format("{:.3g} {}", b, units[i]);
}

// A transcription's scaling options sized for the problem (nx, nu entries).
void CheckScalingFits(const TranscriptionInfo& tinfo,
                      const OptionMap& transcription_options,
                      int nx,
                      int nu) {
  const TranscriptionOptions options = tinfo.Configure(transcription_options);
  std::string error;
  if (!options.scaling.IsValidFor(nx, nu, &error)) {
    throw std::invalid_argument("options: " + tinfo.name + " " + error);
  }
}

// `run` holds each record's SummaryPart (bench/cli/run_outputs.h): its fields and its history,
// one row (an IterationRecord, 56 bytes, and the vector's slack) per iteration, at most the
// iteration limit the solver's options give, and 1000 rows when they give none.
double RecordBytes(const OptionMap& solver_options) {
  double rows = 1000.0;
  for (const char* limit : {"max_iterations", "max_iter"}) {
    const OptionValue* v = solver_options.Find(limit);
    if (v != nullptr && v->kind() == OptionValue::Kind::kInteger) {
      rows = std::min(rows, static_cast<double>(std::max<std::int64_t>(v->integer(), 0)) + 1.0);
    }
  }
  return 2048.0 + 64.0 * rows;
}

// Checks that need neither the problem nor the names: the spec's own rules, the files the
// options name, and the iteration limits as sizes.
void CheckSpecAndSizes(const CaseSpec& spec) {
  // A file a solve writes (Ipopt's output_file) must be writable where it is named, checked
  // here as any output place is (the name's length, the folder, permissions), not when the
  // solver opens it after the work before the solve.
  for (const OptionMap* options : {&spec.options, &spec.replan_options}) {
    for (const auto& [name, value] : *options) {
      if (FilePlan::IsOutputFileOption(name) && !value.empty() && !value.ToText().empty()) {
        CheckOutputFile(value.ToText(), "options: " + name);
      }
    }
  }
  // A solver that keeps a history row per iteration may reserve them all before its first
  // iteration (the Hamiltonian descent does): its iteration limit is a size too, of every
  // solve and of online re-plans.
  for (const auto& [options, field] :
       {std::pair{&spec.options, "options: max_iterations"},
        std::pair{&spec.replan_options, "replan_options: max_iterations"}}) {
    const OptionValue* limit = options->Find("max_iterations");
    if (limit == nullptr) continue;
    std::optional<double> rows;
    if (limit->kind() == OptionValue::Kind::kInteger) {
      rows = static_cast<double>(limit->integer()) + 1.0;
    } else if (limit->kind() == OptionValue::Kind::kText) {
      rows = ParseNumberText(limit->text());  // refused by the solver's schema if not a count
      if (rows) *rows += 1.0;
    }
    if (rows && *rows > 0.0) {
      CheckMemoryEstimate(
          64.0 * *rows, field, fmt::format("{:.0f} history rows (one per iteration)", *rows));
    }
  }
}

}  // namespace

void CheckTranscriptionFits(const CaseSpec& spec, int nx, int nu) {
  if (spec.transcription.empty() || !FindSolver(spec.solver).uses_transcription) return;
  CheckScalingFits(
      FindTranscription(spec.transcription), ResolveMethodOptions(spec).transcription, nx, nu);
}

double EstimateCaseMemoryBytes(const CaseSpec& spec, int nx, int nu, int intervals) {
  const double m = spec.transcription.empty()
                       ? 1.0
                       : FindTranscription(spec.transcription)
                             .PointsPerInterval(ResolveMethodOptions(spec).transcription);
  return EstimateMethodMemoryBytes(spec.solver, m, nx, nu, intervals);
}

double EstimateMethodMemoryBytes(
    const std::string& solver, double points_per_interval, int nx, int nu, int intervals) {
  const double m = points_per_interval;
  const double nodes = static_cast<double>(intervals) * m + 1.0;
  const double w = nx + nu;
  double bytes = 512.0 * w * nodes;
  if (FindSolver(solver).factorizes_sparse_matrices) {
    bytes += 320.0 * nodes * w * (w + (m + 1.0) * nx);
  }
  return bytes;
}

double CaseMemoryBudgetBytes() { return MemoryBudgetBytes(); }

double EstimateRecordBytes(const CaseSpec& spec, int /*nx*/, int /*nu*/, int /*intervals*/) {
  MethodOptions options;
  try {
    options = ResolveMethodOptions(spec);
  } catch (const std::invalid_argument&) {
    // refused by ValidateCase with its own message
  }
  return RecordBytes(options.solver);
}

// The horizon must be long enough for its grid: each step of the judge's 10x finer grid a
// normal double, resolvable next to the horizon's ends (else the grids collapse at solve time,
// with a message about a "time grid" that names no input).
void CheckHorizonSteps(double t0, double tf, int N, const std::string& which) {
  const double fine_step = (tf - t0) / N / 10.0;
  const double scale = std::max(std::abs(t0), std::abs(tf));
  if (!(fine_step >= std::numeric_limits<double>::min()) || !(fine_step >= 1e-12 * scale)) {
    throw std::invalid_argument(fmt::format(
        "tf: the horizon [t0, tf] = [{:g}, {:g}] is too short for {} = {} intervals: a tenth of "
        "each step (tf - t0) / N must be a normal number (>= {:g}) and at least 1e-12 "
        "max(|t0|, |tf|) (choose a larger tf, --set tf=..., or fewer intervals)",
        t0,
        tf,
        which,
        N,
        std::numeric_limits<double>::min()));
  }
}

ResolvedCase ResolveAndValidate(const CaseSpec& given) {
  // The names and options first, then the spec's own rules (the order `solve` has always
  // reported them in).
  ResolvedCase c;
  c.spec = ResolveCase(given, &c.options);
  const CaseSpec& spec = c.spec;
  spec.Validate();
  CheckSpecAndSizes(spec);
  c.solver = &FindSolver(spec.solver);
  if (spec.kind == "online") {
    // The scenario names its problem rule ("defined for comm-path2d only") before any lookup.
    auto scenario = std::make_shared<OnlineScenario>(ResolveOnlineCaseScenario(spec, c.options));
    c.estimate = CheckOnlineCase(spec, *scenario);
    c.online = std::move(scenario);
    c.problem = &FindProblem(spec.problem);
    if (!spec.transcription.empty()) c.transcription = &FindTranscription(spec.transcription);
    return c;
  }
  c.problem = &FindProblem(spec.problem);
  const ProblemInfo& pinfo = *c.problem;
  if (c.solver->uses_transcription) {
    if (spec.transcription.empty()) {
      throw std::invalid_argument("solver '" + spec.solver +
                                  "' needs a transcription (--transcription)");
    }
    c.transcription = &FindTranscription(spec.transcription);
  } else if (!spec.transcription.empty()) {
    throw std::invalid_argument("solver '" + spec.solver + "' takes no transcription");
  }
  c.parameters = Parameters(pinfo.parameters);
  for (const std::string& a : spec.set) c.parameters.SetFromString(a);
  // The problem's own cross-field rules (t0 < tf, S and D in the workspace, the channel's
  // options, ...), without simulating a channel; a problem without a cheaper build for checks
  // is built once, here, and solved as built.
  std::shared_ptr<const Ocp> ocp;
  if (pinfo.make_for_checks) {
    ocp = pinfo.make_for_checks(c.parameters, spec.seed);
  } else {
    ocp = pinfo.make(c.parameters, spec.seed);
    c.built_problem = ocp;
  }
  if (!ocp) throw std::logic_error("problem '" + spec.problem + "': make returned no problem");
  c.nx = ocp->nx();
  c.nu = ocp->nu();
  if (c.transcription != nullptr) {
    CheckScalingFits(*c.transcription, c.options.transcription, c.nx, c.nu);
  }
  if (!spec.initial_guess.empty()) {
    c.initial_guess = ReadInitialGuess(spec.initial_guess);
    CheckInitialGuess(*c.initial_guess, *ocp, spec.initial_guess);
  }
  c.intervals = spec.intervals > 0 ? spec.intervals : pinfo.default_intervals;
  // Mesh refinement may solve meshes up to mesh_max_nodes nodes: the largest one sets the size.
  int N = c.intervals;
  std::string which = "N";
  MeshRefinementOptions mesh;
  double points_per_interval = 1.0;
  if (c.transcription != nullptr) {
    mesh = c.transcription->Configure(c.options.transcription).mesh;
    points_per_interval = c.transcription->PointsPerInterval(c.options.transcription);
    if (mesh.enabled() && mesh.max_nodes - 1 > N) {
      N = mesh.max_nodes - 1;
      which = "mesh_max_nodes";
    }
  }
  CheckHorizonSteps(ocp->t0(), ocp->tf(), N, which);
  const double need = EstimateMethodMemoryBytes(spec.solver, points_per_interval, c.nx, c.nu, N);
  const double budget = CaseMemoryBudgetBytes();
  c.estimate.memory_bytes = need;
  c.estimate.record_bytes = RecordBytes(c.options.solver);
  if (need > budget) {
    throw std::invalid_argument(fmt::format(
        "{}: {} intervals need about {} by OCPBench's estimate (nx = {}, nu = {}, {}), beyond "
        "this machine's memory budget of {} (half its physical memory)",
        which,
        N,
        Bytes(need),
        c.nx,
        c.nu,
        spec.solver + (spec.transcription.empty() ? "" : " + " + spec.transcription),
        Bytes(budget)));
  }
  // h-refinement builds each refined mesh whole (each interval split in up to
  // 1 + mesh_max_new_points pieces) before comparing it with mesh_max_nodes: that mesh is
  // sized here, before anything is solved.
  if (c.transcription != nullptr && mesh.enabled() &&
      c.options.transcription.Has("mesh_max_new_points")) {
    if (mesh.max_new_points > mesh.max_nodes) {
      throw std::invalid_argument(fmt::format(
          "options: mesh_max_new_points: must be at most mesh_max_nodes = {} (a refined mesh "
          "has at most that many nodes), got {}",
          mesh.max_nodes,
          mesh.max_new_points));
    }
    const double refined_points = static_cast<double>(N) * (1.0 + mesh.max_new_points) + 1.0;
    CheckMemoryEstimate(
        16.0 * refined_points,
        "mesh_max_new_points",
        fmt::format("refined meshes of up to {:.4g} points ({} intervals, each split in up to "
                    "1 + {} pieces)",
                    refined_points,
                    N,
                    mesh.max_new_points));
  }
  return c;
}

CaseEstimate ValidateCase(const CaseSpec& spec) { return ResolveAndValidate(spec).estimate; }

}  // namespace ocpb
