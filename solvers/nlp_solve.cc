#include "solvers/nlp_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/timer.h"
#include "solvers/mesh_refinement_loop.h"
#include "transcriptions/registry.h"

namespace ocpb {

const TranscriptionInfo& RequestTranscription(const SolveRequest& request) {
  if (request.transcription.empty()) {
    std::string names;
    for (const TranscriptionInfo& t : Transcriptions())
      names += (names.empty() ? "" : ", ") + t.name;
    throw std::invalid_argument("an NLP solver needs a transcription (valid: " + names + ")");
  }
  return FindTranscription(request.transcription);
}

TranscriptionOptions TranscriptionOptionsFor(const SolveRequest& request) {
  TranscriptionOptions options =
      RequestTranscription(request).Configure(request.transcription_options);
  options.grid = request.grid;
  options.terminal = request.terminal;
  options.initial_guess = request.initial_guess;
  options.initial_states = request.initial_states;
  options.integrator = request.integrator;
  return options;
}

std::unique_ptr<TranscribedNlp> TranscribeRequest(const Ocp& ocp, const SolveRequest& request) {
  return RequestTranscription(request).make()->Transcribe(ocp, TranscriptionOptionsFor(request));
}

double NlpViolation(const Nlp& nlp, ConstVecRef z) {
  Vec zl, zu, gl, gu;
  nlp.Bounds(&zl, &zu, &gl, &gu);
  double worst = 0.0;
  for (int i = 0; i < z.size(); ++i) {
    worst = std::max({worst, zl[i] - z[i], z[i] - zu[i]});
  }
  if (nlp.num_constraints() > 0) {
    Vec g(nlp.num_constraints());
    if (!nlp.Constraints(z, g) || !g.allFinite()) return std::numeric_limits<double>::quiet_NaN();
    for (int j = 0; j < g.size(); ++j) worst = std::max({worst, gl[j] - g[j], g[j] - gu[j]});
  }
  return worst;
}

namespace {

// One transcription on options.grid and one backend run: the result (without timing) and what
// mesh refinement needs from that solution.
MeshSolve SolveOnMesh(const std::string& solver_name,
                      const TranscriptionInfo& info,
                      const Ocp& ocp,
                      const TranscriptionOptions& options,
                      const NlpBackend& backend) {
  const NlpScaling& scaling = options.scaling;
  const std::unique_ptr<TranscribedNlp> nlp = info.make()->Transcribe(ocp, options);
  const Vec z0 = nlp->StartingPoint();
  const NlpMultipliers y0 = options.initial_multipliers
                                ? nlp->StartingMultipliers(z0, *options.initial_multipliers)
                                : NlpMultipliers();
  NlpSolution sol = backend(*nlp, z0, y0);

  MeshSolve out;
  SolveResult& result = out.result;
  result.solver = solver_name;
  result.status = sol.status;
  result.solver_status = sol.solver_status;
  result.message = sol.message;
  if (sol.z.size() != nlp->num_variables()) sol.z = nlp->StartingPoint();
  result.controls = nlp->Controls(sol.z);
  result.state_grid = nlp->StateGrid(sol.z);
  result.states = nlp->States(sol.z);
  if (ocp.HasFreeInitialState() && result.states.rows() == ocp.nx() && result.states.cols() > 0) {
    result.initial_state = result.states.col(0);
  }
  if (sol.lambda.size() == nlp->num_constraints() && sol.lambda.allFinite()) {
    result.costates = nlp->Costates(sol.z, sol.lambda);
    if (result.costates.size() > 0) result.costate_source = "NLP multipliers (" + info.name + ")";
  }
  // Objective values in the problem's units: the transcription's objective scale is undone.
  double f = NAN;
  if (!nlp->Objective(sol.z, &f)) f = NAN;
  result.objective = f / scaling.objective;
  result.iterations = sol.iterations;
  result.history = std::move(sol.history);
  for (IterationRecord& rec : result.history) rec.J /= scaling.objective;
  result.solver_stats = std::move(sol.stats);
  result.solver_stats["nlp_variables"] = nlp->num_variables();
  result.solver_stats["nlp_constraints"] = nlp->num_constraints();
  result.solver_stats["nlp_jacobian_nonzeros"] = static_cast<double>(nlp->jacobian_rows().size());
  result.solver_stats["nlp_violation"] = NlpViolation(*nlp, sol.z);
  if (nlp->HasFinalTimeVariable()) result.solver_stats["final_time"] = nlp->FinalTime(sol.z);
  if (!sol.has_iterate) result.message += " (no iterate: controls are the starting point)";
  if (options.mesh.enabled()) {
    out.errors = nlp->IntervalErrors(sol.z);
    out.order = nlp->IntervalErrorOrder();
    out.states = nlp->StateTrajectory(sol.z);
    out.degrees = nlp->IntervalDegrees();
    out.multipliers_offered = !y0.empty();
    if (options.mesh.warm_multipliers && sol.has_iterate) {
      NlpMultipliers y{sol.lambda, sol.z_lower, sol.z_upper};
      out.multipliers = nlp->MultiplierTrajectoriesAt(sol.z, y);
    }
  }
  return out;
}

}  // namespace

SolveResult SolveTranscribed(const std::string& solver_name,
                             const Ocp& ocp,
                             const SolveRequest& request,
                             const NlpBackend& backend) {
  const TranscriptionInfo& info = RequestTranscription(request);
  ProblemFeatures takes;
  takes.free_final_time = info.takes_free_final_time;
  takes.free_initial_state = info.takes_free_initial_state;
  takes.state_bounds = info.takes_state_bounds;
  takes.boundary_constraints = info.takes_boundary_constraints;
  if (auto refused = FeaturesNotApplicable(ocp, solver_name + " + " + info.name, takes)) {
    refused->solver = solver_name;
    return *refused;
  }
  const Stopwatch watch;
  const TranscriptionOptions options = TranscriptionOptionsFor(request);
  SolveResult result;
  if (options.mesh.enabled()) {
    result = SolveOnRefinedMeshes(options, [&](const TranscriptionOptions& on_mesh) {
      return SolveOnMesh(solver_name, info, ocp, on_mesh, backend);
    });
  } else {
    result = SolveOnMesh(solver_name, info, ocp, options, backend).result;
  }
  result.cpu_seconds = watch.cpu();
  result.wall_seconds = watch.wall();
  return result;
}

}  // namespace ocpb
