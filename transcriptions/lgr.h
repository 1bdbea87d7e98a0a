// Legendre-Gauss-Radau (pseudospectral) collocation on the grid's intervals (OCPBench
// transcription "lgr").
#pragma once

#include <memory>
#include <string>

#include "transcriptions/transcription.h"

namespace ocpb {

/// Legendre-Gauss-Radau collocation, one polynomial per grid interval (an hp mesh with the
/// grid's intervals as segments and K = TranscriptionOptions::degree points in each).
///
/// On interval k, t = t_k + h_k (tau + 1)/2 with the K LGR points -1 = tau_0 < ... < tau_{K-1} < 1
/// (RadauNodes). The state is the polynomial of degree K through X_{k,0..K-1} at the LGR points
/// and X_{k+1,0} (the next interval's first point, x(tf) for the last interval) at tau_K = +1;
/// the control is the polynomial of degree K - 1 through U_{k,0..K-1}. Then
///
///   sum_{j=0..K} D_ij X_{k,j} - h_k/2 f(t_ki, X_{k,i}, U_{k,i}) = 0      (i = 0..K-1)
///   minimize  sum_k h_k/2 sum_i w_i L(t_ki, X_{k,i}, U_{k,i}) + Phi(x(tf)),
///
/// x(t0) = x0 by equal bounds, U_{k,i} in U and c(t_ki, X_{k,i}, U_{k,i}) <= 0 at every LGR point
/// (not at tf, which is not a collocation point), psi(x(tf)) = 0 in TerminalMode::kHard.
/// z = (X_{0,0}, U_{0,0}, ..., X_{0,K-1}, U_{0,K-1}, X_{1,0}, ..., x(tf)); state_grid() holds all
/// LGR points and tf. The quadrature is exact to degree 2K - 2 and the scheme converges at
/// order 2K - 1 in h for smooth solutions (exponentially in K). K = 1 is forward Euler.
/// References: Garg, Patterson, Hager, Rao, Benson, Huntington, "A unified framework for the
/// numerical solution of optimal control problems using pseudospectral methods", Automatica 46
/// (2010) 1843-1851; Garg et al., "Direct trajectory optimization and costate estimation ... using
/// a Radau pseudospectral method", Comput. Optim. Appl. 49 (2011) 335-358.
///
/// Controls for the evaluator: on each interval the Lagrange polynomial through its K control
/// values (extrapolated on [tau_{K-1}, 1]; left limits at t_{k+1} use interval k), projected onto
/// U. Costates: at each interval start and at tf the cost-to-go gradient of the Lagrangian (see
/// CollocationLayout), which is the Radau costate at tau = -1 and converges at order 2K - 1; at the
/// interior LGR points p = -lambda_{k,i} / w_i (lambda the defect multiplier; Garg et al. 2011),
/// which converges at order K in h.
class LgrTranscription final : public Transcription {
 public:
  std::string name() const override { return "lgr"; }
  /// Throws std::invalid_argument unless 1 <= options.degree <= kMaxRadauPoints (60).
  std::unique_ptr<TranscribedNlp> Transcribe(const Ocp& ocp,
                                             const TranscriptionOptions& options) const override;
};

}  // namespace ocpb
