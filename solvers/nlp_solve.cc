#include "solvers/nlp_solve.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/timer.h"
#include "solvers/registry.h"
#include "transcriptions/single_shooting.h"

namespace ocpb {

std::map<std::string, std::string> ExtractScalingOptions(
    const std::map<std::string, std::string>& options, NlpScaling* scaling) {
  std::map<std::string, std::string> rest;
  for (const auto& [key, value] : options) {
    if (!ParseNlpScalingOption(key, value, scaling)) rest[key] = value;
  }
  return rest;
}

std::unique_ptr<TranscribedNlp> TranscribeRequest(const Ocp& ocp,
                                                  const SolveRequest& request,
                                                  const NlpScaling& scaling) {
  if (request.transcription.empty()) {
    std::string names;
    for (const TranscriptionInfo& t : Transcriptions())
      names += (names.empty() ? "" : ", ") + t.name;
    throw std::invalid_argument("an NLP solver needs a transcription (valid: " + names + ")");
  }
  TranscriptionOptions options;
  options.grid = request.grid;
  options.terminal = request.terminal;
  options.initial_guess = request.initial_guess;
  options.degree = request.degree;
  options.scaling = scaling;
  if (request.transcription == SingleShooting::kName) {
    return SingleShooting(request.integrator).Transcribe(ocp, options);
  }
  return FindTranscription(request.transcription).make()->Transcribe(ocp, options);
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

SolveResult SolveTranscribed(const std::string& solver_name,
                             const Ocp& ocp,
                             const SolveRequest& request,
                             const NlpScaling& scaling,
                             const std::function<NlpSolution(const TranscribedNlp& nlp)>& backend) {
  // Single shooting keeps the horizon fixed; the collocation transcriptions make T a variable.
  if (request.transcription == "single-shooting") {
    if (auto refused = FreeFinalTimeNotApplicable(ocp, solver_name + " + single-shooting")) {
      return *refused;
    }
  }
  const Stopwatch watch;
  const std::unique_ptr<TranscribedNlp> nlp = TranscribeRequest(ocp, request, scaling);
  NlpSolution sol = backend(*nlp);

  SolveResult result;
  result.solver = solver_name;
  result.status = sol.status;
  result.solver_status = sol.solver_status;
  result.message = sol.message;
  if (sol.z.size() != nlp->num_variables()) sol.z = nlp->StartingPoint();
  result.controls = nlp->Controls(sol.z);
  result.state_grid = nlp->StateGrid(sol.z);
  result.states = nlp->States(sol.z);
  if (sol.lambda.size() == nlp->num_constraints() && sol.lambda.allFinite()) {
    result.costates = nlp->Costates(sol.z, sol.lambda);
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
  result.cpu_seconds = watch.cpu();
  result.wall_seconds = watch.wall();
  return result;
}

}  // namespace ocpb
