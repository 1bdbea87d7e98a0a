// The Newton step of the stagewise interior-point solver (riccati-ip): an equality-constrained
// QP with the stage structure of an optimal-control problem, solved by a backward Riccati
// recursion and a forward sweep.
#pragma once

#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include "core/types.h"

namespace ocpb {

/// One stage k = 0..N-1 of the QP below: the stage Hessian Q (order (x_k, u_k)), its gradient q,
/// and the linearized transition dx_{k+1} = A dx_k + B du_k + b. Dimensions may differ from stage
/// to stage (nx_k = A.cols(), nu_k = B.cols(), nx_{k+1} = A.rows()).
struct RiccatiStage {
  Mat Q;  ///< (nx_k + nu_k) square, symmetric
  Vec q;  ///< nx_k + nu_k
  Mat A;  ///< nx_{k+1} x nx_k
  Mat B;  ///< nx_{k+1} x nu_k
  Vec b;  ///< nx_{k+1}
};

/// The QP
///
///   minimize    sum_k 1/2 w_k^T (Q_k + dw I) w_k + q_k^T w_k + 1/2 x_N^T (Q_N + dw I) x_N + q_N^T
///   x_N subject to  x_{k+1} = A_k x_k + B_k u_k + b_k     (k = 0..N-1, multiplier lambda_k),
///               C x_N + c - dc nu = 0                   (terminal rows, multiplier nu),
///               x_0 = x0 (given, not a variable),
///
/// with w_k = (x_k, u_k), dw >= 0 the primal regularization (Ipopt's delta_w) and dc >= 0 the
/// terminal rows' dual regularization (Ipopt's delta_c, on those rows only: the dynamics rows
/// always have full rank). Multipliers follow the convention of core/nlp.h for the rows
/// x_{k+1} - A_k x_k - B_k u_k - b_k = 0 and C x_N + c = 0: the Lagrangian is the objective plus
/// lambda_k^T (x_{k+1} - A_k x_k - B_k u_k - b_k) plus nu^T (C x_N + c).
///
/// Terminal rows may have a slack (an inequality row d(x) in [lo, hi] written d(x) - s = 0 with
/// s bounded, as Ipopt writes it): row i with slack_hessian[i] > 0 reads
/// C_i x_N + c_i - s_i - dc nu_i = 0, and the objective gains the slack's own terms
/// 1/2 (slack_hessian[i] + dw) s_i^2 + slack_gradient[i] s_i (in an interior point, the
/// barrier's Sigma and gradient of the slack's bounds). The slacks are eliminated before the
/// final Schur complement: s_i = (nu_i - slack_gradient[i]) / (slack_hessian[i] + dw), which
/// adds 1 / (slack_hessian[i] + dw) to that row's dual regularization; the inertia test is
/// unchanged (each slack is a positive pivot). Empty vectors, or zero entries: no slacks.
struct RiccatiProblem {
  std::vector<RiccatiStage> stages;
  Mat QN;  ///< nx_N square
  Vec qN;
  Mat C;  ///< npsi x nx_N (npsi may be 0)
  Vec c;
  Vec x0;              ///< nx_0 (often 0: the initial state is fixed and not a variable)
  Vec slack_hessian;   ///< npsi entries >= 0 (0: the row has no slack), or empty
  Vec slack_gradient;  ///< npsi entries (0 where no slack), or empty
  /// Whether a first stage without a state (x0 empty) whose H_uu fails its own test (singular,
  /// or more negative curvature than the terminal rows can remove) is solved jointly with the
  /// terminal multiplier (RiccatiSolver::Solve) rather than reported kNotPositiveDefinite.
  bool joint_first_stage = true;
};

/// The vectors of a RiccatiProblem's right-hand side, for RiccatiSolver::SolveFactored (the
/// matrices stay those of the factorized problem): per stage q and b, then qN, c and x0.
struct RiccatiRhs {
  std::vector<Vec> q, b;
  Vec qN, c, x0;
  Vec slack_gradient;  ///< as RiccatiProblem's (empty: zeros)
};

struct RiccatiSolution {
  std::vector<Vec> x;       ///< N + 1 entries (x[0] = x0)
  std::vector<Vec> u;       ///< N entries
  std::vector<Vec> lambda;  ///< N entries, the multipliers of the transitions
  Vec nu;                   ///< npsi
  Vec s;                    ///< npsi: the terminal rows' slacks (0 where a row has none)
};

/// How a factorization went.
enum class RiccatiOutcome {
  kSolved,
  /// The KKT matrix does not have the inertia of a descent step (n positive, m negative
  /// eigenvalues): a stage's H_uu = R + B^T P B (+ dw I) is singular, or the H_uu's have more
  /// negative eigenvalues than the terminal rows can remove (failed_stage() is that stage), or
  /// the final Schur complement does not remove them all (failed_stage() == N). Regularize
  /// (larger dw) and retry.
  kNotPositiveDefinite,
  /// The terminal rows' Schur complement -(G_0 - dc I) is not positive definite: the terminal
  /// rows are (numerically) dependent or not reachable; retry with dc > 0.
  kTerminalRowsDegenerate,
};

/// The backward Riccati recursion with the terminal rows carried as a parameter: the cost-to-go
/// of stage k is V_k(x, nu) = 1/2 x^T P_k x + x^T (p_k + E_k nu) + nu^T e_k + 1/2 nu^T G_k nu,
/// started from P_N = Q_N + dw I, p_N = q_N, E_N = C^T, e_N = c, G_N = 0. Each stage eliminates
/// u_k = K_k x_k + k_k + M_k nu through a Cholesky factorization of H_uu, or, where that fails,
/// its symmetric eigendecomposition. The inertia test is exact: by Haynsworth's inertia
/// additivity the KKT matrix has the inertia of a descent step (n positive, m negative
/// eigenvalues) iff no H_uu is singular and the final Schur complement -(G_0 - dc I) has exactly
/// as many negative eigenvalues as all H_uu together (each negative curvature direction removed
/// by a terminal row); without terminal rows, iff every H_uu is positive definite. At stage 0 the
/// terminal multiplier solves (G_0 - dc I) nu = -(e_0 + E_0^T x0), the final Schur complement
/// of the terminal rows, and a forward sweep gives x, u and lambda_k = -(P_{k+1} x_{k+1} +
/// p_{k+1} + E_{k+1} nu). O(N (nx + nu)^3) work and memory O(N (nx + nu)^2), no fill-in, no
/// pivoting. The workspace is reused across calls (sizes adapt).
class RiccatiSolver {
 public:
  /// Solves the QP; on kNotPositiveDefinite `failed_stage()` says which stage failed. The
  /// solution is only written on kSolved.
  RiccatiOutcome Solve(const RiccatiProblem& problem,
                       double dw,
                       double dc,
                       RiccatiSolution* solution);
  int failed_stage() const { return failed_stage_; }

  /// Solves the system of the last Solve again with another right-hand side, when that Solve
  /// succeeded (else it throws std::logic_error: a failed Solve leaves its factors partly
  /// written): the matrices (Q, A, B, QN, C, dw, dc) must be those of `problem`, which that
  /// Solve factorized; the vectors come from `rhs`. Only the recursion's vector part and the
  /// forward sweep run, O(N (nx + nu)^2): what iterative refinement and a second-order
  /// correction need.
  void SolveFactored(const RiccatiProblem& problem,
                     const RiccatiRhs& rhs,
                     RiccatiSolution* solution);

 private:
  template <int kNx, int kNu>
  bool BackwardStage(const RiccatiStage& s, int k, double dw, int npsi);
  struct ValueFunction;
  // Stage 0 without a state whose H_uu is not positive definite (BackwardStage's scratch): keeps
  // H_uu, g_u and B^T E for the joint solve of u_0 and nu (joint_K_), adds E^T b to e.
  void JointFirstStage(const RiccatiStage& s, const ValueFunction& vn, int npsi);
  // The terminal multiplier from the final Schur complement's eigendecomposition (schur_), the
  // terminal slacks, and the forward sweep; b[k], x0 and slack_gradient are the right-hand
  // side's.
  void TerminalMultiplierAndForwardSweep(const RiccatiProblem& problem,
                                         const std::vector<const Vec*>& b,
                                         const Vec& x0,
                                         const Vec& slack_gradient,
                                         RiccatiSolution* solution);

  // The workspace, sized on the first call and reused (no heap allocation once the stage
  // dimensions repeat): per stage the factors u_k = K x_k + k + M nu, and the cost-to-go of every
  // stage (values_[k] = V_k, k = 0..N; V_k is written by stage k from V_{k+1}).
  struct StageFactor {
    Mat K, M;  // nu x nx, nu x npsi
    Vec k;     // nu
    // H_uu's factorization, kept for SolveFactored: its Cholesky factor L (lower triangle), or,
    // where H_uu was not positive definite, its inverse.
    bool cholesky = true;
    Mat L, Hinv;
  };
  struct ValueFunction {
    Mat P, E;  // nx_k x nx_k, nx_k x npsi
    Vec p;
  };
  std::vector<StageFactor> factors_;
  std::vector<ValueFunction> values_;
  // One stage's scratch: P [A B] (nx_{k+1} x (nx + nu)), P b + p, the blocks H_xx, H_ux, H_uu,
  // the gradients g_x, g_u, B^T E.
  Mat PW_, Hxx_, Hux_, Huu_, BE_;
  Vec Pbp_, gx_, gu_, e_, rhs_, nu_;
  Mat G_, S_;
  int failed_stage_ = -1;
  bool factored_ = false;  // the last Solve succeeded: SolveFactored may use its factors
  int negative_ = 0;       // negative eigenvalues of the H_uu's so far
  Eigen::SelfAdjointEigenSolver<Mat> eig_;
  // The final Schur complement's eigendecomposition (npsi > 0), kept for SolveFactored.
  Eigen::SelfAdjointEigenSolver<Mat> schur_;
  std::vector<const Vec*> b_;
  // 1 / (slack_hessian + dw) per terminal row of the last Solve (0 where a row has no slack).
  Vec slack_inverse_;
  // A joint first stage (JointFirstStage): the matrix [H_uu, B^T E; E^T B, G - dc I - D], its
  // eigendecomposition, the stage's g_u, and the right-hand side and solution of the last solve.
  bool joint_ = false;
  bool joint_first_stage_ = true;  // the problem's joint_first_stage
  Mat joint_K_;
  Eigen::SelfAdjointEigenSolver<Mat> joint_eig_;  // its inertia
  Eigen::PartialPivLU<Mat> joint_lu_;             // its solves
  Vec joint_gu_, jrhs_, jsol_;
  Vec joint_d_;  // the joint matrix's equilibration D (eigendecomposed: D K D)
  // The final Schur complement's equilibration with terminal slacks (empty without: S itself).
  Vec schur_d_;
};

/// The residual of z in the KKT conditions of p (with its dw and dc): returns its max norm and
/// writes into r the right-hand side whose solution, by SolveFactored on p's factorization, is
/// the correction to subtract from z (one step of iterative refinement).
double RiccatiKktResidual(
    const RiccatiProblem& p, double dw, double dc, const RiccatiSolution& z, RiccatiRhs* r);

}  // namespace ocpb
