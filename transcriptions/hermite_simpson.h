// Hermite-Simpson direct collocation, separated form (OCPBench transcription "hermite-simpson").
#pragma once

#include <memory>
#include <string>

#include "transcriptions/transcription.h"

namespace ocpb {

/// Hermite-Simpson collocation in separated form: on each interval [t_k, t_{k+1}] (h = h_k,
/// midpoint t_m = t_k + h/2) the midpoint state x_m and control u_m are variables, and
///
///   x_{k+1} - x_k - h/6 (f_k + 4 f_m + f_{k+1}) = 0                 (Simpson defect)
///   x_m - (x_k + x_{k+1})/2 - h/8 (f_k - f_{k+1}) = 0               (Hermite interpolation)
///
/// with f_k = f(t_k, x_k, u_k), f_m = f(t_m, x_m, u_m). The objective is Simpson's rule,
/// sum_k h/6 (L_k + 4 L_m + L_{k+1}) + Phi(x_N); x_0 = x0 by equal bounds; u in U at every node
/// and midpoint; c <= 0 at every node and midpoint; psi(x_N) = 0 in TerminalMode::kHard.
/// z = (x_0, u_0, x_{0m}, u_{0m}, x_1, u_1, ..., x_N, u_N); state_grid() holds nodes and
/// midpoints. Fourth order in the states and the objective for smooth problems (Betts,
/// "Practical Methods for Optimal Control and Estimation Using Nonlinear Programming", 2nd ed.,
/// SIAM 2010, Sec. 4.6; Hargraves & Paris, J. Guidance 10 (1987) for the compressed form, which
/// eliminates x_m; the separated form keeps the sparsity simple at the price of nx + nu
/// variables per interval).
///
/// Controls for the evaluator: on each interval the quadratic through (t_k, u_k), (t_m, u_m),
/// (t_{k+1}, u_{k+1}), then projected onto U (the quadratic may overshoot a bound between the
/// points; projection keeps the delivered control admissible and never moves it farther from an
/// admissible optimum). Costates: nodes by the cost-to-go gradient of the Lagrangian (see
/// CollocationLayout), fourth order; midpoints from -lambda_S (lambda_S the Simpson defect's
/// multiplier), which is Simpson's mean (p_k + 4 p_m + p_{k+1})/6 of the costate over the
/// interval: p_m = (-6 lambda_S - p_k - p_{k+1})/4 (also fourth order; -lambda_S alone is second).
class HermiteSimpsonTranscription final : public Transcription {
 public:
  std::string name() const override { return "hermite-simpson"; }
  std::unique_ptr<TranscribedNlp> Transcribe(const Ocp& ocp,
                                             const TranscriptionOptions& options) const override;
};

}  // namespace ocpb
