// Control-only single shooting: the controls are the only unknowns, the states come from
// simulation, and the gradient from the discrete adjoint.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/discrete_ocp.h"
#include "core/integrator.h"
#include "transcriptions/transcription.h"

namespace ocpb {

/// The NLP of single shooting (direct single shooting; Betts, "Practical Methods for Optimal
/// Control and Estimation Using Nonlinear Programming", 2nd ed., SIAM 2010, Sec. 3.5) on a grid
/// t_0 < ... < t_N with piecewise-constant controls:
///
///   z = (u_0, u_1, ..., u_{N-1})            (n = nu N; z[k nu + i] = u_k,i)
///   minimize   J(z) = sum_k ell_k(x_k, u_k) + Phi(x_N)     (DiscreteOcp: x_{k+1} = F_k(x_k, u_k))
///   subject to psi(x_N(z)) = 0                              (hard terminal mode only; rows 0..)
///              |u_k,b - c_b|^2 <= r_b^2                     (each ball block b of U, each k)
///              c(t_k, x_k, u_k) <= 0, k = 0..N-1, and c(t_N, x_N, u_{N-1}) <= 0  (path, if any)
///              bounds: box blocks of U exactly; ball blocks by their bounding box c_b +- r_b.
///
/// F_k and ell_k are one Euler step (default) or one RK4 step (the integrator given to
/// SingleShooting) of the dynamics and the running cost, exactly as core/discrete_ocp.h defines
/// them, so J(z) is DiscreteOcp::Simulate and, with Euler, the very problem the Hamiltonian
/// descent solves. Phi = phi + the terminal penalty in TerminalMode::kPenalty, phi in kHard.
///
/// Derivatives (all exact for the discrete problem; no Hessian, so Ipopt runs limited-memory):
///  - grad J: one backward pass of DiscreteOcp::Adjoint.
///  - d psi(x_N)/dz: one backward matrix pass Lambda_N = psi_x(x_N), block k = Lambda_{k+1} B_k,
///    Lambda_k = Lambda_{k+1} A_k, with the step Jacobians A_k = dF_k/dx, B_k = dF_k/du
///    (StepJacobian). Dense: npsi x n.
///  - path constraints: forward sensitivities S_{k+1} = A_k S_k + [0 .. B_k .. 0], so node k's
///    rows are c_x S_k + c_u, lower block-triangular, O(N^2) work and nonzeros.
/// Evaluations at the same z share one simulation (a one-entry cache), so an NLP object must not
/// be used by two threads at once.
///
/// Scaling (TranscriptionOptions::scaling, see nlp_scaling.h): the objective is multiplied by
/// scaling.objective and control component j is stored as u_j / scaling.control[j] (bounds,
/// starting point, gradient and Jacobian columns follow); constraint rows are not scaled, and
/// state scales do not apply (there are no state variables). Controls() and Costates() return
/// physical values.
///
/// Costates(z, lambda): the discrete adjoint of the Lagrangian J + nu^T psi + sum mu_k^T c_k,
///   p_N = Phi_x + psi_x^T nu + c_x(t_N)^T mu_N,  p_k = A_k^T p_{k+1} + d ell_k/dx + c_x(t_k)^T
///   mu_k,
/// an estimate of p(t_k) in the convention H = p^T f + L. States() is empty, as the interface asks
/// of single shooting: the states are a simulation, not unknowns.
class SingleShootingNlp final : public TranscribedNlp {
 public:
  /// Throws std::invalid_argument when the grid does not span [ocp.t0(), ocp.tf()] or the
  /// initial guess has the wrong number of controls.
  SingleShootingNlp(const Ocp& ocp, const TranscriptionOptions& options, Integrator integrator);

  int num_variables() const override { return nu_ * N_; }
  int num_constraints() const override { return m_; }
  void Bounds(Vec* z_lower, Vec* z_upper, Vec* g_lower, Vec* g_upper) const override;
  /// The initial guess sampled on the grid's intervals (default Ocp::NominalControl()), each u_k
  /// projected onto U.
  Vec StartingPoint() const override;

  bool Objective(ConstVecRef z, double* f) const override;
  bool Gradient(ConstVecRef z, VecRef grad) const override;
  bool Constraints(ConstVecRef z, VecRef g) const override;
  bool JacobianValues(ConstVecRef z, VecRef values) const override;

  /// Piecewise constant on the grid: u(t) = u_k on [t_k, t_{k+1}).
  ControlTrajectory Controls(ConstVecRef z) const override;
  const TimeGrid& state_grid() const override { return docp_.grid(); }
  Mat States(ConstVecRef /*z*/) const override { return Mat(); }
  Mat Costates(ConstVecRef z, ConstVecRef lambda) const override;

  /// The simulated states (nx x (N+1)) at z; empty when the simulation is not finite.
  Mat SimulatedStates(ConstVecRef z) const;
  Integrator integrator() const { return docp_.integrator(); }
  /// First row of each constraint group (hard terminal, ball, path) and its size.
  int terminal_row() const { return 0; }
  int num_terminal_rows() const { return npsi_rows_; }
  int ball_row() const { return npsi_rows_; }
  int num_ball_rows() const { return nball_rows_; }
  int path_row() const { return npsi_rows_ + nball_rows_; }
  int num_path_rows() const { return m_ - npsi_rows_ - nball_rows_; }

  /// One step's derivatives at (x, u) on interval k: A = dF_k/dx (nx x nx), B = dF_k/du
  /// (nx x nu), ell_x = d ell_k/dx, ell_u = d ell_k/du, for the NLP's integrator (Euler:
  /// A = I + h f_x, B = h f_u, ell_x = h L_x, ell_u = h L_u; RK4: the chain rule through the four
  /// stages of DiscreteOcp's step).
  void StepJacobian(
      int k, ConstVecRef x, ConstVecRef u, Mat* A, Mat* B, Vec* ell_x, Vec* ell_u) const;

 private:
  struct Cache {
    Vec z;
    bool valid = false;
    Mat U, X;
    double J = NAN;
    bool has_gradient = false;
    Mat G;
    bool has_steps = false;
    std::vector<Mat> A, B;
  };
  // Simulates at z unless the cache already holds z. False when the trajectory is not finite.
  bool Prepare(ConstVecRef z) const;
  bool PrepareSteps() const;

  const Ocp& ocp_;
  DiscreteOcp docp_;
  int nx_, nu_, N_;
  int npsi_rows_ = 0, nball_rows_ = 0, m_ = 0;
  std::vector<ControlSet::Block> balls_;
  double objective_scale_ = 1.0;
  Vec control_scale_;  // size nu; z[k nu + j] = u_k,j / control_scale_[j]
  Vec column_scale_;   // size n: control_scale_ repeated
  Vec z_lower_, z_upper_;
  Vec z0_;
  mutable Cache cache_;
};

/// The single-shooting transcription, registered as "single-shooting". Euler by default;
/// TranscriptionOptions::integrator = kRk4 (SolveRequest::integrator = kRk4 through the NLP
/// solvers) for RK4 steps. RK4's objective is then not the evaluator's Euler cost
/// on the same grid; it is its RK4 cost.
class SingleShooting final : public Transcription {
 public:
  static constexpr const char* kName = "single-shooting";
  std::string name() const override { return kName; }
  /// Simulates with options.integrator.
  std::unique_ptr<TranscribedNlp> Transcribe(const Ocp& ocp,
                                             const TranscriptionOptions& options) const override;
};

}  // namespace ocpb
