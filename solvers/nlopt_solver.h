// The "nlopt" solver: a transcription of the problem, solved by an NLopt algorithm.
#pragma once

#include <string>

#include "solvers/nlopt_adapter.h"
#include "solvers/solver.h"

namespace ocpb {

/// Solves an Ocp by transcribing it (SolveRequest::transcription, as for IpoptSolver; the dense
/// NLopt algorithms suit "single-shooting" best) and running the NLopt algorithm named by the
/// option "algorithm" (NloptOptions::algorithm) with dense gradients.
///
/// Honest scope: every NLopt algorithm here works on dense m x n constraint Jacobians and LD_SLSQP
/// on dense n x n matrices, so cost grows like n m to n^3 where Ipopt's grows like n. Requests
/// beyond the limits of NloptOptions (measured in solvers/README-nlp.md) are refused up front with
/// SolveStatus::kNotApplicable and the reason, as are algorithm/constraint combinations the
/// algorithm cannot take (LD_MMA with equalities, LD_LBFGS with any constraint).
///
/// The result: controls, the NLP objective, NLopt's result name verbatim ("FTOL_REACHED", ...)
/// with its grouping (MapNloptResult; a "converged" point that violates the constraints by more
/// than feasibility_tol is reported kInfeasible), one history row per objective evaluation, and
/// iterations = objective evaluations. NLopt gives no multipliers, hence no costates.
/// SolveRequest::options are NloptOptions keys (NloptOptions::Schema(); the algorithm is the
/// option "algorithm") over the constructor's; SolveRequest::transcription_options are the
/// transcription's (scaling, LGR's degree).
class NloptSolver final : public Solver {
 public:
  using Options = NloptOptions;
  explicit NloptSolver(Options options = Options());
  /// Its options (Options::Schema()) and their application over `base` (throws
  /// std::invalid_argument naming the key and the rule).
  static const OptionSchema& Schema();
  static Options ApplyOptions(const OptionMap& options, const Options& base = Options());
  std::string name() const override { return "nlopt"; }
  /// Throws std::invalid_argument for an unknown option, algorithm or transcription, or a request
  /// the transcription rejects.
  SolveResult Solve(const Ocp& ocp, const SolveRequest& request) const override;
  const Options& options() const { return options_; }

 private:
  Options options_;
};

}  // namespace ocpb
