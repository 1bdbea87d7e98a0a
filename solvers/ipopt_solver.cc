#include "solvers/ipopt_solver.h"

#include <stdexcept>

#include "solvers/nlp_solve.h"

namespace ocpb {

IpoptSolver::IpoptSolver(Options options) : options_(std::move(options)) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("ipopt options: " + error);
}

SolveResult IpoptSolver::Solve(const Ocp& ocp, const SolveRequest& request) const {
  NlpScaling scaling;
  const Options options =
      Options::FromStrings(ExtractScalingOptions(request.options, &scaling), options_);
  return SolveTranscribed(name(), ocp, request, scaling, [&](const TranscribedNlp& nlp) {
    return SolveNlpWithIpopt(nlp, nlp.StartingPoint(), options);
  });
}

}  // namespace ocpb
