// Forward-Euler direct transcription (OCPBench transcription "euler").
#pragma once

#include <memory>
#include <string>

#include "transcriptions/transcription.h"

namespace ocpb {

/// The forward-Euler transcription: on the grid t_0 < ... < t_N (h_k = t_{k+1} - t_k),
///
///   minimize    sum_{k<N} h_k L(t_k, x_k, u_k) + Phi(x_N)
///   subject to  x_{k+1} - x_k - h_k f(t_k, x_k, u_k) = 0     (k = 0..N-1),
///               x_0 = x0                                    (by equal variable bounds),
///               u_k in U,  c(t_k, x_k, u_k) <= 0 (k < N) and c(t_N, x_N, u_{N-1}) <= 0,
///               psi(x_N) = 0                                 (TerminalMode::kHard),
///
/// with Phi = phi (+ sum_i w_i psi_i^2 in TerminalMode::kPenalty). Variables, interleaved in time:
/// z = (x_0, u_0, x_1, u_1, ..., x_{N-1}, u_{N-1}, x_N). Controls are piecewise constant,
/// u(t) = u_k on [t_k, t_{k+1}); the path constraint at t_N uses the left limit u_{N-1}, as the
/// common evaluator does.
///
/// This is exactly DiscreteOcp with Integrator::kEuler, the problem the Hamiltonian descent
/// minimizes: at x = Simulate(U) the NLP objective is its J, and with p_{k+1} = -lambda_k
/// (lambda_k the multiplier of defect k, Lagrangian J + lambda^T g) the NLP's stationarity in
/// x_1..x_N is the discrete adjoint recursion, so Costates() returns DiscreteOcp::Adjoint's
/// Lambda at a KKT point (p_0 from the stationarity in x_0). The starting point simulates the
/// initial controls with Euler, so it is feasible. First order (Betts, "Practical Methods for
/// Optimal Control and Estimation Using Nonlinear Programming", 2nd ed., SIAM 2010, Sec. 4.5).
class EulerTranscription final : public Transcription {
 public:
  std::string name() const override { return "euler"; }
  std::unique_ptr<TranscribedNlp> Transcribe(const Ocp& ocp,
                                             const TranscriptionOptions& options) const override;
};

}  // namespace ocpb
