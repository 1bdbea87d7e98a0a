// The maximum principle's two-point boundary-value problem, discretized by trapezoidal
// collocation: residual F(z) and its sparse Jacobian (the system the indirect Newton method
// solves).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/SparseCore>

#include "core/control_trajectory.h"
#include "core/ocp.h"
#include "core/time_grid.h"
#include "solvers/minimizer_derivative.h"

namespace ocpb {

/// With H = p^T f + L and the closed-form minimizer u*(t, x, p) = argmin_{u in U} H
/// (Ocp::MinimizeHamiltonian), Pontryagin's necessary conditions for the Ocp on a fixed horizon
/// are the boundary-value problem
///
///   x' = f(t, x, u*),  p' = -H_x(t, x, u*, p),  x(t0) = x0,
///   free initial state (Ocp::HasFreeInitialState(), static parameters among them):
///     for each free component i, p_i(t0) = -d phi0 / d x_i(t0) where x_i(t0) lies strictly
///     inside its bounds [l_i, u_i], x_i(t0) = the bound where the condition pushes it out,
///   penalty form:  p(tf) = grad Phi(x(tf)),     Phi = phi + sum_i w_i psi_i^2,
///   hard form:     p(tf) = grad phi(x(tf)) + psi_x(x(tf))^T nu,  psi(x(tf)) = 0,
///   free final time (Ocp::free_final_time()):  also H(tf) = 0, with tf an unknown,
///
/// (Bryson and Ho, "Applied Optimal Control", 1975, Sec. 2.7 and 3.3). On the grid t_0 < ... < t_N
/// with u_k = u*(t_k, x_k, p_k), the trapezoidal rule (second order; the scheme of COPS' trapezoid
/// problems, and of Betts, "Practical Methods for Optimal Control", 2nd ed., Sec. 4.5, here applied
/// to the Hamiltonian system) gives F(z) = 0 with
///
///   rows [0, nx):                   x_0 - x0; on a free component i instead
///                                   x_0,i - clip(x_0,i - (p_0,i + d phi0 / d x_0,i), l_i, u_i)
///   interval k, state rows:         x_{k+1} - x_k - h_k/2 (f_k + f_{k+1})
///   interval k, costate rows:       p_{k+1} - p_k + h_k/2 (H_x,k + H_x,k+1)
///   terminal costate rows (nx):     p_N - grad Phi(x_N)   (hard: p_N - grad phi(x_N) - psi_x^T nu)
///   hard form only (npsi rows):     psi(x_N)
///   free final time only (1 row):   H(t_N, x_N, u_N, p_N)
///
/// Unknowns z = (x_0, p_0, x_1, p_1, ..., x_N, p_N[, nu][, T]): 2 nx (N+1) (+ npsi in the hard
/// form, + 1 for a free final time), as many as equations.
///
/// Free initial state: the projection's natural residual above is p_0,i + d phi0/dx_0,i where the
/// clip is inactive and x_0,i - l_i (or - u_i) where it is active; a static parameter (a constant
/// state with a free initial value, Ocp::SetStaticParameters) is one such component, and its
/// costate row p' = -H_p with p(tf) = d Phi / dp makes p(t0) = -int H_p dt the cost's derivative
/// in the parameter (its adjoint), so the row is the parameter's stationarity (Bryson and Ho,
/// Sec. 2.7; the same row for both schemes: Euler's p_0 is the discrete cost's exact gradient in
/// x_0). Where the clip switches the row is semismooth like u*'s: exactly at the switch
/// (x_0,i - (p_0,i + d phi0/dx_0,i) equal to the bound) it takes the inactive side's derivative.
/// The initial rows are then dense over (x_0, p_0) (phi0's Hessian and p_0's identity) where a
/// fixed initial state has the identity on x_0, and the discrete cost gains phi0(x_0)
/// (Ocp::InitialCost).
///
/// Free final time: the request's grid fixes the nodes' relative positions s_k = (t_k - t0) /
/// (tf - t0) on [0, 1] (tf the problem's nominal final time); the unknown T moves them, t_k =
/// t0 + (T - t0) s_k and h_k = (T - t0)(s_{k+1} - s_k). The problem is autonomous (Ocp's contract
/// for a free final time), so the T column of the Jacobian is
///   d(state rows of k)/dT = -(s_{k+1} - s_k)/2 (f_k + f_{k+1}),
///   d(costate rows of k)/dT = (s_{k+1} - s_k)/2 (H_x,k + H_x,k+1),
/// and the row H(t_N) = 0 (the transversality condition for a free tf with phi independent of tf;
/// Bryson and Ho, Sec. 2.7) has d/dx_N = H_x + U_x^T H_u and d/dp_N = f + U_p^T H_u (H_u = 0 at an
/// interior u*; on the active set the envelope theorem makes the U terms vanish as well; they are
/// kept for exactness). H(t_N) = 0 is imposed at the grid's last node, as the condition states;
/// along the exact solution H is constant, along the discrete one it varies by O(h^2). A T
/// outside the problem's bounds (or <= t0) is a failed evaluation (Failure::kBadFinalTime): the
/// iterates of a method that treats it as a failed line-search trial stay admissible. The Jacobian
/// is assembled from the problem's exact derivatives with the chain rule through u*: for g(x, p) =
/// f(t, x, u*(x, p)) and eta(x, p) = H_x(t, x, u*(x, p), p),
///   dg/dx = f_x + f_u U_x,        dg/dp = f_u U_p,
///   deta/dx = H_xx + H_xu U_x,    deta/dp = f_x^T + H_xu U_p,
/// with (U_x, U_p) from MinimizerDerivative (a generalized Jacobian where u* is clipped: the
/// method is then a semismooth Newton method). Terminal blocks use Ocp::TerminalHessian:
///   d grad Phi / dx = TerminalHessian(sigma = 1, nu = 2 w o psi) + 2 psi_x^T diag(w) psi_x.
/// Its sparsity is fixed: for each interval a dense 2nx x 4nx block (the two nodes it couples),
/// the identity of the initial rows, and the dense terminal blocks; entries that happen to be
/// zero at a point stay in the structure, so the symbolic factorization is done once.
///
/// The discrete cost reported with F is the trapezoidal one,
///   J = sum_k h_k/2 (L_k + L_{k+1}) + Phi(x_N)    (phi(x_N) in the hard form).
///
/// Scheme::kEuler discretizes instead by forward Euler with the exact discrete adjoint of
/// DiscreteOcp (the Hamiltonian descent's discrete problem, and the Euler transcription's): with
/// u_k = u*(t_k, x_k, p_{k+1}) for k < N,
///
///   interval k, state rows:         x_{k+1} - x_k - h_k f(t_k, x_k, u_k)
///   interval k, costate rows:       p_k - p_{k+1} - h_k H_x(t_k, x_k, u_k, p_{k+1})
///   terminal rows:                  as above
///   free final time only (1 row):   sum_k (s_{k+1} - s_k) H(t_k, x_k, u_k, p_{k+1})
///
/// whose solutions are the stationary points of the Euler discrete cost J = sum_k h_k L(t_k, x_k,
/// u_k) + Phi(x_N) (phi in the hard form) over the controls (and T): the costate rows are
/// DiscreteOcp::Adjoint's recursion, u_k minimizes H_k as the descent's direction does, and the
/// last row is the exact derivative dJ/dT / (T - t0) for an autonomous problem (each h_k is
/// (T - t0)(s_{k+1} - s_k), so dJ/dT = sum_k (s_{k+1} - s_k) H_k at the discrete adjoint; u_k
/// drops out because it minimizes H_k). So Newton on it polishes a descent result to the optimum
/// of the same discrete problem (J equal to the Euler transcription's NLP optimum). The unknowns
/// and the sparsity are the trapezoid's (interval k couples nodes k and k+1); the free-time row is
/// dense (every node's x and p). The controls are piecewise constant, u_k on [t_k, t_{k+1})
/// (nu x N in Controls()), and the reported cost is the Euler J.
///
/// Requires Ocp::HasHamiltonianMinimizer() and num_path() == 0 (the constructor throws
/// std::invalid_argument otherwise). Not thread-safe (keeps scratch); one object per solve.
class PmpResidual {
 public:
  /// The discretization of the boundary-value problem (see the class comment).
  enum class Scheme { kTrapezoid, kEuler };

  /// Why an evaluation failed.
  enum class Failure {
    kNone,
    kNonFinite,          ///< NaN/inf in u*, f, H_x, the derivatives or the residual
    kSingularMinimizer,  ///< the reduced KKT matrix of MinimizerDerivative is singular
    kBadFinalTime,       ///< a free final time outside its bounds, <= t0, or not finite
    kAbandoned,          ///< stopped early: the sum of squares exceeds `abandon_above`
  };

  /// The relative margin by which a partial sum of squares must exceed `abandon_above` before an
  /// evaluation is abandoned: far above the rounding of any summation order of F's squares
  /// (about size() * 1.1e-16), so the full sum would exceed the bound too.
  static constexpr double kAbandonMargin = 1e-9;

  /// Throws std::invalid_argument when the grid does not span [t0, tf] (to 1e-9 relative; for a
  /// free final time [t0, T] with T within its bounds, the start's final time) or
  /// the problem has no closed-form minimizer or has path constraints.
  PmpResidual(const Ocp& ocp,
              const TimeGrid& grid,
              TerminalMode mode,
              Scheme scheme = Scheme::kTrapezoid);

  /// The constructor's checks alone (no structure is built), throwing the same errors.
  static void CheckApplicable(const Ocp& ocp, const TimeGrid& grid);

  const Ocp& ocp() const { return ocp_; }
  const TimeGrid& grid() const { return grid_; }
  TerminalMode mode() const { return mode_; }
  Scheme scheme() const { return scheme_; }
  /// Number of unknowns, equal to the number of equations.
  int size() const { return size_; }
  /// Number of multipliers nu (npsi in the hard form, else 0).
  int num_multipliers() const { return nnu_; }
  /// True when the final time is an unknown (the problem's free_final_time()).
  bool free_final_time() const { return free_time_; }
  /// True when some component of x(t0) is an unknown (Ocp::HasFreeInitialState()): the initial
  /// rows are then the transversality rows above, not the identity on x_0.
  bool free_initial_state() const { return free_initial_; }

  /// z from states X (nx x N+1), costates P (nx x N+1), multipliers nu (num_multipliers()) and,
  /// for a free final time, the final time T (ignored otherwise).
  Vec Pack(const Mat& X, const Mat& P, const Vec& nu, double T) const;
  Vec Pack(const Mat& X, const Mat& P, const Vec& nu) const { return Pack(X, P, nu, grid_.tf()); }
  /// The inverse of Pack. Any output may be null.
  void Unpack(ConstVecRef z, Mat* X, Mat* P, Vec* nu) const;
  /// The final time of z: its last entry for a free final time, else the grid's tf.
  double FinalTime(ConstVecRef z) const;
  /// The grid of z: the request's grid, stretched to [t0, FinalTime(z)] for a free final time.
  TimeGrid GridOf(ConstVecRef z) const;

  /// Evaluates F(z) into F (size()) and the discrete cost into *cost (may be null). With
  /// `with_jacobian`, also the Jacobian's values into jacobian(). Returns false on failure;
  /// failure() and failure_node() then say why and where (node index, or N+1 for the terminal
  /// rows). With `with_jacobian` at the point of the last successful evaluation (bitwise the
  /// same z: Newton's Jacobian at its accepted trial), the problem's minimizer, dynamics and
  /// running-cost values of that evaluation are reused (the same numbers), and only the
  /// second-order work is done.
  ///
  /// With a finite `abandon_above` (a bound on sum_i F_i^2, such as a line search's sufficient
  /// decrease), the evaluation stops as soon as the squares of the rows computed so far exceed
  /// it by kAbandonMargin, and returns false with failure() = kAbandoned: a trial that is
  /// rejected anyway costs only the intervals up to where its residual is large. The decision
  /// is the full sum's (the squares are nonnegative), so callers' iterates do not change. The
  /// bound is ignored with `with_jacobian` (the Jacobian is written node by node).
  bool Evaluate(ConstVecRef z,
                VecRef F,
                double* cost,
                bool with_jacobian,
                double abandon_above = std::numeric_limits<double>::infinity());

  /// The Jacobian of the last Evaluate(..., with_jacobian = true): column-major, compressed, with
  /// the fixed structure described above.
  /// (The values are assembled in the structure's own order, entries_, and copied into the
  /// sparse matrix when it is asked for; the matrix itself is built on the first call: structured
  /// solvers that read the blocks never pay for the structure or the scatter.)
  const Eigen::SparseMatrix<double>& jacobian() const;
  /// The number of entries of the Jacobian's structure (jacobian().nonZeros(), without building
  /// the matrix).
  int structural_nonzeros() const { return static_cast<int>(entries_.size()); }
  /// The trapezoid's u*(t_k, x_k, p_k) at every node of GridOf(z) (nu x N+1); Euler's
  /// u*(t_k, x_k, p_{k+1}) on every interval (nu x N).
  Mat Controls(ConstVecRef z) const;
  /// The control function the scheme means: piecewise linear through the trapezoid's node values,
  /// piecewise constant on Euler's intervals, on GridOf(z).
  ControlTrajectory ControlFunction(ConstVecRef z) const;

  /// Blocks of the last evaluated Jacobian for structured solvers (BvpRiccatiSolver):
  ///  - IntervalBlock(k) (a view, valid until the next Evaluate): interval k's 2 nx rows (state
  ///  rows, then costate rows) over the columns
  ///    of nodes k and k+1, (x_k, p_k, x_{k+1}, p_{k+1}): 2 nx x 4 nx;
  ///  - TerminalBlock() (copied, as the two below): the nx terminal-costate rows, then the
  ///  num_multipliers() rows of psi,
  ///    over the columns (x_N, p_N, nu): (nx + nnu) x (2 nx + nnu), zeros off the structure;
  ///  - TimeColumn() (free final time): the T column's entries in every row but the last
  ///    (size() - 1; zeros off the structure); TimeRow(): the last row's entries in every column
  ///    but T's (size() - 1). The (T, T) entry is structurally zero.
  /// The initial rows are the identity on x_0 with a fixed initial state (no accessor).
  using RowMajorMat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  Eigen::Map<const RowMajorMat> IntervalBlock(int k) const;
  void TerminalBlock(MatRef block) const;
  void TimeColumn(VecRef column) const;
  void TimeRow(VecRef row) const;
  /// Intervals N of the grid, and the first row of interval k / column of node k in z.
  int intervals() const { return N_; }
  int IntervalRow(int k) const { return Row(k); }
  int NodeColumn(int k) const { return Col(k); }

  Failure failure() const { return failure_; }
  int failure_node() const { return failure_node_; }
  /// A one-line description of the last failure ("" when none).
  std::string FailureMessage() const;

 private:
  // What a residual evaluation computes at one node (Euler: at interval k's u_k = u*(t_k, x_k,
  // p_{k+1})). Kept per node: Newton evaluates its Jacobian at the line search's accepted
  // trial, the point evaluated last, and the Jacobian then reuses these instead of calling the
  // problem again (the same numbers: the same calls at the same point).
  struct NodeValues {
    Vec u, f, Hx, Lx, Lu;
    Mat fx, fu;
    double L = 0.0;
  };
  // The Jacobian's scratch at one node.
  struct NodeBlocks {
    Vec Hu;
    Mat hess, Ux, Up, Gx, Gp, Ex, Ep;
  };
  // With `reuse`, n holds this node's values at this point already (the last evaluation's).
  bool EvaluateNode(int k,
                    double t,
                    ConstVecRef x,
                    ConstVecRef p,
                    bool with_jacobian,
                    bool reuse,
                    NodeValues* n,
                    NodeBlocks* b);
  // The initial rows (x_0 - x0, or a free component's transversality row) and their Jacobian
  // entries; adds phi0(x_0) to *J with a free initial state. False when not finite.
  bool EvaluateInitialRows(ConstVecRef z, VecRef F, bool with_jacobian, double* J);
  // Records an abandoned evaluation at interval k; returns false.
  bool Abandon(int k);
  // True when z is bitwise the point of the last successful evaluation (values_ hold it).
  bool IsLastEvaluatedPoint(ConstVecRef z) const;
  // The interval rows (and the free-time column and row) of each scheme; false on failure.
  // `squares` starts at the sum of squares of the rows before the intervals', gains each
  // interval's, and the evaluation is abandoned once it exceeds `abandon_limit`.
  bool EvaluateTrapezoid(ConstVecRef z,
                         VecRef F,
                         double T,
                         bool with_jacobian,
                         bool reuse,
                         double abandon_limit,
                         double* squares,
                         double* J);
  bool EvaluateEuler(ConstVecRef z,
                     VecRef F,
                     double T,
                     bool with_jacobian,
                     bool reuse,
                     double abandon_limit,
                     double* squares,
                     double* J);
  double NodeTime(int k, double T) const;
  // The entries' layout (offsets and count), and for Euler the constant entries.
  void BuildStructure();
  // Euler's interval entries that do not depend on the point (identities and zeros), written
  // once: Evaluate writes only the others.
  void EulerConstantEntries();
  // jacobian_ and value_index_ from the layout (on the first jacobian() call).
  void BuildSparseMatrix() const;
  int Row(int k) const { return nx_ + 2 * nx_ * k; }  // first row of interval k
  int Col(int k) const { return 2 * nx_ * k; }        // first column of node k

  const Ocp& ocp_;
  TimeGrid grid_;
  TerminalMode mode_;
  Scheme scheme_;
  bool free_time_;
  bool free_initial_;            // Ocp::HasFreeInitialState()
  bool initial_cost_;            // phi0 counts: a free initial state with Ocp::HasInitialCost()
  VectorBounds initial_bounds_;  // Ocp::InitialNodeBounds()
  Vec initial_gradient_;         // grad phi0(x_0) of the last evaluation (zero without phi0)
  Mat initial_hessian_;          // its Hessian (with the Jacobian)
  int nx_, nu_, npsi_, nnu_, N_, size_;
  std::vector<double> s_;  // free final time: the nodes' relative positions on [0, 1]
  MinimizerDerivative derivative_;
  std::vector<NodeValues> values_;  // per node, N + 1 (Euler: per interval, the first N)
  NodeBlocks blocks_[2];            // nodes k and k+1 of the interval being assembled (by parity)
  Vec evaluated_z_;                 // the point of the last successful Evaluate, when values_valid_
  bool values_valid_ = false;
  mutable Eigen::SparseMatrix<double> jacobian_;  // values copied from entries_ on demand
  mutable bool jacobian_stale_ = false;
  std::vector<double> entries_;  // the Jacobian's values in BuildStructure's order
  // value_index_[e] is the position in jacobian_.valuePtr() of structural entry e, in the order
  // BuildStructure() generates them.
  mutable std::vector<int> value_index_;
  int initial_entries_ = 0;   // nx (the identity), or 2 nx^2 with a free initial state
  int interval_entries_ = 0;  // 8 nx^2
  int terminal_offset_ = 0;   // first terminal entry
  int time_offset_ = 0;       // free final time: first entry of the T column, then the H row
  Failure failure_ = Failure::kNone;
  int failure_node_ = -1;
};

}  // namespace ocpb
