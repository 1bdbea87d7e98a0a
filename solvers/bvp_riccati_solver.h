// The Newton matrix of the discretized maximum principle (PmpResidual) solved by a Riccati
// (decoupling) sweep over its intervals, in place of a general sparse LU.
#pragma once

#include <vector>

#include "core/types.h"
#include "solvers/pmp_residual.h"

namespace ocpb {

/// Solves J d = b for the Jacobian J of a PmpResidual (either scheme, either terminal form, a
/// free final time included) in O(N nx^3) operations, exploiting its structure: the initial rows
/// are the identity on x_0, interval k's rows couple only the nodes k and k+1 (z_k = (x_k, p_k)),
///   L_k z_k + R_k z_{k+1} (+ c_k dT) = b_k,
/// and the terminal rows couple z_N with the multipliers nu. The sweep is the classical
/// decoupling of a two-point boundary-value problem (the Riccati transformation; Ascher, Mattheij
/// and Russell, "Numerical Solution of Boundary Value Problems for ODEs", 1995, Sec. 4.5 and 6.4):
/// with the ansatz p_k = S_k x_k + T_k dnu + s_k, from the terminal rows backwards,
///
///   [R_x + R_p S_{k+1} | L_p] (x_{k+1}, p_k) = b_k - R_p s_{k+1} - L_x x_k - R_p T_{k+1} dnu,
///
/// one 2nx x 2nx LU per interval (partial pivoting), which gives S_k, T_k, s_k and x_{k+1} as an
/// affine function of x_k and dnu; a forward pass from x_0 then gives x_N = a_N + W_N dnu, and
/// the psi rows fix dnu (an npsi x npsi LU). For the Newton matrix of an optimal-control problem
/// this is the Riccati recursion of the linear-quadratic subproblem (for Euler, S_k is the
/// linearized costate's dependence on the state; 2nx x 2nx LU stands for I - B_k S_{k+1}). A free
/// final time is a border: the core system without the T row and column is solved for b and for
/// the T column, and the last row fixes dT.
///
/// The sweep does not pivot across intervals: an LU block can be singular where the sparse LU of
/// the whole matrix is not (a conjugate point of the linearization far from an optimum). So
/// Factorize() and Solve() return false when a block is singular or not finite, and Solve()
/// also when the solution's residual |J d - b|_inf exceeds `kRelativeResidual` |b|_inf after one
/// step of iterative refinement; the caller then uses the sparse LU (IndirectNewton does, and
/// counts it).
class BvpRiccatiSolver {
 public:
  /// Partial-pivoting LU of a small dense block in plain loops (Eigen's blocked kernels cost
  /// more than the arithmetic at these sizes: 2 nx = 10 on comm-path2d).
  class SmallLu {
   public:
    /// False when a pivot is not finite or negligible (|pivot| <= 1e-13 max |pivot|).
    bool Compute(ConstMatRef a);
    /// x := A^-1 x, for a vector or each column of a matrix.
    void SolveVector(VecRef x) const;
    void SolveColumns(MatRef x) const;

   private:
    Mat lu_;
    std::vector<int> pivot_;
  };

  /// The accepted relative residual of a solve (|J d - b|_inf <= this |b|_inf).
  static constexpr double kRelativeResidual = 1e-10;

  /// `pmp` must outlive the solver; its layout is fixed at construction.
  explicit BvpRiccatiSolver(const PmpResidual& pmp);

  /// Factors pmp.jacobian() (the last Evaluate with the Jacobian). False when an interval block,
  /// the multipliers' block or the free-time border is singular or not finite.
  bool Factorize();
  /// d from J d = b with the last factorization; false when the residual test fails.
  bool Solve(const Vec& b, Vec* d);

 private:
  // r = J d from the blocks (the factorized matrix; no sparse matrix needed).
  void Multiply(ConstVecRef d, Vec& r) const;
  // x := K_k^-1 x (2 nx rows): the LU of K_k, or for Euler its block form.
  void SolveK(int k, MatRef x) const;
  // The core system (no T row/column): d_core from b_core.
  void SolveCore(ConstVecRef b, VecRef d);
  // The whole system (the border of a free final time included), no checks.
  void ApplyInverse(ConstVecRef b, VecRef d);

  const PmpResidual& pmp_;
  int nx_, nnu_, N_, core_;
  bool free_time_;
  bool euler_;  // Scheme::kEuler: K_k = [M 0; G I], one nx x nx LU (see Factorize)
  Mat terminal_, K_, RpT_;
  Vec rhs_;
  std::vector<SmallLu> lu_;  // per interval, of K_k = [R_x + R_p S | L_p]
  std::vector<Mat> S_, T_;   // per node: p_k = S_k x_k + T_k dnu + s_k
  std::vector<Mat> Y_, V_;   // per interval: K^-1 L_x, K^-1 R_p T_{k+1}
  std::vector<Mat> Rp_;      // per interval: R_p
  std::vector<Mat> G_;       // Euler, per interval: R_p,bottom S_{k+1}
  std::vector<Mat> W_;       // per node: x_k = a_k + W_k dnu
  SmallLu terminal_lu_;      // of the terminal costate rows' p_N block
  SmallLu nu_lu_;            // of Psi_x W_N
  Mat terminal_x_, terminal_nu_, psi_x_;
  // Solve scratch: s per node, y per interval, a per node.
  std::vector<Vec> s_, y_, a_;
  Vec time_column_, time_row_, w_, core_d_, residual_, correction_;
  double border_ = 0.0;  // -time_row_ . w_ (the (T, T) entry is zero)
};

}  // namespace ocpb
