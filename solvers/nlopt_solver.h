// The "nlopt" solver: a transcription of the problem, solved by an NLopt algorithm.
#pragma once

#include <string>

#include "solvers/nlopt_adapter.h"
#include "solvers/solver.h"

namespace ocpb {

/// Solves an Ocp by transcribing it (SolveRequest::transcription, as for IpoptSolver; the dense
/// NLopt algorithms suit "single-shooting" best) and running the NLopt algorithm named by
/// SolveRequest::algorithm (or Options::algorithm when empty; see NloptOptions) with dense
/// gradients.
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
/// SolveRequest::options are NloptOptions keys (NloptOptions::FromStrings) over the constructor's;
/// the keys objective_scale, state_scale and control_scale set the transcription's NlpScaling.
class NloptSolver final : public Solver {
 public:
  using Options = NloptOptions;
  explicit NloptSolver(Options options = Options());
  std::string name() const override { return "nlopt"; }
  /// Throws std::invalid_argument for an unknown option, algorithm or transcription, or a request
  /// the transcription rejects.
  SolveResult Solve(const Ocp& ocp, const SolveRequest& request) const override;
  const Options& options() const { return options_; }

 private:
  Options options_;
};

}  // namespace ocpb
