#include "solvers/nlopt_solver.h"

#include <stdexcept>

#include "solvers/nlp_solve.h"

namespace ocpb {

NloptSolver::NloptSolver(Options options) : options_(std::move(options)) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument(error);
}

const OptionSchema& NloptSolver::Schema() { return Options::Schema(); }

NloptSolver::Options NloptSolver::ApplyOptions(const OptionMap& options, const Options& base) {
  return Options::Apply(options, base);
}

SolveResult NloptSolver::Solve(const Ocp& ocp, const SolveRequest& request) const {
  const Options options = ApplyOptions(request.options, options_);
  // NLopt's algorithms take no starting multipliers: a mesh refinement's mapped ones are unused.
  return SolveTranscribed(
      name(), ocp, request, [&](const TranscribedNlp& nlp, const Vec& z0, const NlpMultipliers&) {
        return SolveNlpWithNlopt(nlp, z0, options);
      });
}

}  // namespace ocpb
