// The Newton matrix of the discretized maximum principle (PmpResidual) solved by a Riccati
// (decoupling) sweep over its intervals, in place of a general sparse LU.
#pragma once

#include <memory>

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
/// linearized costate's dependence on the state; R_x = (I; 0) and L_p = (0; I), so the block is
/// [M 0; G I] with M = I + R_p,top S_{k+1}: one nx x nx LU). A free final time is a border: the
/// core system without the T row and column is solved for b and for the T column, and the last
/// row fixes dT.
///
/// The per-interval work is done in plain loops on contiguous storage (solvers/small_lu.h),
/// compiled for nx = 1 .. 6 at fixed size (unrolled) and for any other nx at runtime size
/// (Kernel::kRuntimeSize forces the latter: tests check the two agree). On comm-path2d (nx = 5,
/// N = 400, hard form) a factorization costs about 1/6 of the instructions of the previous
/// Eigen-dynamic version (solvers/README-family.md).
///
/// The sweep does not pivot across intervals: an LU block can be singular where the sparse LU of
/// the whole matrix is not (a conjugate point of the linearization far from an optimum). So
/// Factorize() and Solve() return false when a block is singular or not finite, and Solve()
/// also when the solution's residual |J d - b|_inf exceeds `kRelativeResidual` |b|_inf after one
/// step of iterative refinement; the caller then uses the sparse LU (IndirectNewton does, and
/// counts it). The sweep starts from x_0 fixed by the initial rows: with a free initial state
/// (PmpResidual::free_initial_state(), transversality rows over (x_0, p_0)) Factorize() always
/// returns false, so every step goes to the caller's sparse LU.
class BvpRiccatiSolver {
 public:
  /// The accepted relative residual of a solve (|J d - b|_inf <= this |b|_inf).
  static constexpr double kRelativeResidual = 1e-10;

  /// Which compiled kernel runs the sweep: the fixed-size one when nx has one (nx <= 6), or the
  /// runtime-size one (every nx; the same arithmetic, for tests and larger nx).
  enum class Kernel { kFixedSize, kRuntimeSize };

  /// `pmp` must outlive the solver; its layout is fixed at construction.
  explicit BvpRiccatiSolver(const PmpResidual& pmp, Kernel kernel = Kernel::kFixedSize);
  ~BvpRiccatiSolver();
  BvpRiccatiSolver(const BvpRiccatiSolver&) = delete;
  BvpRiccatiSolver& operator=(const BvpRiccatiSolver&) = delete;

  /// Factors pmp.jacobian() (the last Evaluate with the Jacobian). False when an interval block,
  /// the multipliers' block or the free-time border is singular or not finite.
  bool Factorize();
  /// d from J d = b with the last factorization; false when the residual test fails.
  bool Solve(const Vec& b, Vec* d);

  /// The sweep's work per nx (implemented by a template on the compile-time nx, 0 = runtime).
  class Sweep {
   public:
    virtual ~Sweep() = default;
    virtual bool Factorize() = 0;
    virtual bool Solve(const Vec& b, Vec* d) = 0;
  };

 private:
  std::unique_ptr<Sweep> sweep_;
};

}  // namespace ocpb
