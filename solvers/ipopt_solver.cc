#include "solvers/ipopt_solver.h"

#include <stdexcept>

#include "solvers/nlp_solve.h"

namespace ocpb {

IpoptSolver::IpoptSolver(Options options) : options_(std::move(options)) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument(error);
}

const OptionSchema& IpoptSolver::Schema() { return Options::Schema(); }

IpoptSolver::Options IpoptSolver::ApplyOptions(const OptionMap& options, const Options& base) {
  return Options::Apply(options, base);
}

SolveResult IpoptSolver::Solve(const Ocp& ocp, const SolveRequest& request) const {
  const Options options = ApplyOptions(request.options, options_);
  return SolveTranscribed(name(),
                          ocp,
                          request,
                          [&](const TranscribedNlp& nlp, const Vec& z0, const NlpMultipliers& y0) {
                            return SolveNlpWithIpopt(nlp, z0, options, y0);
                          });
}

}  // namespace ocpb
