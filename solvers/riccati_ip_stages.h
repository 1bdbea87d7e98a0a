// The NLP of a direct transcription (forward Euler or the trapezoid) read stage by stage: what
// riccati-ip's interior point (solvers/riccati_ip_solver.cc) evaluates and factors. Internal to
// riccati-ip; its tests reach it through EulerStageLagrangian (solvers/riccati_ip_solver.h).
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "core/control_set.h"
#include "core/ocp.h"
#include "solvers/all_finite.h"
#include "transcriptions/collocation_nlp.h"

namespace ocpb::riccati_ip_internal {

constexpr double kRipInfBound = 1e19;
constexpr double kRipInf = std::numeric_limits<double>::infinity();
constexpr double kRipEps = std::numeric_limits<double>::epsilon();

inline bool RipFinite(double v) { return std::isfinite(v); }

// Ipopt's comparison with room for rounding (its Compare_le): lhs <= rhs up to 10 eps |base|.
// Near a solution the changes of the barrier objective reach its rounding error; a strict test
// then rejects every trial for noise and the line search stalls at tight tolerances.
inline bool LeqUpToRounding(double lhs, double rhs, double base) {
  return lhs - rhs <= 10.0 * std::numeric_limits<double>::epsilon() * std::abs(base);
}

template <class Derived>
inline bool RipAllFinite(const Eigen::PlainObjectBase<Derived>& m) {
  return AllFinite(m.data(), static_cast<int>(m.size()));
}

// The Euler NLP of one CollocationNlp read as stages: x_{k+1} = x_k + h_k f(t_k, x_k, u_k),
// stage k < N with variables (x_k, u_k), stage N with x_N and, when there are path
// constraints, a copy v = u_{N-1} (the NLP's path constraint at t_N reads u_{N-1}, which the
// copy turns into a stage-N function; the copy row v - u_{N-1} = 0 is linear). x_0's fixed
// components are no variables; its free ones (a free or partly free initial state, static
// parameters: Ocp::InitialNodeBounds with lower < upper) are variables of stage 0 beside u_0,
// within their initial-state bounds, with the initial cost phi0(x_0) when the problem has one.
// A free final time T is the NLP's: its steps are r h_k with r = (T - t0) / (tf - t0) on the
// nominal grid (f and L at the nominal times t_k), and its running cost r sum h_k L; the
// interior-point method carries T through the recursion as an augmented state (below).
class EulerStages {
 public:
  // nullptr with the reason when `nlp` is not an Euler NLP of the supported class.
  static std::unique_ptr<EulerStages> From(const TranscribedNlp& nlp, std::string* why_not);

  explicit EulerStages(const CollocationNlp& n) : ocp(n.ocp()), nlp(n) {}

  const Ocp& ocp;
  const CollocationNlp& nlp;
  int N = 0, nx = 0, nu = 0, nc = 0, npsi = 0, nball = 0;
  bool hard = false;
  bool copy = false;  // path constraints at t_N: stage N carries v = u_{N-1}
  std::vector<double> t, h;
  // The trapezoid (since 2026-12-07): N + 1 nodes (x_k, u_k), u_N a variable like the others,
  // defect k = x_{k+1} - x_k - h_k/2 (f_k + f_{k+1}), running cost sum_k wt_k L_k (wt_k =
  // (h_{k-1} + h_k) / 2, the NLP's point weights) and path constraints and balls at every node.
  // No copy. A free final time and boundary constraints are refused (From).
  bool trapezoid = false;
  std::vector<double> wt;
  // The number of control columns: N (Euler), N + 1 (trapezoid).
  int nctl() const { return trapezoid ? N + 1 : N; }
  Vec lb, ub;  // per control component, +-inf where unbounded (balls: none)
  // Per state component, +-inf where unbounded: the problem's state bounds, which the Euler
  // NLP imposes on x_1..x_N as variable bounds (not on x_0).
  Vec xlb, xub;
  // x_0: its free components (ascending), their initial-state bounds (per state component,
  // +-inf where unbounded and for the fixed components, which are no variables), and whether
  // the initial cost phi0(x_0) counts (Ocp::HasInitialCost with a free initial state).
  std::vector<int> free0;
  Vec x0lb, x0ub;
  bool initial_cost = false;
  // A free final time: the NLP's variable T (index time_index), its bounds (1-vectors, +-inf
  // where unbounded) and the nominal horizon [t0, t0 + duration] of t and h.
  bool free_time = false;
  int time_index = -1;
  Vec Tlb, Tub;
  double t0 = 0.0, duration = 1.0;
  int nT() const { return free_time ? 1 : 0; }
  // Controls: the components that are variables (ascending); a fixed one (lower == upper, e.g.
  // a phase without that control) keeps its value and is no variable, as Ipopt's
  // fixed_variable_treatment = make_parameter removes it (its lb, ub are +-inf here).
  std::vector<int> ufree;
  Vec ufixed;  // per control component: the fixed value, NaN for the free ones
  int nuf() const { return static_cast<int>(ufree.size()); }
  bool has_fixed_controls() const { return nuf() < nu; }
  // Boundary constraints b_lo <= b(x_0, x_N) <= b_hi: rows after psi's among the terminal rows
  // (Values::psi, Iterate::nu). They need x_0's free components at x_N, so with boundary
  // constraints the recursion carries them (ncw) beside T. An equality row reads
  // b - b_lo = 0; an inequality row (lower < upper, listed in bineq) b - s = 0 with a slack s
  // within [sblo, sbhi] (Iterate::SB), as Ipopt writes d_L <= d(x) <= d_U: the slacks are
  // eliminated in the Riccati solve's final Schur complement (RiccatiProblem::slack_hessian).
  int nb = 0;
  Vec blo;  // the equality rows' values (0 on the inequality rows)
  std::vector<int> bineq;
  Vec sblo, sbhi;  // per inequality row, +-inf where unbounded
  int nbi() const { return static_cast<int>(bineq.size()); }
  int ncw() const { return nb > 0 ? nw() : 0; }
  // The entries every stage's state carries after x: T (free_time), then x_0's free components.
  int np() const { return nT() + ncw(); }
  int nterm() const { return npsi + nb; }  // terminal rows: psi (hard form), then b
  std::vector<ControlSet::Block> balls;
  std::vector<int> state_off, control_off;
  // Ipopt's bound_relax_factor: the inequality rows are c - relax_path <= 0 and
  // |u - c|^2 - r^2 - relax_ball[b] <= 0 (lb and ub are relaxed by Relax()).
  double relax_path = 0.0;
  std::vector<double> relax_ball;

  // The variable bounds as the problem states them (From sets them; Relax widens lb .. Tub):
  // the final point is projected onto them, as Ipopt projects its own (honor_original_bounds,
  // its default).
  struct {
    Vec lb, ub, xlb, xub, x0lb, x0ub, Tlb, Tub, sblo, sbhi;
  } original;

  // Relaxes every inequality by factor * max(1, |bound|), as Ipopt does.
  void Relax(double factor) {
    relax_path = factor;
    relax_ball.assign(nball, 0.0);
    for (int b = 0; b < nball; ++b) {
      relax_ball[b] = factor * std::max(1.0, balls[b].radius * balls[b].radius);
    }
    for (Vec* lower : {&lb, &xlb, &x0lb, &Tlb, &sblo}) {
      for (double& v : *lower) {
        if (RipFinite(v)) v -= factor * std::max(1.0, std::abs(v));
      }
    }
    for (Vec* upper : {&ub, &xub, &x0ub, &Tub, &sbhi}) {
      for (double& v : *upper) {
        if (RipFinite(v)) v += factor * std::max(1.0, std::abs(v));
      }
    }
  }

  int ni(int k) const { return k < N || trapezoid ? nc + nball : (copy ? nc : 0); }
  bool has_state_bounds() const {
    return xlb.array().isFinite().any() || xub.array().isFinite().any();
  }
  bool has_initial_bounds() const {
    return x0lb.array().isFinite().any() || x0ub.array().isFinite().any();
  }
  // Whether the iterate carries state-bound multipliers (zxl, zxu: x_0's in column 0).
  bool has_state_multipliers() const { return has_state_bounds() || has_initial_bounds(); }
  int nw() const { return static_cast<int>(free0.size()); }

  struct Iterate {
    Mat X, U;  // nx x (N+1), nu x nctl()
    Mat T;     // 1 x 1: the final time (free_time), else 0 x 0
    Vec V;     // nu (copy) or empty
    std::vector<Vec> s, y, v;
    Mat zl, zu;    // nu x nctl() (0 where no bound)
    Mat zxl, zxu;  // nx x (N+1): x_0's initial-state bounds' in column 0, then the state
                   // bounds' (0 where unbounded or fixed; empty without either)
    Mat zTl, zTu;  // 1 x 1: T's bounds' (free_time; 0 where unbounded)
    Mat SB;        // nbi x 1: the boundary inequalities' slacks
    Mat zSl, zSu;  // nbi x 1: their bounds' multipliers (0 where unbounded)
    Mat lam;       // nx x N, defect multipliers (NLP convention, scaled problem)
    Vec lamV, nu;
  };
  struct StageEval {
    Vec f;
    Mat fx, fu;
    double L = 0.0;
    Vec Lx, Lu;
    Vec c;       // ni rows: path, then balls (|u - c|^2 - r^2)
    Mat cx, cu;  // ni x nx, ni x nu
    Mat H;       // (nx + nu)^2 Hessian of the stage Lagrangian (filled by Hessians())
    // free_time: d^2/dT d(x, u) of the stage Lagrangian (EvalHessians), and the stage's dJ/dT
    // without sigma, h_k L / duration (EvalDerivatives).
    Vec HT;
    double gT = 0.0;
  };
  struct TerminalEval {  // the two ends: x_N's terms, and x_0's initial cost
    double Phi = 0.0;    // terminal objective (penalty included)
    Vec grad;            // nx
    Vec psi;             // npsi (hard form)
    Mat psix;
    Mat H;              // nx x nx Hessian of sigma Phi + nu^T psi
    double Phi0 = 0.0;  // phi0(x_0), its gradient and sigma times its Hessian (initial_cost)
    Vec grad0;
    Mat H0;
    Vec b;         // b(x_0, x_N) (nb), its Jacobians, and the Hessian of nu_b^T b in (x_0, x_N)
    Mat bx0, bxN;  // nb x nx
    Mat Hb;        // 2nx x 2nx
  };
  struct Values {  // what a line-search trial needs
    double f = 0.0;
    std::vector<Vec> c;
    Mat defects;        // nx x N: x_{k+1} - x_k - h f (trapezoid: - h/2 (f_k + f_{k+1}))
    Vec psi, copy_row;  // psi: the terminal rows, psi(x_N) (hard form) then b(x_0, x_N) - b_lo
                        // (b - s on the inequality rows)
    bool ok = false;
  };

  // The step of interval k at `it`: r h_k with a free final time, else h_k.
  double Step(const Iterate& it, int k) const {
    return free_time ? (it.T(0, 0) - t0) / duration * h[k] : h[k];
  }
  // The factor r = (T - t0) / duration of a free final time (1 otherwise).
  double Rate(const Iterate& it) const { return free_time ? (it.T(0, 0) - t0) / duration : 1.0; }
  // Node k's running-cost weight at `it`: Euler's step h_k, the trapezoid's r wt_k.
  double NodeWeight(const Iterate& it, int k) const {
    return trapezoid ? Rate(it) * wt[k] : Step(it, k);
  }

  // u at stage k, or v at stage N (for evaluations at t_N); the trapezoid's u_k at every node.
  Eigen::Ref<const Vec> StageControl(const Iterate& it, int k) const {
    return k < N || trapezoid ? Eigen::Ref<const Vec>(it.U.col(k)) : Eigen::Ref<const Vec>(it.V);
  }
  // Node k's path rows c - relax and balls |u - c|^2 - r^2 - relax into c (ni(k) rows), with
  // their Jacobians when cx, cu are given (sized ni(k) x nx, ni(k) x nu, zero).
  void NodeInequalities(int k, const Iterate& it, VecRef c, Mat* cx, Mat* cu) const;

  // Values at `it` into `v` (its storage reused).
  void EvalValues(const Iterate& it, Values* v) const;
  // First derivatives at every node; false when one is not finite.
  bool EvalDerivatives(const Iterate& it, std::vector<StageEval>* st, TerminalEval* te) const;
  // Lagrangian Hessians with the multipliers of `it` (sigma: objective scale).
  bool EvalHessians(const Iterate& it,
                    double sigma,
                    std::vector<StageEval>* st,
                    TerminalEval* te) const;
  // Gradient of sigma f + equality and inequality multiplier terms (no bound terms): per stage
  // (rx_k, ru_k), rx of stage 0 being the x_0 part; the copy's rv; with a free final time its
  // T entry rT (else 0).
  void LagrangianGradient(const Iterate& it,
                          double sigma,
                          const std::vector<StageEval>& st,
                          const TerminalEval& te,
                          Mat* rx,
                          Mat* ru,
                          Vec* rv,
                          double* rT) const;

  void ToIterate(const Vec& z, Iterate* it) const;
  Vec ToNlp(const Iterate& it) const;

 private:
  // Scratch of the evaluations (one EulerStages per solve, used by one thread).
  mutable Vec f_scratch_, lam_scratch_, zero_scratch_;
};

}  // namespace ocpb::riccati_ip_internal
