// Trapezoidal direct collocation (OCPBench transcription "trapezoid").
#pragma once

#include <memory>
#include <string>

#include "transcriptions/transcription.h"

namespace ocpb {

/// Trapezoidal collocation: states and controls at the nodes t_0..t_N (h_k = t_{k+1} - t_k),
///
///   minimize    sum_{k<N} h_k/2 (L_k + L_{k+1}) + Phi(x_N),   L_k = L(t_k, x_k, u_k)
///   subject to  x_{k+1} - x_k - h_k/2 (f_k + f_{k+1}) = 0     (k = 0..N-1),
///               x_0 = x0 (equal bounds),  u_k in U,  c(t_k, x_k, u_k) <= 0 (k = 0..N),
///               psi(x_N) = 0 (TerminalMode::kHard),
///
/// z = (x_0, u_0, ..., x_N, u_N). Controls are piecewise linear between the nodes (so a convex U
/// holds between nodes too); the state is the implied quadratic. Second order (Betts, "Practical
/// Methods for Optimal Control and Estimation Using Nonlinear Programming", 2nd ed., SIAM 2010,
/// Sec. 4.6). Costates: at each node, the gradient of the cost-to-go part of the Lagrangian (see
/// CollocationLayout), i.e. p_k = P_k + h_k/2 (L_x + f_x^T P_k) at node k with P_k = -lambda_k,
/// a second-order estimate; p_N = grad of the terminal terms.
class TrapezoidTranscription final : public Transcription {
 public:
  std::string name() const override { return "trapezoid"; }
  std::unique_ptr<TranscribedNlp> Transcribe(const Ocp& ocp,
                                             const TranscriptionOptions& options) const override;
};

}  // namespace ocpb
