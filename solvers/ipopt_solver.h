// The "ipopt" solver: a transcription of the problem, solved by Ipopt.
#pragma once

#include <string>

#include "solvers/ipopt_adapter.h"
#include "solvers/solver.h"

namespace ocpb {

/// Solves an Ocp by transcribing it (SolveRequest::transcription: "euler", "trapezoid",
/// "hermite-simpson", "lgr" with SolveRequest::degree, or "single-shooting") into a sparse NLP on
/// SolveRequest::grid and running Ipopt (interior point, filter line search; Wächter & Biegler,
/// Math. Prog. 106, 2006) with MUMPS from the transcription's starting point, built from
/// SolveRequest::initial_guess (Ocp::NominalControl() projected onto U when absent).
///
/// The result: controls from the transcription (what the evaluator judges), its states, costates
/// from Ipopt's constraint multipliers (TranscribedNlp::Costates), the NLP objective, Ipopt's
/// status verbatim with its grouping (MapIpoptStatus), one history row per Ipopt iteration,
/// Ipopt's own iteration count and CPU time (solver_stats "ipopt_cpu_seconds"), and the whole
/// solve's CPU/wall time (transcription included) in cpu_seconds / wall_seconds.
/// SolveRequest::options are Ipopt options (IpoptOptions::Schema()) over the constructor's;
/// SolveRequest::transcription_options are the transcription's (scaling, LGR's degree).
class IpoptSolver final : public Solver {
 public:
  using Options = IpoptOptions;
  explicit IpoptSolver(Options options = Options());
  /// Its options (Options::Schema()) and their application over `base` (throws
  /// std::invalid_argument naming the key and the rule).
  static const OptionSchema& Schema();
  static Options ApplyOptions(const OptionMap& options, const Options& base = Options());
  std::string name() const override { return "ipopt"; }
  /// Throws std::invalid_argument for an unknown option or transcription, or a request the
  /// transcription rejects; every numerical outcome is the result's status.
  SolveResult Solve(const Ocp& ocp, const SolveRequest& request) const override;
  const Options& options() const { return options_; }

 private:
  Options options_;
};

}  // namespace ocpb
