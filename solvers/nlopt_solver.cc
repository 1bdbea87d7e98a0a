#include "solvers/nlopt_solver.h"

#include <stdexcept>

#include "solvers/nlp_solve.h"

namespace ocpb {

NloptSolver::NloptSolver(Options options) : options_(std::move(options)) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("nlopt options: " + error);
}

SolveResult NloptSolver::Solve(const Ocp& ocp, const SolveRequest& request) const {
  NlpScaling scaling;
  std::map<std::string, std::string> strings = ExtractScalingOptions(request.options, &scaling);
  if (!request.algorithm.empty()) strings["algorithm"] = request.algorithm;
  const Options options = Options::FromStrings(strings, options_);
  return SolveTranscribed(name(), ocp, request, scaling, [&](const TranscribedNlp& nlp) {
    return SolveNlpWithNlopt(nlp, nlp.StartingPoint(), options);
  });
}

}  // namespace ocpb
