#include "solvers/riccati_ip_solver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/LU>

#include "core/option_binding.h"
#include "core/timer.h"
#include "solvers/all_finite.h"
#include "solvers/riccati_ip_stages.h"
#include "solvers/riccati_kkt.h"
#include "transcriptions/collocation_nlp.h"
#include "transcriptions/registry.h"

namespace ocpb {

// The NLP read stage by stage (solvers/riccati_ip_stages.h) and its helpers.
using riccati_ip_internal::EulerStages;
using riccati_ip_internal::kRipEps;
using riccati_ip_internal::kRipInf;
using riccati_ip_internal::kRipInfBound;
using riccati_ip_internal::LeqUpToRounding;
using riccati_ip_internal::RipAllFinite;
using riccati_ip_internal::RipFinite;

// ---- options ----------------------------------------------------------------------------------

namespace {

const OptionBinding<RiccatiIpOptions>& RiccatiIpBinding() {
  static const OptionBinding<RiccatiIpOptions> table = [] {
    using O = RiccatiIpOptions;
    OptionBinding<O> t("riccati-ip");
    t.Number("tol",
             &O::tol,
             "convergence tolerance on the scaled KKT error (Ipopt's E_0)",
             OptionBounds::Above(0));
    t.Number("dual_inf_tol",
             &O::dual_inf_tol,
             "unscaled dual infeasibility a converged point must also meet",
             OptionBounds::Above(0));
    t.Number("constr_viol_tol",
             &O::constr_viol_tol,
             "unscaled constraint violation a converged point must also meet",
             OptionBounds::Above(0));
    t.Number("compl_inf_tol",
             &O::compl_inf_tol,
             "unscaled complementarity a converged point must also meet",
             OptionBounds::Above(0));
    t.Number("acceptable_tol",
             &O::acceptable_tol,
             "acceptable level of the scaled KKT error (Ipopt's); see acceptable_iter",
             OptionBounds::Above(0));
    t.Integer("acceptable_iter",
              &O::acceptable_iter,
              "stop as acceptable after this many consecutive acceptable iterates (0: never)",
              OptionBounds::AtLeast(0));
    t.Number("acceptable_dual_inf_tol",
             &O::acceptable_dual_inf_tol,
             "unscaled dual infeasibility an acceptable point must also meet",
             OptionBounds::Above(0));
    t.Number("acceptable_constr_viol_tol",
             &O::acceptable_constr_viol_tol,
             "unscaled constraint violation an acceptable point must also meet",
             OptionBounds::Above(0));
    t.Number("acceptable_compl_inf_tol",
             &O::acceptable_compl_inf_tol,
             "unscaled complementarity an acceptable point must also meet",
             OptionBounds::Above(0));
    t.Integer("min_refinement_steps",
              &O::min_refinement_steps,
              "iterative refinement corrections every Newton step takes at least",
              OptionBounds::AtLeast(0));
    t.Integer("max_refinement_steps",
              &O::max_refinement_steps,
              "iterative refinement corrections a Newton step takes at most (Ipopt's)",
              OptionBounds::AtLeast(0));
    t.Integer("max_soc",
              &O::max_soc,
              "second-order corrections tried per step at most (Ipopt's; 0: none)",
              OptionBounds::AtLeast(0));
    t.Integer("max_iter", &O::max_iter, "iteration limit", OptionBounds::AtLeast(0));
    t.Number("max_cpu_time", &O::max_cpu_time, "CPU time limit, s", OptionBounds::Above(0));
    t.Number("mu_init", &O::mu_init, "first barrier parameter", OptionBounds::Above(0));
    t.Number("bound_push",
             &O::bound_push,
             "absolute push of starting controls, states and slacks into their bounds",
             OptionBounds::Above(0));
    t.Number("bound_frac",
             &O::bound_frac,
             "relative push of starting controls and states into their bounds' interval",
             OptionBounds::OpenClosed(0, 0.5));
    t.Number(
        "bound_relax_factor",
        &O::bound_relax_factor,
        "inequalities, control and state bounds relaxed by this times max(1, |bound|) (Ipopt's)",
        OptionBounds::AtLeast(0));
    t.Text("nlp_scaling_method",
           &O::nlp_scaling_method,
           "objective scaling: gradient-based (Ipopt's rule, objective only) or none",
           {"none", "gradient-based"});
    t.Number("nlp_scaling_max_gradient",
             &O::nlp_scaling_max_gradient,
             "largest gradient max-norm gradient-based scaling leaves alone",
             OptionBounds::Above(0));
    t.Integer("print_level",
              &O::print_level,
              "0 silent, 1 one line per iteration on stderr",
              OptionBounds::Closed(0, 1));
    return t;
  }();
  return table;
}

// The restoration's damping sequence (RiccatiInteriorPoint::Restore): Gauss-Newton, then
// Levenberg-Marquardt steps with the relaxed rows' residuals weighted rho: as it falls the step
// shortens, and the barrier terms (not scaled by rho) weigh more in it, towards a centring step
// that keeps the iterate off its bounds.
constexpr double kRestorationRho[] = {kRipInf, 1e4, 1e2, 1.0, 1e-2, 1e-4, 1e-6};

}  // namespace

const OptionSchema& RiccatiIpOptions::Schema() { return RiccatiIpBinding().schema(); }

RiccatiIpOptions RiccatiIpOptions::Apply(const OptionMap& options, RiccatiIpOptions base) {
  RiccatiIpOptions o = RiccatiIpBinding().Apply(options, std::move(base));
  if (o.min_refinement_steps > o.max_refinement_steps) {
    throw std::invalid_argument(
        "riccati-ip option min_refinement_steps (" + std::to_string(o.min_refinement_steps) +
        ") must be <= max_refinement_steps (" + std::to_string(o.max_refinement_steps) + ")");
  }
  return o;
}

// ---- the interior-point method ------------------------------------------------------------------

namespace {

// Ipopt's constants (Wächter & Biegler, Math. Prog. 106, 2006, Sec. 2 and 3).
constexpr double kKappaEps = 10.0;  // barrier problem solved when E_mu <= kappa_eps mu
constexpr double kKappaMu = 0.2, kThetaMu = 1.5;
constexpr double kSMax = 100.0;
constexpr double kKappaSigma = 1e10;
constexpr double kGammaTheta = 1e-5, kGammaPhi = 1e-8, kDeltaSwitch = 1.0;
constexpr double kSTheta = 1.1, kSPhi = 2.3, kEtaPhi = 1e-8, kGammaAlpha = 0.05;
constexpr double kDeltaW0 = 1e-4, kDeltaWMin = 1e-20, kDeltaWMax = 1e40;
constexpr double kKappaWMinus = 1.0 / 3.0, kKappaWPlus = 8.0, kKappaWPlusFirst = 100.0;
// Ipopt's kappa_d: the barrier objective gains kappa_d mu times the distance to the bound of
// every variable bounded on one side only (the slacks, one-sided control bounds), which keeps
// such variables from running off to infinity.
constexpr double kKappaD = 1e-5;

using Iterate = EulerStages::Iterate;
using StageEval = EulerStages::StageEval;
using TerminalEval = EulerStages::TerminalEval;
using Values = EulerStages::Values;

// The constraint residuals on the right-hand side of the Newton system: at the iterate for a
// regular step (the NLP's rows: defects, the copy row, psi, and c + s of the inequalities), and
// the accumulated c_soc of a second-order correction.
struct Residuals {
  Mat defects;  // nx x N
  Vec copy_row, psi;
  std::vector<Vec> ineq;  // per stage, c_k + s_k
};

double MaxNorm(const Residuals& r) {
  const auto norm = [](const auto& m) { return m.size() > 0 ? m.cwiseAbs().maxCoeff() : 0.0; };
  double v = std::max({norm(r.defects), norm(r.copy_row), norm(r.psi)});
  for (const Vec& c : r.ineq) v = std::max(v, norm(c));
  return v;
}

void RhsOf(const RiccatiProblem& p, RiccatiRhs* r) {
  const size_t N = p.stages.size();
  r->q.resize(N);
  r->b.resize(N);
  for (size_t k = 0; k < N; ++k) {
    r->q[k] = p.stages[k].q;
    r->b[k] = p.stages[k].b;
  }
  r->qN = p.qN;
  r->c = p.c;
  r->x0 = p.x0;
  r->slack_gradient = p.slack_gradient;
}

// The max norm of p's right-hand side (its vectors).
double RhsMaxNorm(const RiccatiProblem& p) {
  const auto norm = [](const Vec& v) { return v.size() > 0 ? v.cwiseAbs().maxCoeff() : 0.0; };
  double v = std::max({norm(p.qN), norm(p.c), norm(p.x0), norm(p.slack_gradient)});
  for (const RiccatiStage& s : p.stages) v = std::max({v, norm(s.q), norm(s.b)});
  return v;
}

double MaxNorm(const RiccatiSolution& z) {
  const auto norm = [](const Vec& v) { return v.size() > 0 ? v.cwiseAbs().maxCoeff() : 0.0; };
  double v = std::max(norm(z.nu), norm(z.s));
  for (const Vec& x : z.x) v = std::max(v, norm(x));
  for (const Vec& u : z.u) v = std::max(v, norm(u));
  for (const Vec& l : z.lambda) v = std::max(v, norm(l));
  return v;
}

// What the filter line search compares a trial point with (Wächter & Biegler, Sec. 2.3).
struct LineSearchReference {
  double theta = 0, phi = 0, gphi = 0;  // at the iterate; gphi: barrier objective's slope along d
  double theta_min = 0, theta_max = 0;
  const std::vector<std::pair<double, double>>* filter = nullptr;
};

struct Direction {
  Mat dX, dU;  // dX col 0: x_0's free components (0 elsewhere)
  Mat dT;      // 1 x 1 (free final time) or empty
  Vec dV;
  std::vector<Vec> ds, dy, dv;
  Mat dzl, dzu;
  Mat dzxl, dzxu;  // the state bounds' multipliers
  Mat dzTl, dzTu;  // T's
  Mat dSB;         // the boundary inequalities' slacks (nbi x 1)
  Mat dzSl, dzSu;  // their bounds' multipliers
  Mat lam;         // new values
  Vec lamV, nu;
};

class RiccatiInteriorPoint {
 public:
  RiccatiInteriorPoint(const EulerStages& S, const RiccatiIpOptions& o) : S_(S), o_(o) {}
  NlpSolution Run(const Vec& z0);

 private:
  // The simple bounds, one Box per kind of bounded variable: the controls u_k (nodes 0..N-1, the
  // trapezoid's 0..N, at
  // offset nx of stage k's (x_k, u_k)), x_0's free components (node 0: the initial-state
  // bounds) and the states x_k (nodes 1..N, offset 0; x_N's block is the terminal one), each
  // entry with a lower and an upper multiplier in z (zl, zu or zxl,
  // zxu). Every barrier, step and multiplier rule below loops over them.
  // The final time T (free_time) is a third kind: one entry at node 0, whose barrier terms
  // enter stage 0's block where T is a variable (TimeBoundTerms), not through AddBoundTerms;
  // the boundary inequalities' slacks a fourth (one column, "node 0"), whose barrier terms go
  // to the Riccati solve's terminal slacks (SlackTerms).
  enum class BoxKind { kControl, kState, kTime, kSlack };
  struct Box {
    BoxKind kind = BoxKind::kControl;
    const Vec* lb = nullptr;  // relaxed by bound_relax_factor
    const Vec* ub = nullptr;
    int first = 0, last = 0;           // nodes [first, last)
    int offset = 0;                    // in a stage's (x, u)
    const Vec* original_lb = nullptr;  // as the problem states them
    const Vec* original_ub = nullptr;
  };
  std::vector<Box> boxes_;
  // Mat& for an Iterate or Direction of either constness: the member of b's kind.
  template <class It>
  static auto& Pick(It& it, const Box& b, auto control, auto state, auto time, auto slack) {
    return b.kind == BoxKind::kControl ? it.*control
           : b.kind == BoxKind::kState ? it.*state
           : b.kind == BoxKind::kTime  ? it.*time
                                       : it.*slack;
  }
  template <class It>
  static auto& Value(It& it, const Box& b) {
    return Pick(it, b, &Iterate::U, &Iterate::X, &Iterate::T, &Iterate::SB);
  }
  template <class It>
  static auto& Zl(It& it, const Box& b) {
    return Pick(it, b, &Iterate::zl, &Iterate::zxl, &Iterate::zTl, &Iterate::zSl);
  }
  template <class It>
  static auto& Zu(It& it, const Box& b) {
    return Pick(it, b, &Iterate::zu, &Iterate::zxu, &Iterate::zTu, &Iterate::zSu);
  }
  static const Mat& Step(const Direction& d, const Box& b) {
    return Pick(d, b, &Direction::dU, &Direction::dX, &Direction::dT, &Direction::dSB);
  }
  template <class D>
  static auto& DZl(D& d, const Box& b) {
    return Pick(d, b, &Direction::dzl, &Direction::dzxl, &Direction::dzTl, &Direction::dzSl);
  }
  template <class D>
  static auto& DZu(D& d, const Box& b) {
    return Pick(d, b, &Direction::dzu, &Direction::dzxu, &Direction::dzTu, &Direction::dzSu);
  }
  // Calls f(box, node k, component j, lower bound, upper bound) for every entry with a finite
  // bound on at least one side (the other side +-inf).
  template <class F>
  void ForEachBounded(F&& f) const {
    for (const Box& b : boxes_) {
      for (int k = b.first; k < b.last; ++k) {
        for (int j = 0; j < b.lb->size(); ++j) {
          const double lo = (*b.lb)[j], hi = (*b.ub)[j];
          if (RipFinite(lo) || RipFinite(hi)) f(b, k, j, lo, hi);
        }
      }
    }
  }
  // Adds node k's bound terms (Sigma = z / distance to H's diagonal, the barrier gradient
  // -+ mu / distance, and kappa_d mu for one-sided bounds to g) at their offsets in the node's
  // block: stage k's (x_k, u_k) for k < N, x_N for k = N (the trapezoid's node blocks (x_k, u_k)
  // for every k).
  void AddBoundTerms(int k, double mu, Mat* H, Vec* g) const;
  double Theta(const Values& v, const std::vector<Vec>& s) const;
  double BarrierObjective(const Values& v, const Iterate& it) const;
  void Measure(double mu);
  // The residuals of the NLP's rows at values v with slacks s.
  void ResidualsAt(const Values& v, const std::vector<Vec>& s, Residuals* r) const;
  // Builds the condensed stagewise KKT system at it_ for barrier parameter mu with the constraint
  // residuals r on its right-hand side and solves it (kind: below); fills the full direction.
  // False with the reason when the system cannot be solved.
  enum class StepKind {
    kNewton,                 // the primal-dual Newton step, with inertia correction
    kSecondOrderCorrection,  // the Newton step's matrix again (its delta_w, delta_c)
    kFeasibility,  // the restoration phase's minimum-norm step: identity Hessian, no objective
  };
  bool BuildAndSolve(
      double mu, const Residuals& r, StepKind kind, Direction* d, std::string* failure);
  // Iterative refinement of sol_ in the stagewise system qp_ factorized with dw, dc (Ipopt's
  // rule, on the condensed system): at least min_refinement_steps and at most
  // max_refinement_steps corrections by RiccatiSolver::SolveFactored, stopping once the
  // residual ratio ||r|| / (min(||sol||, 1e6 ||rhs||) + ||rhs||) is <= 1e-10 or stops falling.
  // Near a solution the condensed system's entries reach mu / s^2 ~ 1 / mu; without refinement
  // the multipliers carry the recursion's rounding and the dual infeasibility stalls (at
  // tol 1e-12: brachistochrone's stopped at 1e-7 .. 1e-5).
  void Refine(double dw, double dc);
  // The largest primal and dual steps in (0, 1] that keep slacks, control bounds and their
  // multipliers at least a fraction 1 - tau from their bounds (fraction to the boundary).
  void StepToBoundary(const Direction& d,
                      double tau,
                      double* alpha_primal,
                      double* alpha_dual) const;
  // it_'s primal variables moved by alpha along d into trial (its storage reused).
  void PrimalTrial(const Direction& d, double alpha, Iterate* trial) const;
  // Whether a trial point is acceptable: to the filter, and against the iterate either by the
  // Armijo condition on the barrier objective (an f-type step, when theta <= theta_min and the
  // switching condition holds for alpha) or by sufficient decrease in theta or phi.
  bool Acceptable(const LineSearchReference& ref,
                  const Values& v,
                  const Iterate& trial,
                  double alpha,
                  bool* f_type) const;
  // Ipopt's second-order correction (Wächter & Biegler, Sec. 2.4, steps ), tried
  // when the full first trial x + alpha0 d was rejected without a decrease in theta (the Maratos
  // effect): the step's KKT matrix is solved again with the constraint residuals replaced by
  // c_soc = alpha0 c(x) + c(x + alpha0 d), up to four times (c_soc <- alpha_soc c_soc +
  // c(x_soc)) while theta falls by 1 % from one correction to the next. On success *d, *alpha,
  // *trial and *tv hold the corrected step, its fraction-to-the-boundary step size and the
  // accepted point.
  bool SecondOrderCorrection(const LineSearchReference& ref,
                             double alpha0,
                             double tau,
                             Direction* d,
                             double* alpha,
                             Iterate* trial,
                             Values* tv,
                             bool* f_type);
  void LeastSquaresMultipliers();
  // Stage k's Q, q (from the Hessian H and gradient g of its (x_k, u_k), with the carried rows
  // when S_.np() > 0 (WithCarried); stage 0 keeps x_0's free components, T and u_0), A and B of
  // the linearized Euler step x_{k+1} = x_k + h f (with T's column and the carried identity),
  // and on the last stage with the copy of u_{N-1} its identity rows. True on that stage. The
  // right-hand side b is the caller's (the Newton step's defects, or zero for the multiplier
  // start).
  bool StageBlocks(int k, const Mat& H, const Vec& g, RiccatiStage* q) const;
  // The trapezoid's stagewise QP (S_.trapezoid). Its defect k couples the nodes k and k + 1
  // through u_{k+1} as well, so the recursion's state is xi = (x_k, u_k) (free components of u)
  // and its control u_{k+1}: stage 0 has no state and the controls (x_0's free components,
  // u_0), with the identity transition into xi_1 = (x_0, u_0); stage k + 1 (k < N) carries node
  // k's Hessian and gradient on xi and none on its control (node k + 1's are on xi_{k+2}), and
  // its transition is the linearized defect solved for x_{k+1}:
  //   x_{k+1} = M_k^-1 [(I + h/2 f_x,k) x_k + h/2 f_u,k u_k + h/2 f_u,k+1 u_{k+1} - d_k],
  //   M_k = I - h/2 f_x,k+1,   u_{k+1} = u_{k+1};
  // the terminal block is node N's (x_N, u_N). The rows are M_k^-1 times the NLP's, so the NLP's
  // defect multipliers are M_k^-T times the recursion's (TrapezoidPrimalDual), and the KKT
  // matrix's inertia is the NLP's (a congruence, and each duplicated u_{k+1} adds one positive
  // and one negative eigenvalue with its copy row). node_H_, node_g_ hold the nodes' (x, u)
  // blocks (condensed inequalities and bound terms included); `defects` the right-hand side's
  // defects (nullptr: zero).
  // False with the reason in *failure when an M_k is singular (f_x with an eigenvalue near
  // 2 / h: the step cannot be computed this way; Ipopt's factorization would not need M_k).
  bool TrapezoidQp(
      double mu, const Residuals& r, bool feasibility, bool relaxed, std::string* failure);
  // With boundary constraints xi also carries x_0's free components w (xi = (x, u, T, w),
  // w_{k+1} = w_k, b's x_0 part on w in the terminal rows and its Hessian on the terminal
  // block, unless !boundary_hessian: the restoration's and least-squares identity).
  // With a free final time xi also carries T (xi = (x, u, T), T_{k+1} = T_k, the defect's T
  // column h / (2 duration) (f_k + f_{k+1})), T being stage 0's control with the diagonal hTT
  // and gradient gT there (its barrier terms, or the least-squares problem's identity).
  bool TrapezoidStagesFromNodes(
      const Mat* defects, double hTT, double gT, bool boundary_hessian, std::string* failure);
  // The step's dX, dU (nodes 0..N), dT and defect multipliers from sol_ (the trapezoid's QP).
  void TrapezoidPrimalDual(Mat* dX, Mat* dU, Mat* dT, Mat* lam) const;
  // LeastSquaresMultipliers' QP for the trapezoid (node blocks I + J^T J).
  bool TrapezoidLeastSquaresQp();  // false where an M_k is singular
  // u_k's step from a stage's solved "controls" (their last nuf entries are the free control
  // components): scattered into du, 0 for the fixed components.
  void ScatterControls(const Vec& stage_controls, Eigen::Ref<Vec> du) const;
  // With carried entries (S_.np(): a free final time T, and with boundary constraints x_0's
  // free components w) every stage's state is (x_k, T, w) (the terminal one (x_N, T, w, v)):
  // H and g (in (x, u) order) with those rows and columns inserted after x, T's Hessian row HT
  // (nullptr: zeros), diagonal hTT and gradient gT; w's rows empty; into Ha, ga.
  void WithCarried(
      const Mat& H, const Vec& g, const Vec* HT, double hTT, double gT, Mat* Ha, Vec* ga) const;
  // The terminal rows' Jacobian in the terminal block (x_N, T, w, v): psi_x on x_N; b's on x_N
  // and on the carried w.
  void TerminalRows(Mat* C) const;
  // Adds the Hessian of nu_b^T b(x_0, x_N) to the terminal block, x_0's part on the carried w
  // (which starts at w0: Euler's (x_N, T, w, v), the trapezoid's (x_N, u_N, T, w)).
  void AddBoundaryHessian(Mat* QN, int w0) const;
  // Adds T's barrier terms (its Sigma and barrier gradient, kappa_d for a one-sided bound) to
  // hTT and gT, as AddBoundTerms does for the other variables.
  void TimeBoundTerms(double mu, double* hTT, double* gT) const;
  // The boundary inequalities' slacks in the Riccati solve (RiccatiProblem::slack_hessian and
  // slack_gradient on their terminal rows of qp_): weight `base` (0 for the Newton step, 1 for
  // the restoration's minimum-norm step and the least-squares multipliers) plus, with
  // `barrier`, Sigma = z / distance; the gradient is the barrier's (-+ mu / distance, kappa_d mu
  // for a one-sided bound) with `barrier`, else the bound multipliers' z_u - z_l.
  void SlackTerms(double mu, double base, bool barrier);
  // Swaps a trial's primal variables (x, u, T, v, slacks) into it_.
  void TakePrimal(Iterate* trial);
  // The restoration's Levenberg-Marquardt form of stage q: x_{k+1} = A x + B u + b + e with e
  // a new leading block of the stage's controls, weighted restoration_rho_ |e|^2 / 2.
  void RelaxDefects(RiccatiStage* q) const;
  // Adds stage k's inequalities with their slacks and multipliers eliminated to the (x, u)
  // Hessian H and gradient g (n = nx + nu): J^T S^-1 V J and J^T (mu S^-1 e - kappa_d mu e +
  // S^-1 V rc), J = [c_x c_u], rc the rows' residuals (c + s at the iterate).
  void CondenseInequalities(int k, double mu, const Vec& rc, int n, Mat* H, Vec* g);
  // The restoration phase, entered when the filter line search reaches its minimal step at a
  // point that is not acceptable (Wächter & Biegler's A-9; not their restoration NLP, see the
  // README): the iterate where it begins enters the filter; then minimum-norm Gauss-Newton
  // steps on the constraints (StepKind::kFeasibility, whose barrier terms keep slacks and
  // controls inside their bounds), each backtracked until theta falls by the factor
  // 1 - gamma_theta (where no step of the backtracking does, the step is recomputed with
  // Levenberg-Marquardt damping, RelaxDefects, at falling rho: kRestorationRho), until a point
  // is acceptable to the filter and decreases theta or phi
  // against the iterate where the phase began; the equality multipliers are then reset to their
  // least-squares estimates (the bound multipliers are only kept within their kappa_sigma
  // window). Leaves it_, vals_ and the first derivatives consistent; true when the method can
  // go on (also when an iteration or time limit ends the phase: the main loop then stops),
  // false with the reason and the status: Restoration_Failed when a step cannot decrease theta,
  // Error_In_Step_Computation or Invalid_Number_Detected as in the main loop.
  bool Restore(const LineSearchReference& ref,
               double tau,
               std::vector<std::pair<double, double>>* filter,
               std::string* why,
               std::string* solver_status);
  // Keeps the slacks' and the control bounds' multipliers within a factor kappa_sigma of
  // mu / distance (Ipopt's safeguard after every step).
  void ClampBoundMultipliers();
  // Ipopt's acceptable level at it_ (after Measure()).
  bool CurrentIsAcceptable() const;
  NlpSolution Finish(SolveStatus status, const std::string& solver_status, std::string message);

  const EulerStages& S_;
  const RiccatiIpOptions& o_;
  Iterate it_;
  std::vector<StageEval> st_;
  TerminalEval te_;
  Values vals_;  // values at it_
  double sigma_ = 1.0;
  // Measures at it_ (Measure()).
  double dual_inf_ = 0, constr_viol_ = 0, compl_ = 0, compl_mu_ = 0, s_d_ = 1, s_c_ = 1;
  double E0_ = 0, Emu_ = 0;
  Mat rx_, ru_;
  Vec rv_;
  double rT_ = 0.0;
  // The restoration's damping (inf: Gauss-Newton steps; else RelaxDefects' weight rho), and
  // how often a step was damped further.
  double restoration_rho_ = std::numeric_limits<double>::infinity();
  int restoration_damped_ = 0;
  Residuals res_, soc_res_, trial_res_;
  RiccatiRhs rhs_, refine_rhs_;
  RiccatiSolution correction_;
  int refinement_steps_ = 0;
  Direction soc_d_;
  double dw_ = 0.0, dc_ = 0.0;  // the regularization of the last solve
  int soc_trials_ = 0, soc_accepted_ = 0;
  int restoration_phases_ = 0, restoration_iterations_ = 0, acceptable_count_ = 0;
  // The last step, for print_level 1: its primal and dual step sizes and kind (f: Armijo, h:
  // filter, s: a second-order correction, r: after the restoration phase).
  double last_alpha_ = 0.0, last_alpha_z_ = 0.0;
  const char* last_step_ = "";
  RiccatiProblem qp_;
  RiccatiSolver riccati_;
  RiccatiSolution sol_;
  // Workspace of BuildAndSolve (sized once).
  Mat H_;
  Vec g_, jd_, w_, r_;
  mutable Mat Ha_;  // a stage's block with the carried rows and columns (WithCarried)
  mutable Vec ga_;
  std::vector<int> nonzero_;
  mutable std::vector<int> stage0_, stagek_;  // StageBlocks' index selections  // StageBlocks'
                                              // stage-0 indices: x_0's free components, u_0
  // The trapezoid's node blocks, M_k's factors and (x, free u) selection (TrapezoidQp).
  std::vector<Mat> node_H_;
  std::vector<Vec> node_g_;
  std::vector<Eigen::PartialPivLU<Mat>> trap_m_;
  Mat trap_scratch_m_, trap_scratch_rhs_, trap_scratch_solved_;
  Vec trap_scratch_defect_;
  std::vector<int> trap_sel_;
  double delta_last_ = 0.0;
  int iterations_ = 0, regularizations_ = 0, factorizations_ = 0, trials_ = 0;
  double kkt_cpu_ = 0.0, callback_cpu_ = 0.0, mu_ = 0.1;
  std::vector<IterationRecord> history_;
  Stopwatch watch_;
};

double RiccatiInteriorPoint::Theta(const Values& v, const std::vector<Vec>& s) const {
  double th = v.defects.lpNorm<1>() + v.psi.lpNorm<1>() + v.copy_row.lpNorm<1>();
  for (int k = 0; k <= S_.N; ++k) {
    if (s[k].size() > 0) th += (v.c[k] + s[k]).lpNorm<1>();
  }
  return th;
}

double RiccatiInteriorPoint::BarrierObjective(const Values& v, const Iterate& it) const {
  double phi = sigma_ * v.f;
  for (int k = 0; k <= S_.N; ++k) {
    for (int i = 0; i < it.s[k].size(); ++i) {
      phi += mu_ * (kKappaD * it.s[k][i] - std::log(it.s[k][i]));
    }
  }
  ForEachBounded([&](const Box& b, int k, int j, double lo, double hi) {
    const double x = Value(it, b)(j, k);
    if (RipFinite(lo)) phi -= mu_ * std::log(x - lo);
    if (RipFinite(hi)) phi -= mu_ * std::log(hi - x);
    if (RipFinite(lo) && !RipFinite(hi)) phi += kKappaD * mu_ * (x - lo);
    if (RipFinite(hi) && !RipFinite(lo)) phi += kKappaD * mu_ * (hi - x);
  });
  return phi;
}

void RiccatiInteriorPoint::Measure(double mu) {
  const int N = S_.N;
  S_.LagrangianGradient(it_, sigma_, st_, te_, &rx_, &ru_, &rv_, &rT_);
  if (S_.free_time) rT_ += it_.zTu(0, 0) - it_.zTl(0, 0);
  ru_ -= it_.zl;
  ru_ += it_.zu;
  if (S_.has_state_multipliers()) {
    rx_ -= it_.zxl;
    rx_ += it_.zxu;
  }
  double dual = rx_.rightCols(N).lpNorm<Eigen::Infinity>();
  for (int i : S_.free0) dual = std::max(dual, std::abs(rx_(i, 0)));
  for (int i = 0; i < S_.nbi(); ++i) {  // a slack's: -nu - z_l + z_u
    const double r = -it_.nu[S_.npsi + S_.bineq[i]] - it_.zSl(i, 0) + it_.zSu(i, 0);
    dual = std::max(dual, std::abs(r));
  }
  dual = std::max(dual, std::abs(rT_));
  for (int j : S_.ufree) dual = std::max(dual, ru_.row(j).lpNorm<Eigen::Infinity>());
  if (rv_.size() > 0) dual = std::max(dual, rv_.lpNorm<Eigen::Infinity>());
  double cv = std::max(vals_.defects.lpNorm<Eigen::Infinity>(),
                       vals_.psi.size() > 0 ? vals_.psi.lpNorm<Eigen::Infinity>() : 0.0);
  if (vals_.copy_row.size() > 0) cv = std::max(cv, vals_.copy_row.lpNorm<Eigen::Infinity>());
  double compl0 = 0.0, complmu = 0.0;
  double mult_sum = it_.lam.lpNorm<1>() + it_.lamV.lpNorm<1>() + it_.nu.lpNorm<1>();
  double bound_sum = 0.0;
  int m = N * S_.nx + static_cast<int>(it_.lamV.size() + it_.nu.size());
  int nb = 0;
  for (int k = 0; k <= N; ++k) {
    const Vec& s = it_.s[k];
    if (s.size() == 0) continue;
    dual = std::max(dual, (it_.y[k] - it_.v[k]).lpNorm<Eigen::Infinity>());
    cv = std::max(cv, (vals_.c[k] + s).lpNorm<Eigen::Infinity>());
    for (int i = 0; i < s.size(); ++i) {
      const double sv = s[i] * it_.v[k][i];
      compl0 = std::max(compl0, std::abs(sv));
      complmu = std::max(complmu, std::abs(sv - mu));
    }
    mult_sum += it_.y[k].lpNorm<1>() + it_.v[k].lpNorm<1>();
    bound_sum += it_.v[k].lpNorm<1>();
    m += static_cast<int>(s.size());
    nb += static_cast<int>(s.size());
  }
  // A bound at `distance` with multiplier z.
  const auto bound = [&](double distance, double z) {
    const double c = distance * z;
    compl0 = std::max(compl0, std::abs(c));
    complmu = std::max(complmu, std::abs(c - mu));
    bound_sum += z;
    mult_sum += z;
    ++nb;
  };
  ForEachBounded([&](const Box& b, int k, int j, double lo, double hi) {
    const double x = Value(it_, b)(j, k);
    if (RipFinite(lo)) bound(x - lo, Zl(it_, b)(j, k));
    if (RipFinite(hi)) bound(hi - x, Zu(it_, b)(j, k));
  });
  const int n = N * S_.nx + S_.nctl() * S_.nuf() + S_.nw() + S_.nT() +
                static_cast<int>(it_.V.size()) + S_.nbi() + nb;  // slacks count too
  s_d_ = std::max(kSMax, mult_sum / std::max(1, m + n)) / kSMax;
  s_c_ = std::max(kSMax, bound_sum / std::max(1, n)) / kSMax;
  dual_inf_ = dual;
  constr_viol_ = cv;
  compl_ = compl0;
  compl_mu_ = complmu;
  E0_ = std::max({dual / s_d_, cv, compl0 / s_c_});
  Emu_ = std::max({dual / s_d_, cv, complmu / s_c_});
}

void RiccatiInteriorPoint::ResidualsAt(const Values& v,
                                       const std::vector<Vec>& s,
                                       Residuals* r) const {
  r->defects = v.defects;
  r->copy_row = v.copy_row;
  r->psi = v.psi;
  r->ineq.resize(S_.N + 1);
  for (int k = 0; k <= S_.N; ++k) {
    r->ineq[k].resize(s[k].size());
    if (s[k].size() > 0) r->ineq[k] = v.c[k] + s[k];
  }
}

bool RiccatiInteriorPoint::BuildAndSolve(
    double mu, const Residuals& r, StepKind kind, Direction* d, std::string* failure) {
  const bool same_regularization = kind == StepKind::kSecondOrderCorrection;
  const bool feasibility = kind == StepKind::kFeasibility;
  // The restoration's Levenberg-Marquardt step: defect relaxations e_k lead each stage's
  // controls (RelaxDefects), the terminal rows relaxed by the dual regularization 1 / rho:
  // both residuals weighted rho / 2 |.|^2 beside the step's own |d|^2 / 2.
  const bool relaxed = feasibility && RipFinite(restoration_rho_);
  const int ne = relaxed ? S_.nx : 0;
  const int N = S_.N, nx = S_.nx, nu = S_.nu;
  const double cpu0 = CpuSeconds();
  if (S_.trapezoid) {
    if (!TrapezoidQp(mu, r, feasibility, relaxed, failure)) {
      kkt_cpu_ += CpuSeconds() - cpu0;
      return false;
    }
  } else {
    qp_.stages.resize(N);
    for (int k = 0; k < N; ++k) {
      const StageEval& e = st_[k];
      RiccatiStage& q = qp_.stages[k];
      // The stage's (x_k, u_k) Hessian and gradient with the slacks and bound multipliers
      // eliminated, in the workspace H_, g_; then cut into Q, q, A, B.
      if (feasibility) {
        H_.setIdentity(nx + nu, nx + nu);
        g_.setZero(nx + nu);
      } else {
        H_ = e.H;
        g_.resize(nx + nu);
        const double hk = S_.Step(it_, k);
        g_.head(nx) = sigma_ * hk * e.Lx;
        g_.tail(nu) = sigma_ * hk * e.Lu;
        if (k == 0 && S_.initial_cost) {
          H_.topLeftCorner(nx, nx) += te_.H0;
          g_.head(nx) += sigma_ * te_.grad0;
        }
      }
      if (it_.s[k].size() > 0) CondenseInequalities(k, mu, r.ineq[k], nx + nu, &H_, &g_);
      AddBoundTerms(k, mu, &H_, &g_);
      if (S_.np() > 0) {
        // T's entries: its Hessian row, the stage's dJ/dT, and at stage 0 (where T is a
        // variable) its barrier terms; the restoration's minimum-norm step weighs T once, at 0.
        // The carried copies of x_0's free components have none.
        const Vec* HT = feasibility || !S_.free_time ? nullptr : &e.HT;
        double hTT = feasibility && k == 0 ? 1.0 : 0.0, gT = feasibility ? 0.0 : sigma_ * e.gT;
        if (k == 0) TimeBoundTerms(mu, &hTT, &gT);
        WithCarried(H_, g_, HT, hTT, gT, &Ha_, &ga_);
      }
      const bool last_copy = StageBlocks(k, S_.np() > 0 ? Ha_ : H_, S_.np() > 0 ? ga_ : g_, &q);
      q.b.setZero(q.B.rows());
      q.b.head(nx) = -r.defects.col(k);
      if (last_copy) q.b.tail(nu) = -r.copy_row;
      if (relaxed) RelaxDefects(&q);
    }
    const int nxN = nx + (S_.copy ? nu : 0);
    qp_.QN.setZero(nxN, nxN);
    qp_.qN.setZero(nxN);
    if (feasibility) {
      qp_.QN.setIdentity();
    } else {
      qp_.QN.topLeftCorner(nx, nx) = te_.H;
      qp_.qN.head(nx) = sigma_ * te_.grad;
    }
    if (S_.copy) {
      if (!feasibility) qp_.QN += st_[N].H;
      CondenseInequalities(N, mu, r.ineq[N], nxN, &qp_.QN, &qp_.qN);
    }
    AddBoundTerms(N, mu, &qp_.QN, &qp_.qN);
    if (S_.np() > 0) {  // the terminal block (x_N, T, w, v): T's row empty (x_N's terms do not
      WithCarried(qp_.QN, qp_.qN, nullptr, 0.0, 0.0, &Ha_, &ga_);  // depend on it)
      qp_.QN.swap(Ha_);
      qp_.qN.swap(ga_);
    }
    if (!feasibility) AddBoundaryHessian(&qp_.QN, nx + S_.nT());
    TerminalRows(&qp_.C);
    qp_.c = r.psi;
    qp_.x0.resize(0);
    SlackTerms(mu, feasibility ? 1.0 : 0.0, true);
    // The joint first stage where boundary rows link x(t0)'s free components (multi-phase and
    // estimation problems: their first stage's curvature comes from those rows, pinene's never
    // from the stage itself); elsewhere (a free T, free x(t0) without boundary rows) a singular
    // first stage is regularized, as before: jointly solved, quadrotor's last steps at tol 1e-10
    // (H_uu singular in its last iterations) oscillated and stopped at the acceptable level.
    qp_.joint_first_stage = S_.nb > 0;
  }

  // delta_w goes to every diagonal entry of the recursion, the carried copies T_k, w_k
  // included, so T and w are regularized N + 1 times where Ipopt regularizes them once. Making
  // it exact (-delta_w on the copies first) was measured on the library (2026-12-07): closer to
  // Ipopt's iterates (tumor, balanced-field, f8-aircraft, cart-pendulum at Ipopt's point), but
  // space-shuttle and dielectrophoretic-particle then ended Restoration_Failed where they
  // converge with this, so the stronger regularization of the copies stays.
  if (same_regularization) {  // the matrix is the last Newton step's: solve with its factors
    RhsOf(qp_, &rhs_);
    riccati_.SolveFactored(qp_, rhs_, &sol_);
  }
  // Inertia correction (Ipopt's rule, Wächter & Biegler Sec. 3.1, on the Riccati recursion).
  double dw = 0.0, dc = relaxed && S_.nterm() > 0 ? 1.0 / restoration_rho_ : 0.0;
  bool regularized = false;
  for (; !same_regularization;) {
    ++factorizations_;
    const RiccatiOutcome out = riccati_.Solve(qp_, dw, dc, &sol_);
    if (out == RiccatiOutcome::kSolved) break;
    if (out == RiccatiOutcome::kTerminalRowsDegenerate && dc == 0.0) {
      dc = 1e-8 * std::pow(mu, 0.25);
      continue;
    }
    if (dw == 0.0) {
      dw = delta_last_ == 0.0 ? kDeltaW0 : std::max(kDeltaWMin, kKappaWMinus * delta_last_);
    } else {
      dw *= delta_last_ == 0.0 ? kKappaWPlusFirst : kKappaWPlus;
    }
    regularized = true;
    if (dw > kDeltaWMax) {
      *failure = "the inertia correction exceeded delta_w = 1e40";
      kkt_cpu_ += CpuSeconds() - cpu0;
      return false;
    }
  }
  Refine(same_regularization ? dw_ : dw, same_regularization ? dc_ : dc);
  if (kind == StepKind::kNewton) {  // the restoration's steps leave Ipopt's memory alone
    if (regularized) {
      ++regularizations_;
      delta_last_ = dw;
    }
    dw_ = dw;
    dc_ = dc;
  }

  // The full direction.
  d->dX.resize(nx, N + 1);
  d->dX.col(0).setZero();
  d->dT.resize(S_.nT(), S_.nT());
  d->dSB.resize(S_.nbi(), 1);
  d->dU.resize(nu, S_.nctl());
  d->lam.resize(nx, N);
  for (int i = 0; i < S_.nbi(); ++i) d->dSB(i, 0) = sol_.s[S_.npsi + S_.bineq[i]];
  if (S_.trapezoid) {
    TrapezoidPrimalDual(&d->dX, &d->dU, &d->dT, &d->lam);
  } else {
    for (int i = 0; i < S_.nw(); ++i) d->dX(S_.free0[i], 0) = sol_.u[0][ne + i];
    if (S_.free_time) d->dT(0, 0) = sol_.u[0][ne + S_.nw()];
    for (int k = 0; k < N; ++k) {
      ScatterControls(sol_.u[k], d->dU.col(k));
      d->dX.col(k + 1) = sol_.x[k + 1].head(nx);
      d->lam.col(k) = sol_.lambda[k].head(nx);
    }
  }
  if (S_.copy) {
    d->dV = sol_.x[N].tail(nu);
    d->lamV = sol_.lambda[N - 1].tail(nu);
  } else {
    d->dV.resize(0);
    d->lamV.resize(0);
  }
  d->nu = sol_.nu;
  d->ds.resize(N + 1);
  d->dy.resize(N + 1);
  d->dv.resize(N + 1);
  for (int k = 0; k <= N; ++k) {
    const Vec& s = it_.s[k];
    if (s.size() == 0) {
      d->ds[k].resize(0);
      d->dy[k].resize(0);
      d->dv[k].resize(0);
      continue;
    }
    const StageEval& e = st_[k];
    const auto du =
        k < N || S_.trapezoid ? Eigen::Ref<const Vec>(d->dU.col(k)) : Eigen::Ref<const Vec>(d->dV);
    const int m = static_cast<int>(s.size());
    Vec& Jd = jd_;
    Jd.resize(m);
    Jd.noalias() = e.cx * d->dX.col(k);
    Jd.noalias() += e.cu * du;
    d->ds[k].resize(m);
    d->dy[k].resize(m);
    d->dv[k].resize(m);
    for (int i = 0; i < m; ++i) {
      const double rc = r.ineq[k][i];
      const double sig = it_.v[k][i] / s[i];
      const double mu_s = mu / s[i];
      const double ds = -rc - Jd[i];
      d->ds[k][i] = ds;
      d->dy[k][i] = (mu_s - kKappaD * mu) - it_.y[k][i] + sig * (rc + Jd[i]);
      d->dv[k][i] = mu_s - it_.v[k][i] - sig * ds;
    }
  }
  d->dzl.setZero(nu, S_.nctl());
  d->dzu.setZero(nu, S_.nctl());
  d->dzxl.setZero(it_.zxl.rows(), it_.zxl.cols());
  d->dzxu.setZero(it_.zxu.rows(), it_.zxu.cols());
  d->dzTl.setZero(S_.nT(), S_.nT());
  d->dzTu.setZero(S_.nT(), S_.nT());
  d->dzSl.setZero(S_.nbi(), 1);
  d->dzSu.setZero(S_.nbi(), 1);
  ForEachBounded([&](const Box& b, int k, int j, double lo, double hi) {
    const double x = Value(it_, b)(j, k), dx = Step(*d, b)(j, k);
    if (RipFinite(lo)) {
      const double dl = x - lo, z = Zl(it_, b)(j, k);
      DZl(*d, b)(j, k) = mu / dl - z - z / dl * dx;
    }
    if (RipFinite(hi)) {
      const double dh = hi - x, z = Zu(it_, b)(j, k);
      DZu(*d, b)(j, k) = mu / dh - z + z / dh * dx;
    }
  });
  kkt_cpu_ += CpuSeconds() - cpu0;
  return true;
}

void RiccatiInteriorPoint::Refine(double dw, double dc) {
  const double rhs_norm = RhsMaxNorm(qp_);
  double last_ratio = kRipInf;
  for (int step = 0; step < o_.max_refinement_steps; ++step) {
    const double residual = RiccatiKktResidual(qp_, dw, dc, sol_, &refine_rhs_);
    const double ratio = residual / (std::min(MaxNorm(sol_), 1e6 * rhs_norm) + rhs_norm);
    if (step >= o_.min_refinement_steps && (ratio <= 1e-10 || ratio >= last_ratio)) break;
    if (!(residual > 0.0)) break;  // exact (or not finite: the step's checks catch it)
    last_ratio = ratio;
    riccati_.SolveFactored(qp_, refine_rhs_, &correction_);
    ++refinement_steps_;
    const int N = static_cast<int>(sol_.u.size());
    for (int k = 0; k <= N; ++k) sol_.x[k] -= correction_.x[k];
    for (int k = 0; k < N; ++k) {
      sol_.u[k] -= correction_.u[k];
      sol_.lambda[k] -= correction_.lambda[k];
    }
    sol_.nu -= correction_.nu;
    sol_.s -= correction_.s;
  }
}

void RiccatiInteriorPoint::AddBoundTerms(int k, double mu, Mat* H, Vec* g) const {
  for (const Box& b : boxes_) {
    if (k < b.first || k >= b.last || b.kind == BoxKind::kTime || b.kind == BoxKind::kSlack) {
      continue;
    }
    // x_N leads the terminal block (Euler's, and the trapezoid's (x_N, u_N)).
    const int off = k < S_.N || S_.trapezoid ? b.offset : 0;
    const Mat& x = Value(it_, b);
    for (int j = 0; j < b.lb->size(); ++j) {
      const double lo = (*b.lb)[j], hi = (*b.ub)[j];
      const int i = off + j;
      if (RipFinite(lo)) {
        const double dl = x(j, k) - lo;
        (*H)(i, i) += Zl(it_, b)(j, k) / dl;
        (*g)[i] -= mu / dl;
        if (!RipFinite(hi)) (*g)[i] += kKappaD * mu;
      }
      if (RipFinite(hi)) {
        const double dh = hi - x(j, k);
        (*H)(i, i) += Zu(it_, b)(j, k) / dh;
        (*g)[i] += mu / dh;
        if (!RipFinite(lo)) (*g)[i] -= kKappaD * mu;
      }
    }
  }
}

void RiccatiInteriorPoint::StepToBoundary(const Direction& d,
                                          double tau,
                                          double* alpha_primal,
                                          double* alpha_dual) const {
  double ap = 1.0, ad = 1.0;
  auto ftb = [&](double value, double step, double* alpha) {
    if (step < 0.0) *alpha = std::min(*alpha, -tau * value / step);
  };
  for (int k = 0; k <= S_.N; ++k) {
    for (int i = 0; i < it_.s[k].size(); ++i) {
      ftb(it_.s[k][i], d.ds[k][i], &ap);
      ftb(it_.v[k][i], d.dv[k][i], &ad);
    }
  }
  ForEachBounded([&](const Box& b, int k, int j, double lo, double hi) {
    const double x = Value(it_, b)(j, k), dx = Step(d, b)(j, k);
    if (RipFinite(lo)) {
      ftb(x - lo, dx, &ap);
      ftb(Zl(it_, b)(j, k), DZl(d, b)(j, k), &ad);
    }
    if (RipFinite(hi)) {
      ftb(hi - x, -dx, &ap);
      ftb(Zu(it_, b)(j, k), DZu(d, b)(j, k), &ad);
    }
  });
  *alpha_primal = ap;
  *alpha_dual = ad;
}

void RiccatiInteriorPoint::PrimalTrial(const Direction& d, double alpha, Iterate* trial) const {
  trial->X = it_.X + alpha * d.dX;
  trial->U = it_.U + alpha * d.dU;
  trial->T = it_.T + alpha * d.dT;
  trial->SB = it_.SB + alpha * d.dSB;
  if (S_.copy) {
    trial->V = it_.V + alpha * d.dV;
  } else {
    trial->V.resize(0);
  }
  trial->s.resize(S_.N + 1);
  for (int k = 0; k <= S_.N; ++k) trial->s[k] = it_.s[k] + alpha * d.ds[k];
}

bool RiccatiInteriorPoint::Acceptable(const LineSearchReference& ref,
                                      const Values& v,
                                      const Iterate& trial,
                                      double alpha,
                                      bool* f_type) const {
  *f_type = false;
  if (!v.ok) return false;
  const double th_t = Theta(v, trial.s);
  const double phi_t = BarrierObjective(v, trial);
  if (!(th_t <= ref.theta_max) || !RipFinite(phi_t)) return false;
  for (const auto& [fth, fphi] : *ref.filter) {
    if (th_t >= fth && phi_t >= fphi) return false;
  }
  const bool switching = ref.gphi < 0.0 && alpha * std::pow(-ref.gphi, kSPhi) >
                                               kDeltaSwitch * std::pow(ref.theta, kSTheta);
  if (ref.theta <= ref.theta_min && switching) {
    *f_type = true;
    return LeqUpToRounding(phi_t - ref.phi, kEtaPhi * alpha * ref.gphi, ref.phi);
  }
  return LeqUpToRounding(th_t, (1.0 - kGammaTheta) * ref.theta, ref.theta) ||
         LeqUpToRounding(phi_t - ref.phi, -kGammaPhi * ref.theta, ref.phi);
}

bool RiccatiInteriorPoint::SecondOrderCorrection(const LineSearchReference& ref,
                                                 double alpha0,
                                                 double tau,
                                                 Direction* d,
                                                 double* alpha,
                                                 Iterate* trial,
                                                 Values* tv,
                                                 bool* f_type) {
  constexpr double kKappaSoc = 0.99;  // Ipopt's kappa_soc
  // c_soc = alpha0 c(x) + c(x + alpha0 d): residuals scale linearly, so the residual structs
  // combine entry by entry.
  const auto accumulate = [](double a, const Residuals& at_trial, Residuals* acc) {
    acc->defects = a * acc->defects + at_trial.defects;
    acc->copy_row = a * acc->copy_row + at_trial.copy_row;
    acc->psi = a * acc->psi + at_trial.psi;
    for (size_t k = 0; k < acc->ineq.size(); ++k) {
      acc->ineq[k] = a * acc->ineq[k] + at_trial.ineq[k];
    }
  };
  soc_res_ = res_;
  ResidualsAt(*tv, trial->s, &trial_res_);
  accumulate(alpha0, trial_res_, &soc_res_);
  double theta_old = ref.theta;
  for (int p = 1; p <= o_.max_soc; ++p) {
    ++soc_trials_;
    std::string failure;
    if (!BuildAndSolve(mu_, soc_res_, StepKind::kSecondOrderCorrection, &soc_d_, &failure)) {
      return false;
    }
    double alpha_soc = 1.0, unused = 1.0;
    StepToBoundary(soc_d_, tau, &alpha_soc, &unused);
    ++trials_;
    PrimalTrial(soc_d_, alpha_soc, trial);
    const double cpu0 = CpuSeconds();
    S_.EvalValues(*trial, tv);
    callback_cpu_ += CpuSeconds() - cpu0;
    if (!tv->ok) return false;
    // Acceptability with the original step's alpha0 (the switching and Armijo conditions
    // refer to the uncorrected direction, as in Wächter & Biegler's ).
    if (Acceptable(ref, *tv, *trial, alpha0, f_type)) {
      std::swap(*d, soc_d_);
      *alpha = alpha_soc;
      ++soc_accepted_;
      return true;
    }
    const double theta_soc = Theta(*tv, trial->s);
    if (p == o_.max_soc || theta_soc > kKappaSoc * theta_old) return false;
    theta_old = theta_soc;
    ResidualsAt(*tv, trial->s, &trial_res_);
    accumulate(alpha_soc, trial_res_, &soc_res_);
  }
  return false;
}

void RiccatiInteriorPoint::ClampBoundMultipliers() {
  for (int k = 0; k <= S_.N; ++k) {
    for (int i = 0; i < it_.s[k].size(); ++i) {
      const double s = it_.s[k][i];
      it_.v[k][i] = std::clamp(it_.v[k][i], mu_ / (kKappaSigma * s), kKappaSigma * mu_ / s);
    }
  }
  ForEachBounded([&](const Box& b, int k, int j, double lo, double hi) {
    const double x = Value(it_, b)(j, k);
    if (RipFinite(lo)) {
      double& z = Zl(it_, b)(j, k);
      z = std::clamp(z, mu_ / (kKappaSigma * (x - lo)), kKappaSigma * mu_ / (x - lo));
    }
    if (RipFinite(hi)) {
      double& z = Zu(it_, b)(j, k);
      z = std::clamp(z, mu_ / (kKappaSigma * (hi - x)), kKappaSigma * mu_ / (hi - x));
    }
  });
}

bool RiccatiInteriorPoint::CurrentIsAcceptable() const {
  return E0_ <= o_.acceptable_tol && dual_inf_ / sigma_ <= o_.acceptable_dual_inf_tol &&
         constr_viol_ <= o_.acceptable_constr_viol_tol &&
         compl_ / sigma_ <= o_.acceptable_compl_inf_tol;
}

bool RiccatiInteriorPoint::Restore(const LineSearchReference& ref,
                                   double tau,
                                   std::vector<std::pair<double, double>>* filter,
                                   std::string* why,
                                   std::string* solver_status) {
  ++restoration_phases_;
  *solver_status = "Restoration_Failed";
  filter->emplace_back((1.0 - kGammaTheta) * ref.theta, ref.phi - kGammaPhi * ref.theta);
  Iterate trial;
  Values tv;
  double theta = ref.theta;
  for (;;) {
    ResidualsAt(vals_, it_.s, &res_);
    bool decreased = false;
    double theta_t = theta;
    // The Gauss-Newton step first (rho = inf); where its line search fails (typically the
    // fraction to the boundary cuts a long step to nothing), Levenberg-Marquardt steps with
    // the dynamics and terminal rows relaxed, shorter as rho falls.
    for (const double rho : kRestorationRho) {
      if (RipFinite(rho)) ++restoration_damped_;  // a step recomputed with damping
      restoration_rho_ = rho;
      std::string failure;
      if (!BuildAndSolve(mu_, res_, StepKind::kFeasibility, &soc_d_, &failure)) {
        restoration_rho_ = kRipInf;
        *why = "restoration phase: " + failure;
        *solver_status = "Error_In_Step_Computation";
        return false;
      }
      double alpha = 1.0, unused = 1.0;
      StepToBoundary(soc_d_, tau, &alpha, &unused);
      for (; alpha >= 1e-10; alpha *= 0.5) {
        ++trials_;
        PrimalTrial(soc_d_, alpha, &trial);
        const double cpu0 = CpuSeconds();
        S_.EvalValues(trial, &tv);
        callback_cpu_ += CpuSeconds() - cpu0;
        if (!tv.ok) continue;
        theta_t = Theta(tv, trial.s);
        // Strictly lower, by the sufficient-decrease factor up to rounding.
        if (theta_t < theta && LeqUpToRounding(theta_t, (1.0 - kGammaTheta) * theta, theta)) {
          decreased = true;
          break;
        }
      }
      if (decreased) break;
    }
    restoration_rho_ = kRipInf;
    if (!decreased) {
      char buf[160];
      std::snprintf(buf,
                    sizeof buf,
                    "the restoration phase could not decrease the constraint violation "
                    "(theta = %.3e, %d restoration iterations)",
                    theta,
                    restoration_iterations_);
      *why = buf;
      return false;
    }
    TakePrimal(&trial);
    std::swap(vals_, tv);
    ClampBoundMultipliers();
    theta = theta_t;
    ++iterations_;
    ++restoration_iterations_;
    const double cpu0 = CpuSeconds();
    const bool ok = S_.EvalDerivatives(it_, &st_, &te_);
    callback_cpu_ += CpuSeconds() - cpu0;
    if (!ok) {
      *why = "restoration phase: a derivative at an iterate is not finite";
      *solver_status = "Invalid_Number_Detected";
      return false;
    }
    const double phi = BarrierObjective(vals_, it_);
    bool in_filter = theta <= ref.theta_max && RipFinite(phi);
    for (const auto& [fth, fphi] : *filter) {
      if (theta >= fth && phi >= fphi) in_filter = false;
    }
    if (in_filter && (LeqUpToRounding(theta, (1.0 - kGammaTheta) * ref.theta, ref.theta) ||
                      LeqUpToRounding(phi - ref.phi, -kGammaPhi * ref.theta, ref.phi))) {
      LeastSquaresMultipliers();
      return true;  // the main loop records this iterate
    }
    if (iterations_ >= o_.max_iter || watch_.cpu() >= o_.max_cpu_time) return true;
    // An intermediate iterate of the phase: in the history without a dual infeasibility (not
    // measured here).
    IterationRecord rec;
    rec.iteration = iterations_;
    rec.J = vals_.f;
    ResidualsAt(vals_, it_.s, &res_);
    rec.primal_inf = MaxNorm(res_);
    rec.cpu_seconds = watch_.cpu();
    history_.push_back(rec);
  }
}

void RiccatiInteriorPoint::CondenseInequalities(
    int k, double mu, const Vec& rc, int n, Mat* H, Vec* g) {
  const StageEval& e = st_[k];
  const Vec& s = it_.s[k];
  const int m = static_cast<int>(s.size());
  const int nx = S_.nx;
  w_.resize(m);
  r_.resize(m);
  for (int i = 0; i < m; ++i) {
    const double sig = it_.v[k][i] / s[i];
    w_[i] = sig;
    r_[i] = mu / s[i] - kKappaD * mu + sig * rc[i];
  }
  const auto column = [&](int j) {
    return j < nx ? e.cx.data() + static_cast<long>(j) * m
                  : e.cu.data() + static_cast<long>(j - nx) * m;
  };
  // Only the columns of J with a nonzero entry contribute (a ball's row has them in its own
  // controls only).
  nonzero_.clear();
  for (int j = 0; j < n; ++j) {
    const double* cj = column(j);
    for (int l = 0; l < m; ++l) {
      if (cj[l] != 0.0) {
        nonzero_.push_back(j);
        break;
      }
    }
  }
  Mat& Hm = *H;
  const int nnz = static_cast<int>(nonzero_.size());
  for (int b = 0; b < nnz; ++b) {
    const int j = nonzero_[b];
    const double* cj = column(j);
    double gj = 0.0;
    for (int l = 0; l < m; ++l) gj += cj[l] * r_[l];
    (*g)[j] += gj;
    for (int a = b; a < nnz; ++a) {
      const int i = nonzero_[a];
      const double* ci = column(i);
      double v = 0.0;
      for (int l = 0; l < m; ++l) v += ci[l] * w_[l] * cj[l];
      Hm(i, j) += v;
      if (i != j) Hm(j, i) += v;
    }
  }
}

// Ipopt's starting equality multipliers: the least-squares solution of the dual
// infeasibility at the start (Wächter & Biegler, Sec. 3.6), i.e. the augmented system with the
// identity in place of the Hessian, solved by the same recursion: with the slacks eliminated
// (y = J_c w + v) it is the stage QP with Q_k = I + J_c^T J_c, q_k = grad f - z_l + z_u +
// J_c^T v, no transition or terminal residuals. Discarded (zero) when its largest entry exceeds
// 1000 (Ipopt's constr_mult_init_max) or the recursion fails.
bool RiccatiInteriorPoint::StageBlocks(int k, const Mat& H, const Vec& g, RiccatiStage* q) const {
  const int nx = S_.nx, nu = S_.nu, nT = S_.nT(), nxa = nx + S_.np();
  const StageEval& e = st_[k];
  const bool last_copy = S_.copy && k == S_.N - 1;
  const int rows = nxa + (last_copy ? nu : 0);  // x_{k+1}, T, and v = u_{N-1} on the last
  const double hk = S_.Step(it_, k);
  if (k == 0) {  // no x_0 but its free components (and T), which lead the stage's "controls"
    const int nw = S_.nw();
    stage0_.resize(nw + nT + S_.nuf());
    for (int i = 0; i < nw; ++i) stage0_[i] = S_.free0[i];
    if (nT > 0) stage0_[nw] = nx;
    for (int j = 0; j < S_.nuf(); ++j) stage0_[nw + nT + j] = nxa + S_.ufree[j];
    q->Q = H(stage0_, stage0_);
    q->q = g(stage0_);
    q->A.setZero(rows, 0);
    q->B.setZero(rows, nw + nT + S_.nuf());
    for (int i = 0; i < nw; ++i) {
      q->B.col(i).head(nx) = hk * e.fx.col(S_.free0[i]);
      q->B(S_.free0[i], i) += 1.0;
    }
    if (nT > 0) {
      q->B.col(nw).head(nx) = S_.h[0] / S_.duration * e.f;
      q->B(nx, nw) = 1.0;
    }
    for (int i = 0; i < S_.ncw(); ++i) q->B(nx + nT + i, i) = 1.0;  // w carried from here on
    for (int j = 0; j < S_.nuf(); ++j) {
      q->B.col(nw + nT + j).head(nx) = hk * e.fu.col(S_.ufree[j]);
      if (last_copy) q->B(nxa + S_.ufree[j], nw + nT + j) = 1.0;  // v = u_{N-1}
    }
    return last_copy;
  }
  if (S_.has_fixed_controls()) {  // (x, carried, free u)
    stagek_.resize(nxa + S_.nuf());
    for (int i = 0; i < nxa; ++i) stagek_[i] = i;
    for (int j = 0; j < S_.nuf(); ++j) stagek_[nxa + j] = nxa + S_.ufree[j];
    q->Q = H(stagek_, stagek_);
    q->q = g(stagek_);
  } else {
    q->Q = H;
    q->q = g;
  }
  q->A.setZero(rows, nxa);
  q->A.topLeftCorner(nx, nx) = hk * e.fx;
  q->A.topLeftCorner(nx, nx).diagonal().array() += 1.0;
  for (int j = nx; j < nxa; ++j) q->A(j, j) = 1.0;                  // T_{k+1} = T_k, w_{k+1} = w_k
  if (nT > 0) q->A.col(nx).head(nx) = S_.h[k] / S_.duration * e.f;  // d x_{k+1} / dT
  q->B.setZero(rows, S_.nuf());
  for (int j = 0; j < S_.nuf(); ++j) {
    q->B.col(j).head(nx) = hk * e.fu.col(S_.ufree[j]);
    if (last_copy) q->B(nxa + S_.ufree[j], j) = 1.0;  // v = u_{N-1}
  }
  return last_copy;
}

bool RiccatiInteriorPoint::TrapezoidQp(
    double mu, const Residuals& r, bool feasibility, bool relaxed, std::string* failure) {
  const int N = S_.N, nx = S_.nx, nu = S_.nu, nT = S_.nT();
  const double rate = S_.Rate(it_);
  node_H_.resize(N + 1);
  node_g_.resize(N + 1);
  for (int k = 0; k <= N; ++k) {
    // Node k's (x, u[, T]) block: T's row is the Lagrangian's d/dT in (x, u) (L and the
    // dynamics are linear in T: no T-T entry), its gradient entry sigma dJ_k/dT.
    Mat& H = node_H_[k];
    Vec& g = node_g_[k];
    const StageEval& e = st_[k];
    H.setZero(nx + nu + nT, nx + nu + nT);
    g.setZero(nx + nu + nT);
    if (feasibility) {
      H.topLeftCorner(nx + nu, nx + nu).setIdentity();
    } else {
      H.topLeftCorner(nx + nu, nx + nu) = e.H;
      g.head(nx) = sigma_ * rate * S_.wt[k] * e.Lx;
      g.segment(nx, nu) = sigma_ * rate * S_.wt[k] * e.Lu;
      if (k == 0 && S_.initial_cost) {
        H.topLeftCorner(nx, nx) += te_.H0;
        g.head(nx) += sigma_ * te_.grad0;
      }
      if (k == N) {
        H.topLeftCorner(nx, nx) += te_.H;
        g.head(nx) += sigma_ * te_.grad;
      }
      if (nT > 0) {
        H.row(nx + nu).head(nx + nu) = e.HT.transpose();
        H.col(nx + nu).head(nx + nu) = e.HT;
        g[nx + nu] = sigma_ * e.gT;
      }
    }
    if (it_.s[k].size() > 0) CondenseInequalities(k, mu, r.ineq[k], nx + nu, &H, &g);
    AddBoundTerms(k, mu, &H, &g);
  }
  // T is a variable once, of stage 0: its barrier terms (and the restoration's identity) there.
  double hTT = feasibility ? 1.0 : 0.0, gT = 0.0;
  TimeBoundTerms(mu, &hTT, &gT);
  if (!TrapezoidStagesFromNodes(&r.defects, hTT, gT, !feasibility, failure)) return false;
  for (int j = 1; relaxed && j <= N; ++j) RelaxDefects(&qp_.stages[j]);
  qp_.c = r.psi;
  SlackTerms(mu, feasibility ? 1.0 : 0.0, true);
  return true;
}

bool RiccatiInteriorPoint::TrapezoidStagesFromNodes(
    const Mat* defects, double hTT, double gT, bool boundary_hessian, std::string* failure) {
  const int N = S_.N, nx = S_.nx, nu = S_.nu, nf = S_.nuf(), nw = S_.nw(), nT = S_.nT();
  // xi = (x, free u, T, w): w the carried copies of x_0's free components (boundary rows).
  const int nxi0 = nx + nf + nT, ncw = S_.ncw(), nxi = nxi0 + ncw;
  trap_sel_.resize(nxi0);
  for (int i = 0; i < nx; ++i) trap_sel_[i] = i;
  for (int j = 0; j < nf; ++j) trap_sel_[nx + j] = nx + S_.ufree[j];
  if (nT > 0) trap_sel_[nx + nf] = nx + nu;
  qp_.stages.resize(N + 1);
  trap_m_.resize(N);
  RiccatiStage& q0 = qp_.stages[0];  // (w, u_0, T) -> xi_1 = (x_0, u_0, T, w)
  q0.Q.setZero(nw + nf + nT, nw + nf + nT);
  q0.q.setZero(nw + nf + nT);
  q0.A.setZero(nxi, 0);
  q0.B.setZero(nxi, nw + nf + nT);
  for (int i = 0; i < nw; ++i) q0.B(S_.free0[i], i) = 1.0;
  for (int i = 0; i < ncw; ++i) q0.B(nxi0 + i, i) = 1.0;
  for (int j = 0; j < nf; ++j) q0.B(nx + j, nw + j) = 1.0;
  if (nT > 0) {
    q0.B(nx + nf, nw + nf) = 1.0;
    q0.Q(nw + nf, nw + nf) = hTT;
    q0.q[nw + nf] = gT;
  }
  q0.b.setZero(nxi);
  const double rate = S_.Rate(it_);
  // Scratch sized once per call; the solves write into it (no temporaries per interval).
  Mat& M = trap_scratch_m_;
  Mat& rhs = trap_scratch_rhs_;
  Mat& solved = trap_scratch_solved_;
  Vec& defect = trap_scratch_defect_;
  M.resize(nx, nx);
  rhs.resize(nx, nx + 2 * nf + nT);
  solved.resize(nx, nx + 2 * nf + nT);
  defect.resize(nx);
  for (int k = 0; k < N; ++k) {
    RiccatiStage& q = qp_.stages[k + 1];
    const StageEval& a = st_[k];
    const StageEval& c = st_[k + 1];
    const double hh = 0.5 * rate * S_.h[k];
    q.Q.setZero(nxi + nf, nxi + nf);
    q.Q.topLeftCorner(nxi0, nxi0) = node_H_[k](trap_sel_, trap_sel_);
    q.q.setZero(nxi + nf);
    q.q.head(nxi0) = node_g_[k](trap_sel_);
    M = -hh * c.fx;
    M.diagonal().array() += 1.0;
    trap_m_[k].compute(M);
    // 1 / ||M^-1||_1 (Eigen's rcond is relative, 1 / (||M|| ||M^-1||): 1 for any 1 x 1 M, and
    // ~1 for M ~ eps I); M = I + O(h) has the scale 1, so the absolute measure is the one that
    // says how much the solve amplifies (found in review).
    const double m_norm = M.cwiseAbs().colwise().sum().maxCoeff();
    if (!(trap_m_[k].rcond() * m_norm > 1e-12)) {  // (NaN too)
      if (failure != nullptr) {
        *failure = "I - r h/2 f_x is singular at node " + std::to_string(k + 1) +
                   " (the trapezoid's defect cannot be solved for x_{k+1} there)";
      }
      return false;
    }
    // [I + h/2 f_x,k, h/2 f_u,k, (dT: h / (2 duration) (f_k + f_k+1)), h/2 f_u,k+1] (free u),
    // then M_k^-1 times it.
    rhs.leftCols(nx) = hh * a.fx;
    rhs.leftCols(nx).diagonal().array() += 1.0;
    for (int j = 0; j < nf; ++j) {
      rhs.col(nx + j) = hh * a.fu.col(S_.ufree[j]);
      rhs.col(nxi0 + j) = hh * c.fu.col(S_.ufree[j]);
    }
    if (nT > 0) rhs.col(nx + nf) = 0.5 * S_.h[k] / S_.duration * (a.f + c.f);
    solved.noalias() = trap_m_[k].solve(rhs);
    q.A.setZero(nxi, nxi);
    q.A.topLeftCorner(nx, nxi0) = solved.leftCols(nxi0);
    if (nT > 0) q.A(nx + nf, nx + nf) = 1.0;                      // T_{k+1} = T_k
    for (int i = 0; i < ncw; ++i) q.A(nxi0 + i, nxi0 + i) = 1.0;  // w_{k+1} = w_k
    q.B.setZero(nxi, nf);
    q.B.topRows(nx) = solved.rightCols(nf);
    q.B.block(nx, 0, nf, nf).setIdentity();
    q.b.setZero(nxi);
    if (defects != nullptr) {
      defect.noalias() = trap_m_[k].solve(defects->col(k));
      q.b.head(nx) = -defect;
    }
  }
  qp_.QN.setZero(nxi, nxi);
  qp_.QN.topLeftCorner(nxi0, nxi0) = node_H_[N](trap_sel_, trap_sel_);
  qp_.qN.setZero(nxi);
  qp_.qN.head(nxi0) = node_g_[N](trap_sel_);
  if (boundary_hessian) AddBoundaryHessian(&qp_.QN, nxi0);
  // The terminal rows: psi on x_N; b on x_N and, through the carried w, on x_0's free part.
  qp_.C.setZero(S_.nterm(), nxi);
  if (S_.npsi > 0) qp_.C.topLeftCorner(S_.npsi, nx) = te_.psix;
  if (S_.nb > 0) {
    qp_.C.block(S_.npsi, 0, S_.nb, nx) = te_.bxN;
    for (int i = 0; i < ncw; ++i) qp_.C.col(nxi0 + i).tail(S_.nb) = te_.bx0.col(S_.free0[i]);
  }
  qp_.x0.resize(0);
  // As Euler's: the first stage is solved jointly with the terminal rows where boundary rows
  // link x(t0)'s free components.
  qp_.joint_first_stage = S_.nb > 0;
  return true;
}

void RiccatiInteriorPoint::TrapezoidPrimalDual(Mat* dX, Mat* dU, Mat* dT, Mat* lam) const {
  const int N = S_.N, nx = S_.nx;
  for (int k = 0; k <= N; ++k) {
    dX->col(k) = sol_.x[k + 1].head(nx);
    ScatterControls(sol_.x[k + 1].head(nx + S_.nuf()), dU->col(k));
  }
  dT->resize(S_.nT(), S_.nT());
  if (S_.free_time) (*dT)(0, 0) = sol_.x[1][nx + S_.nuf()];
  for (int k = 0; k < N; ++k) {
    lam->col(k) = trap_m_[k].transpose().solve(sol_.lambda[k + 1].head(nx));
  }
}

bool RiccatiInteriorPoint::TrapezoidLeastSquaresQp() {
  const int N = S_.N, nx = S_.nx, nu = S_.nu, nT = S_.nT();
  const double rate = S_.Rate(it_);
  node_H_.resize(N + 1);
  node_g_.resize(N + 1);
  for (int k = 0; k <= N; ++k) {
    const StageEval& e = st_[k];
    Mat& H = node_H_[k];
    Vec& g = node_g_[k];
    H.setZero(nx + nu + nT, nx + nu + nT);
    H.topLeftCorner(nx + nu, nx + nu).setIdentity();
    g.setZero(nx + nu + nT);
    g.head(nx) = sigma_ * rate * S_.wt[k] * e.Lx;
    g.segment(nx, nu) = sigma_ * rate * S_.wt[k] * e.Lu - it_.zl.col(k) + it_.zu.col(k);
    if (S_.has_state_multipliers()) g.head(nx) += it_.zxu.col(k) - it_.zxl.col(k);
    if (k == 0 && S_.initial_cost) g.head(nx) += sigma_ * te_.grad0;
    if (k == N) g.head(nx) += sigma_ * te_.grad;
    if (nT > 0) g[nx + nu] = sigma_ * e.gT;
    if (S_.ni(k) > 0) {
      Mat J(S_.ni(k), nx + nu);
      J << e.cx, e.cu;
      H.topLeftCorner(nx + nu, nx + nu).noalias() += J.transpose() * J;
      g.head(nx + nu).noalias() += J.transpose() * it_.v[k];
    }
  }
  // The identity on T once (the NLP's one variable), at stage 0, with its bound multipliers.
  const double gT = S_.free_time ? it_.zTu(0, 0) - it_.zTl(0, 0) : 0.0;
  if (!TrapezoidStagesFromNodes(nullptr, 1.0, gT, false, nullptr)) return false;
  qp_.c.setZero(S_.nterm());
  SlackTerms(mu_, 1.0, false);
  return true;
}

void RiccatiInteriorPoint::ScatterControls(const Vec& stage_controls, Eigen::Ref<Vec> du) const {
  du.setZero();
  const auto free = stage_controls.tail(S_.nuf());
  for (int j = 0; j < S_.nuf(); ++j) du[S_.ufree[j]] = free[j];
}

void RiccatiInteriorPoint::WithCarried(
    const Mat& H, const Vec& g, const Vec* HT, double hTT, double gT, Mat* Ha, Vec* ga) const {
  const int n = static_cast<int>(H.rows()), nx = S_.nx, rest = n - nx, np = S_.np();
  Ha->setZero(n + np, n + np);
  ga->setZero(n + np);
  Ha->topLeftCorner(nx, nx) = H.topLeftCorner(nx, nx);
  Ha->topRightCorner(nx, rest) = H.topRightCorner(nx, rest);
  Ha->bottomLeftCorner(rest, nx) = H.bottomLeftCorner(rest, nx);
  Ha->bottomRightCorner(rest, rest) = H.bottomRightCorner(rest, rest);
  ga->head(nx) = g.head(nx);
  ga->tail(rest) = g.tail(rest);
  if (!S_.free_time) return;  // the carried copies of x_0's components: empty rows
  if (HT != nullptr) {
    Ha->col(nx).head(nx) = HT->head(nx);
    Ha->col(nx).tail(rest) = HT->tail(rest);
    Ha->row(nx) = Ha->col(nx).transpose();
  }
  (*Ha)(nx, nx) = hTT;
  (*ga)[nx] = gT;
}

void RiccatiInteriorPoint::TerminalRows(Mat* C) const {
  const int nx = S_.nx, nT = S_.nT();
  const int cols = nx + S_.np() + (S_.copy ? S_.nu : 0);  // (x_N, T, w, v)
  C->setZero(S_.nterm(), cols);
  if (S_.npsi > 0) C->topLeftCorner(S_.npsi, nx) = te_.psix;
  if (S_.nb == 0) return;
  C->block(S_.npsi, 0, S_.nb, nx) = te_.bxN;
  for (int i = 0; i < S_.ncw(); ++i) {
    C->col(nx + nT + i).tail(S_.nb) = te_.bx0.col(S_.free0[i]);
  }
}

void RiccatiInteriorPoint::AddBoundaryHessian(Mat* QN, int w0) const {
  if (S_.nb == 0) return;
  const int nx = S_.nx;
  const Mat& Hb = te_.Hb;  // order (x_0, x_N)
  QN->topLeftCorner(nx, nx) += Hb.bottomRightCorner(nx, nx);
  for (int i = 0; i < S_.ncw(); ++i) {
    const int a = S_.free0[i];
    for (int r = 0; r < nx; ++r) {
      (*QN)(r, w0 + i) += Hb(nx + r, a);
      (*QN)(w0 + i, r) += Hb(a, nx + r);
    }
    for (int j = 0; j < S_.ncw(); ++j) (*QN)(w0 + i, w0 + j) += Hb(a, S_.free0[j]);
  }
}

void RiccatiInteriorPoint::TimeBoundTerms(double mu, double* hTT, double* gT) const {
  if (!S_.free_time) return;
  const double T = it_.T(0, 0), lo = S_.Tlb[0], hi = S_.Tub[0];
  if (RipFinite(lo)) {
    *hTT += it_.zTl(0, 0) / (T - lo);
    *gT -= mu / (T - lo);
    if (!RipFinite(hi)) *gT += kKappaD * mu;
  }
  if (RipFinite(hi)) {
    *hTT += it_.zTu(0, 0) / (hi - T);
    *gT += mu / (hi - T);
    if (!RipFinite(lo)) *gT -= kKappaD * mu;
  }
}

void RiccatiInteriorPoint::SlackTerms(double mu, double base, bool barrier) {
  if (S_.nbi() == 0) {
    qp_.slack_hessian.resize(0);
    qp_.slack_gradient.resize(0);
    return;
  }
  qp_.slack_hessian.setZero(S_.nterm());
  qp_.slack_gradient.setZero(S_.nterm());
  for (int i = 0; i < S_.nbi(); ++i) {
    const int row = S_.npsi + S_.bineq[i];
    const double sb = it_.SB(i, 0), lo = S_.sblo[i], hi = S_.sbhi[i];
    double h = base, g = 0.0;
    if (!barrier) {
      g = it_.zSu(i, 0) - it_.zSl(i, 0);
    } else {
      if (RipFinite(lo)) {
        h += it_.zSl(i, 0) / (sb - lo);
        g -= mu / (sb - lo);
        if (!RipFinite(hi)) g += kKappaD * mu;
      }
      if (RipFinite(hi)) {
        h += it_.zSu(i, 0) / (hi - sb);
        g += mu / (hi - sb);
        if (!RipFinite(lo)) g -= kKappaD * mu;
      }
    }
    qp_.slack_hessian[row] = h;
    qp_.slack_gradient[row] = g;
  }
}

void RiccatiInteriorPoint::RelaxDefects(RiccatiStage* q) const {
  const int nx = S_.nx, ns = static_cast<int>(q->A.cols()), nv = static_cast<int>(q->B.cols());
  const int n = ns + nv, rows = static_cast<int>(q->B.rows());
  Mat Q = Mat::Zero(n + nx, n + nx);
  Q.topLeftCorner(ns, ns) = q->Q.topLeftCorner(ns, ns);
  Q.topRightCorner(ns, nv) = q->Q.topRightCorner(ns, nv);
  Q.bottomLeftCorner(nv, ns) = q->Q.bottomLeftCorner(nv, ns);
  Q.bottomRightCorner(nv, nv) = q->Q.bottomRightCorner(nv, nv);
  Q.block(ns, ns, nx, nx).diagonal().setConstant(restoration_rho_);
  Vec g = Vec::Zero(n + nx);
  g.head(ns) = q->q.head(ns);
  g.tail(nv) = q->q.tail(nv);
  Mat B = Mat::Zero(rows, nx + nv);
  B.topLeftCorner(nx, nx).setIdentity();
  B.rightCols(nv) = q->B;
  q->Q.swap(Q);
  q->q.swap(g);
  q->B.swap(B);
}

void RiccatiInteriorPoint::TakePrimal(Iterate* trial) {
  it_.X.swap(trial->X);
  it_.U.swap(trial->U);
  it_.T.swap(trial->T);
  it_.SB.swap(trial->SB);
  it_.V.swap(trial->V);
  it_.s.swap(trial->s);
}

void RiccatiInteriorPoint::LeastSquaresMultipliers() {
  const int N = S_.N, nx = S_.nx, nu = S_.nu;
  const double cpu0 = CpuSeconds();
  if (S_.trapezoid) {
    ++factorizations_;
    if (TrapezoidLeastSquaresQp() &&
        riccati_.Solve(qp_, 0.0, 0.0, &sol_) == RiccatiOutcome::kSolved) {
      Iterate trial = it_;
      Mat dX(nx, N + 1), dU(nu, N + 1), dT;
      TrapezoidPrimalDual(&dX, &dU, &dT, &trial.lam);
      double largest = trial.lam.lpNorm<Eigen::Infinity>();
      trial.nu = sol_.nu;
      if (S_.nterm() > 0) largest = std::max(largest, trial.nu.lpNorm<Eigen::Infinity>());
      for (int k = 0; k <= N; ++k) {
        if (S_.ni(k) == 0) continue;
        trial.y[k] = st_[k].cx * dX.col(k) + st_[k].cu * dU.col(k) + it_.v[k];
        largest = std::max(largest, trial.y[k].lpNorm<Eigen::Infinity>());
      }
      if (largest <= 1000.0) it_ = std::move(trial);
    }
    kkt_cpu_ += CpuSeconds() - cpu0;
    return;
  }
  qp_.stages.resize(N);
  for (int k = 0; k < N; ++k) {
    const StageEval& e = st_[k];
    RiccatiStage& q = qp_.stages[k];
    Mat H = Mat::Identity(nx + nu, nx + nu);
    Vec g(nx + nu);
    const double hk = S_.Step(it_, k);
    g.head(nx) = sigma_ * hk * e.Lx;
    g.tail(nu) = sigma_ * hk * e.Lu - it_.zl.col(k) + it_.zu.col(k);
    if (S_.has_state_multipliers()) g.head(nx) += it_.zxu.col(k) - it_.zxl.col(k);
    if (k == 0 && S_.initial_cost) g.head(nx) += sigma_ * te_.grad0;
    Mat J(S_.ni(k), nx + nu);
    if (S_.ni(k) > 0) {
      J << e.cx, e.cu;
      H.noalias() += J.transpose() * J;
      g.noalias() += J.transpose() * it_.v[k];
    }
    if (S_.np() > 0) {  // the identity on T once (the NLP's one variable), at stage 0
      double gT = sigma_ * e.gT;
      if (k == 0 && S_.free_time) gT += it_.zTu(0, 0) - it_.zTl(0, 0);
      WithCarried(H, g, nullptr, k == 0 && S_.free_time ? 1.0 : 0.0, gT, &Ha_, &ga_);
      H.swap(Ha_);
      g.swap(ga_);
    }
    StageBlocks(k, H, g, &q);
    q.b.setZero(q.B.rows());
  }
  const int nxN = nx + (S_.copy ? nu : 0);
  // The identity on x_N only: the copy of u_{N-1} is no variable of the NLP, and without its own
  // identity block eliminating it gives the NLP's least-squares problem exactly.
  qp_.QN.setZero(nxN, nxN);
  qp_.QN.topLeftCorner(nx, nx).setIdentity();
  qp_.qN.setZero(nxN);
  qp_.qN.head(nx) = sigma_ * te_.grad;
  if (S_.has_state_bounds()) qp_.qN.head(nx) += it_.zxu.col(N) - it_.zxl.col(N);
  Mat JN(S_.ni(N), nxN);
  if (S_.copy) {
    JN << st_[N].cx, st_[N].cu;
    qp_.QN.noalias() += JN.transpose() * JN;
    qp_.qN.noalias() += JN.transpose() * it_.v[N];
  }
  if (S_.np() > 0) {
    WithCarried(qp_.QN, qp_.qN, nullptr, 0.0, 0.0, &Ha_, &ga_);
    qp_.QN.swap(Ha_);
    qp_.qN.swap(ga_);
  }
  TerminalRows(&qp_.C);
  qp_.c.setZero(S_.nterm());
  qp_.x0.resize(0);
  SlackTerms(mu_, 1.0, false);
  qp_.joint_first_stage = S_.nb > 0;  // as BuildAndSolve's
  ++factorizations_;
  if (riccati_.Solve(qp_, 0.0, 0.0, &sol_) == RiccatiOutcome::kSolved) {
    Iterate trial = it_;
    double largest = 0.0;
    for (int k = 0; k < N; ++k) {
      trial.lam.col(k) = sol_.lambda[k].head(nx);
      largest = std::max(largest, trial.lam.col(k).lpNorm<Eigen::Infinity>());
    }
    if (S_.copy) trial.lamV = sol_.lambda[N - 1].tail(nu);
    trial.nu = sol_.nu;
    if (S_.nterm() > 0) largest = std::max(largest, trial.nu.lpNorm<Eigen::Infinity>());
    for (int k = 0; k <= N; ++k) {
      if (S_.ni(k) == 0) continue;
      const StageEval& e = st_[k];
      Vec du(nu);
      if (k < N) ScatterControls(sol_.u[k], du);
      if (k == N) du = sol_.x[N].tail(nu);
      Vec dx = Vec::Zero(nx);
      if (k > 0) dx = sol_.x[k].head(nx);
      for (int i = 0; k == 0 && i < S_.nw(); ++i) dx[S_.free0[i]] = sol_.u[0][i];
      trial.y[k] = e.cx * dx + e.cu * du + it_.v[k];
      largest = std::max(largest, trial.y[k].lpNorm<Eigen::Infinity>());
    }
    if (largest <= 1000.0) it_ = std::move(trial);
  }
  kkt_cpu_ += CpuSeconds() - cpu0;
}

NlpSolution RiccatiInteriorPoint::Run(const Vec& z0) {
  const int N = S_.N, nx = S_.nx, nu = S_.nu;
  S_.ToIterate(z0, &it_);
  // x_0's fixed components are fixed by the NLP's bounds, which the method never leaves: take
  // them from the problem, not from the starting point (an initial guess's states need not start
  // at x0). Its free components start where the NLP's starting point has them.
  {
    Vec x0 = S_.nlp.ocp().x0();
    for (int i : S_.free0) x0[i] = it_.X(i, 0);
    it_.X.col(0) = x0;
  }
  boxes_.clear();
  const auto& o = S_.original;
  boxes_.push_back({BoxKind::kControl, &S_.lb, &S_.ub, 0, S_.nctl(), nx, &o.lb, &o.ub});
  if (S_.has_initial_bounds()) {
    boxes_.push_back({BoxKind::kState, &S_.x0lb, &S_.x0ub, 0, 1, 0, &o.x0lb, &o.x0ub});
  }
  if (S_.free_time) boxes_.push_back({BoxKind::kTime, &S_.Tlb, &S_.Tub, 0, 1, 0, &o.Tlb, &o.Tub});
  if (S_.has_state_bounds()) {
    boxes_.push_back({BoxKind::kState, &S_.xlb, &S_.xub, 1, N + 1, 0, &o.xlb, &o.xub});
  }
  it_.SB.resize(S_.nbi(), 1);
  if (S_.nbi() > 0) {
    boxes_.push_back({BoxKind::kSlack, &S_.sblo, &S_.sbhi, 0, 1, 0, &o.sblo, &o.sbhi});
  }
  // Controls and states pushed into their bounds (Ipopt's bound_push, bound_frac); then the
  // boundary inequalities' slacks set to b(x(t0), x(tf)) at the pushed point and pushed into
  // theirs, as Ipopt starts its slacks at d(x_0).
  const auto push = [&](bool slacks) {
    ForEachBounded([&](const Box& b, int k, int j, double lo, double hi) {
      if ((b.kind == BoxKind::kSlack) != slacks) return;
      double& x = Value(it_, b)(j, k);
      const double width = RipFinite(lo) && RipFinite(hi) ? hi - lo : kRipInf;
      if (RipFinite(lo)) {
        x = std::max(
            x, lo + std::min(o_.bound_push * std::max(1.0, std::abs(lo)), o_.bound_frac * width));
      }
      if (RipFinite(hi)) {
        x = std::min(
            x, hi - std::min(o_.bound_push * std::max(1.0, std::abs(hi)), o_.bound_frac * width));
      }
    });
  };
  push(false);
  if (S_.nbi() > 0) {
    Vec b(S_.nb);
    S_.ocp.BoundaryConstraints(it_.X.col(0), it_.X.col(N), b);
    for (int i = 0; i < S_.nbi(); ++i) it_.SB(i, 0) = b[S_.bineq[i]];
    push(true);
  }
  if (S_.copy) it_.V = it_.U.col(N - 1);
  double cpu0 = CpuSeconds();
  S_.EvalValues(it_, &vals_);
  callback_cpu_ += CpuSeconds() - cpu0;
  if (!vals_.ok) {
    return Finish(SolveStatus::kNumericalFailure,
                  "Invalid_Number_Detected",
                  "a value at the starting point is not finite");
  }
  it_.s.resize(N + 1);
  it_.y.resize(N + 1);
  it_.v.resize(N + 1);
  for (int k = 0; k <= N; ++k) {
    it_.s[k] = (-vals_.c[k]).cwiseMax(o_.bound_push);
    it_.y[k] = Vec::Zero(S_.ni(k));
    it_.v[k] = Vec::Ones(S_.ni(k));
  }
  it_.zl.setZero(nu, S_.nctl());
  it_.zu.setZero(nu, S_.nctl());
  it_.zxl.setZero(S_.has_state_multipliers() ? nx : 0, S_.has_state_multipliers() ? N + 1 : 0);
  it_.zxu.setZero(it_.zxl.rows(), it_.zxl.cols());
  it_.zTl.setZero(S_.nT(), S_.nT());
  it_.zTu.setZero(S_.nT(), S_.nT());
  it_.zSl.setZero(S_.nbi(), 1);
  it_.zSu.setZero(S_.nbi(), 1);
  ForEachBounded([&](const Box& b, int k, int j, double lo, double hi) {
    if (RipFinite(lo)) Zl(it_, b)(j, k) = 1.0;
    if (RipFinite(hi)) Zu(it_, b)(j, k) = 1.0;
  });
  it_.lam.setZero(nx, N);
  it_.lamV.setZero(S_.copy ? nu : 0);
  it_.nu.setZero(S_.nterm());

  cpu0 = CpuSeconds();
  bool ok = S_.EvalDerivatives(it_, &st_, &te_);
  callback_cpu_ += CpuSeconds() - cpu0;
  if (!ok) {
    return Finish(SolveStatus::kNumericalFailure,
                  "Invalid_Number_Detected",
                  "a derivative at the starting point is not finite");
  }
  // Objective scaling (Ipopt's gradient-based rule, on the objective only).
  sigma_ = 1.0;
  if (o_.nlp_scaling_method == "gradient-based") {
    double gmax = 0.0;
    for (int k = 0; k < S_.nctl(); ++k) {
      const double hk = S_.NodeWeight(it_, k);
      if (k > 0 && k < N) gmax = std::max(gmax, hk * st_[k].Lx.lpNorm<Eigen::Infinity>());
      if (k == N) {  // the trapezoid's x_N: its running and terminal parts are one entry
        gmax = std::max(gmax, (hk * st_[N].Lx + te_.grad).lpNorm<Eigen::Infinity>());
      }
      for (int i = 0; k == 0 && i < S_.nw(); ++i) {
        const int j = S_.free0[i];
        const double g0 = hk * st_[0].Lx[j] + (S_.initial_cost ? te_.grad0[j] : 0.0);
        gmax = std::max(gmax, std::abs(g0));
      }
      for (int j : S_.ufree) gmax = std::max(gmax, hk * std::abs(st_[k].Lu[j]));
    }
    if (S_.free_time) {  // dJ/dT = sum_k h_k L_k / duration (trapezoid: wt_k)
      double gT = 0.0;
      for (int k = 0; k < S_.nctl(); ++k) gT += st_[k].gT;
      gmax = std::max(gmax, std::abs(gT));
    }
    if (!S_.trapezoid) gmax = std::max(gmax, te_.grad.lpNorm<Eigen::Infinity>());
    if (gmax > o_.nlp_scaling_max_gradient) sigma_ = o_.nlp_scaling_max_gradient / gmax;
  }
  LeastSquaresMultipliers();
  mu_ = o_.mu_init;
  double tau = std::max(0.99, 1.0 - mu_);
  const double theta0 = Theta(vals_, it_.s);
  const double theta_max = 1e4 * std::max(1.0, theta0);
  const double theta_min = 1e-4 * std::max(1.0, theta0);
  std::vector<std::pair<double, double>> filter;
  Direction d;
  Iterate trial;
  Values tv;  // a trial point's values

  for (;;) {
    cpu0 = CpuSeconds();
    ok = S_.EvalHessians(it_, sigma_, &st_, &te_);
    callback_cpu_ += CpuSeconds() - cpu0;
    if (!ok) {
      return Finish(SolveStatus::kNumericalFailure,
                    "Invalid_Number_Detected",
                    "a Hessian entry is not finite");
    }
    Measure(mu_);
    {
      IterationRecord rec;
      rec.iteration = iterations_;
      rec.J = vals_.f;
      rec.primal_inf = constr_viol_;
      rec.dual_inf = dual_inf_;
      rec.cpu_seconds = watch_.cpu();
      history_.push_back(rec);
      if (o_.print_level >= 1) {
        std::fprintf(stderr,
                     "riccati-ip %4d  f %+.10e  inf_pr %.2e  inf_du %.2e  mu %.1e  E0 %.2e  "
                     "alpha_pr %.2e  alpha_du %.2e %s\n",
                     iterations_,
                     vals_.f,
                     constr_viol_,
                     dual_inf_,
                     mu_,
                     E0_,
                     last_alpha_,
                     last_alpha_z_,
                     last_step_);
      }
    }
    if (E0_ <= o_.tol && dual_inf_ / sigma_ <= o_.dual_inf_tol &&
        constr_viol_ <= o_.constr_viol_tol && compl_ / sigma_ <= o_.compl_inf_tol) {
      return Finish(SolveStatus::kConverged, "Solve_Succeeded", "");
    }
    acceptable_count_ = CurrentIsAcceptable() ? acceptable_count_ + 1 : 0;
    if (o_.acceptable_iter > 0 && acceptable_count_ >= o_.acceptable_iter) {
      return Finish(SolveStatus::kAcceptable,
                    "Solved_To_Acceptable_Level",
                    std::to_string(acceptable_count_) +
                        " consecutive iterates at the acceptable level, not at tol");
    }
    if (iterations_ >= o_.max_iter) {
      return Finish(SolveStatus::kMaxIterations, "Maximum_Iterations_Exceeded", "");
    }
    if (watch_.cpu() >= o_.max_cpu_time) {
      return Finish(SolveStatus::kMaxTime, "Maximum_CpuTime_Exceeded", "");
    }
    // Monotone (Fiacco-McCormick) barrier update.
    // Ipopt's floor of the monotone mode: the level at which the barrier problem's own test
    // (E_mu <= kappa_eps mu) implies the overall one, min(tol, compl_inf_tol) / (kappa_eps + 1).
    const double mu_min = std::min(o_.tol, o_.compl_inf_tol) / (kKappaEps + 1.0);
    bool mu_changed = false;
    while (Emu_ <= kKappaEps * mu_ && mu_ > mu_min) {
      mu_ = std::max(mu_min, std::min(kKappaMu * mu_, std::pow(mu_, kThetaMu)));
      tau = std::max(0.99, 1.0 - mu_);
      Measure(mu_);
      mu_changed = true;
    }
    if (mu_changed) filter.clear();

    std::string failure;
    ResidualsAt(vals_, it_.s, &res_);
    if (!BuildAndSolve(mu_, res_, StepKind::kNewton, &d, &failure)) {
      return Finish(SolveStatus::kNumericalFailure, "Error_In_Step_Computation", failure);
    }
    double alpha_max = 1.0, alpha_z = 1.0;
    StepToBoundary(d, tau, &alpha_max, &alpha_z);
    // Directional derivative of the barrier objective.
    double gphi = 0.0;
    for (int k = 0; k < S_.nctl(); ++k) {
      const StageEval& e = st_[k];
      const double weight = S_.NodeWeight(it_, k);
      gphi += sigma_ * weight * (e.Lx.dot(d.dX.col(k)) + e.Lu.dot(d.dU.col(k)));
      if (S_.free_time) gphi += sigma_ * e.gT * d.dT(0, 0);
    }
    if (S_.initial_cost) gphi += sigma_ * te_.grad0.dot(d.dX.col(0));
    ForEachBounded([&](const Box& b, int k, int j, double lo, double hi) {
      const double x = Value(it_, b)(j, k), dx = Step(d, b)(j, k);
      if (RipFinite(lo)) gphi -= mu_ * dx / (x - lo);
      if (RipFinite(hi)) gphi += mu_ * dx / (hi - x);
      if (RipFinite(lo) != RipFinite(hi)) gphi += (RipFinite(lo) ? 1.0 : -1.0) * kKappaD * mu_ * dx;
    });
    gphi += sigma_ * te_.grad.dot(d.dX.col(N));
    for (int k = 0; k <= N; ++k) {
      if (it_.s[k].size() > 0) {
        gphi += mu_ * (kKappaD * d.ds[k].sum() - d.ds[k].cwiseQuotient(it_.s[k]).sum());
      }
    }
    LineSearchReference ref;
    ref.theta = Theta(vals_, it_.s);
    ref.phi = BarrierObjective(vals_, it_);
    ref.gphi = gphi;
    ref.theta_min = theta_min;
    ref.theta_max = theta_max;
    ref.filter = &filter;
    const double theta = ref.theta, phi = ref.phi;
    // A tiny step (Ipopt's tiny_step_tol): taken in full, no line search.
    double rel = (d.dX.col(0).array().abs() / (1.0 + it_.X.col(0).array().abs())).maxCoeff();
    if (S_.free_time) rel = std::max(rel, std::abs(d.dT(0, 0)) / (1.0 + std::abs(it_.T(0, 0))));
    for (int k = 0; k < N; ++k) {
      rel = std::max(
          rel, (d.dX.col(k + 1).array().abs() / (1.0 + it_.X.col(k + 1).array().abs())).maxCoeff());
    }
    for (int k = 0; k < S_.nctl(); ++k) {
      rel = std::max(rel,
                     (d.dU.col(k).array().abs() / (1.0 + it_.U.col(k).array().abs())).maxCoeff());
    }
    const bool tiny = rel < 10.0 * kRipEps && theta < 1e-4;

    double alpha = alpha_max;
    bool accepted = false, f_type = false, restored = false, soc = false;
    // A trial point's primal variables (the only part of it the line search reads), written
    // in place from it_ and the direction; swapped into it_ on acceptance.
    for (int backtracks = 0;; ++backtracks) {
      ++trials_;
      PrimalTrial(d, alpha, &trial);
      cpu0 = CpuSeconds();
      S_.EvalValues(trial, &tv);
      callback_cpu_ += CpuSeconds() - cpu0;
      if (tiny) {
        accepted = tv.ok;
        f_type = true;
        if (accepted) break;
      }
      accepted = Acceptable(ref, tv, trial, alpha, &f_type);
      if (accepted) break;
      if (backtracks == 0 && !tiny && o_.max_soc > 0 && tv.ok && Theta(tv, trial.s) >= theta &&
          SecondOrderCorrection(ref, alpha, tau, &d, &alpha, &trial, &tv, &f_type)) {
        StepToBoundary(d, tau, &alpha_max, &alpha_z);  // the corrected step's dual step size
        accepted = true;
        soc = true;
        break;
      }
      double alpha_min = kGammaTheta;
      if (gphi < 0.0) {
        alpha_min = std::min(kGammaTheta, kGammaPhi * theta / -gphi);
        if (theta <= theta_min) {
          alpha_min =
              std::min(alpha_min, kDeltaSwitch * std::pow(theta, kSTheta) / std::pow(-gphi, kSPhi));
        }
      }
      alpha_min *= kGammaAlpha;
      alpha *= 0.5;
      if (alpha < alpha_min || alpha < 1e-16) {
        if (CurrentIsAcceptable()) {
          return Finish(SolveStatus::kAcceptable,
                        "Solved_To_Acceptable_Level",
                        "the filter line search failed at an acceptable point");
        }
        std::string why, solver_status;
        if (!Restore(ref, tau, &filter, &why, &solver_status)) {
          if (solver_status == "Invalid_Number_Detected") {
            // The point's measures are not defined: say so rather than keep the last ones.
            E0_ = dual_inf_ = constr_viol_ = compl_ = std::numeric_limits<double>::quiet_NaN();
            rx_.resize(0, 0);
          } else {
            Measure(mu_);  // the reported point's measures, wherever the phase left it
          }
          return Finish(SolveStatus::kNumericalFailure, solver_status, why);
        }
        restored = true;
        break;
      }
    }
    if (restored) {  // it_ and its first derivatives are the restored point's
      last_step_ = "r";
      continue;
    }
    last_alpha_ = alpha;
    last_alpha_z_ = alpha_z;
    last_step_ = soc ? "s" : f_type ? "f" : "h";
    if (!f_type) filter.emplace_back((1.0 - kGammaTheta) * theta, phi - kGammaPhi * theta);

    // Accept: primal and equality multipliers with alpha, bound multipliers with alpha_z.
    TakePrimal(&trial);
    it_.lam += alpha * (d.lam - it_.lam);
    if (S_.copy) it_.lamV += alpha * (d.lamV - it_.lamV);
    if (S_.nterm() > 0) it_.nu += alpha * (d.nu - it_.nu);
    for (int k = 0; k <= N; ++k) {
      if (it_.s[k].size() == 0) continue;
      it_.y[k] += alpha * d.dy[k];
      it_.v[k] += alpha_z * d.dv[k];
    }
    it_.zl += alpha_z * d.dzl;
    it_.zu += alpha_z * d.dzu;
    if (S_.has_state_multipliers()) {
      it_.zxl += alpha_z * d.dzxl;
      it_.zxu += alpha_z * d.dzxu;
    }
    it_.zTl += alpha_z * d.dzTl;
    it_.zTu += alpha_z * d.dzTu;
    it_.zSl += alpha_z * d.dzSl;
    it_.zSu += alpha_z * d.dzSu;
    ClampBoundMultipliers();
    std::swap(vals_, tv);
    ++iterations_;
    cpu0 = CpuSeconds();
    ok = S_.EvalDerivatives(it_, &st_, &te_);
    callback_cpu_ += CpuSeconds() - cpu0;
    if (!ok) {
      return Finish(SolveStatus::kNumericalFailure,
                    "Invalid_Number_Detected",
                    "a derivative at an iterate is not finite");
    }
  }
}

NlpSolution RiccatiInteriorPoint::Finish(SolveStatus status,
                                         const std::string& solver_status,
                                         std::string message) {
  const int N = S_.N, nx = S_.nx, nu = S_.nu, nc = S_.nc;
  NlpSolution out;
  out.status = status;
  out.solver_status = solver_status;
  out.message = std::move(message);
  out.iterations = iterations_;
  out.history = std::move(history_);
  if (it_.X.size() == 0) return out;
  {  // the last iterate projected onto the problem's own bounds (Ipopt's honor_original_bounds)
    Iterate projected;
    projected.X = it_.X;
    projected.U = it_.U;
    projected.T = it_.T;
    projected.SB = it_.SB;  // (not an NLP variable)
    for (const Box& b : boxes_) {
      for (int k = b.first; k < b.last; ++k) {
        for (int j = 0; j < b.lb->size(); ++j) {
          double& x = Value(projected, b)(j, k);
          x = std::clamp(x, (*b.original_lb)[j], (*b.original_ub)[j]);
        }
      }
    }
    out.z = S_.ToNlp(projected);
  }
  // objective: the last iterate's, as Ipopt reports it (SolveTranscribed evaluates the NLP's
  // objective at the projected z for the records, for both solvers).
  out.has_iterate = true;
  out.objective = vals_.f;
  const double inv = 1.0 / sigma_;
  if (static_cast<int>(it_.s.size()) == N + 1 && it_.lam.cols() == N) {
    Vec lambda = Vec::Zero(S_.nlp.num_constraints());
    for (int k = 0; k < N; ++k) lambda.segment(S_.nlp.defect_row(k), nx) = inv * it_.lam.col(k);
    for (int k = 0; k <= N && nc > 0; ++k) {
      lambda.segment(S_.nlp.path_row_begin() + k * nc, nc) = inv * it_.y[k].head(nc);
    }
    for (int k = 0; k < S_.nctl(); ++k) {
      for (int b = 0; b < S_.nball; ++b) {
        lambda[S_.nlp.ball_row_begin() + k * S_.nball + b] = inv * it_.y[k][nc + b];
      }
    }
    if (S_.npsi > 0)
      lambda.segment(S_.nlp.terminal_row_begin(), S_.npsi) = inv * it_.nu.head(S_.npsi);
    if (S_.nb > 0) lambda.segment(S_.nlp.boundary_row_begin(), S_.nb) = inv * it_.nu.tail(S_.nb);
    out.lambda = lambda;
    const int n = S_.nlp.num_variables();
    out.z_lower = Vec::Zero(n);
    out.z_upper = Vec::Zero(n);
    for (int k = 0; k < S_.nctl(); ++k) {
      out.z_lower.segment(S_.control_off[k], nu) = inv * it_.zl.col(k);
      out.z_upper.segment(S_.control_off[k], nu) = inv * it_.zu.col(k);
      for (int j = 0; j < nu && S_.has_fixed_controls() && ru_.cols() == S_.nctl(); ++j) {
        if (std::isnan(S_.ufixed[j])) continue;  // a fixed one's: its stationarity
        out.z_lower[S_.control_off[k] + j] = std::max(0.0, inv * ru_(j, k));
        out.z_upper[S_.control_off[k] + j] = std::max(0.0, -inv * ru_(j, k));
      }
      if (S_.has_state_multipliers() && k < N) {
        out.z_lower.segment(S_.state_off[k + 1], nx) = inv * it_.zxl.col(k + 1);
        out.z_upper.segment(S_.state_off[k + 1], nx) = inv * it_.zxu.col(k + 1);
      }
    }
    if (rx_.cols() == N + 1) {  // a fixed x_0 component's bound multiplier: its stationarity
      const Vec r = inv * rx_.col(0);
      out.z_lower.segment(S_.state_off[0], nx) = r.cwiseMax(0.0);
      out.z_upper.segment(S_.state_off[0], nx) = (-r).cwiseMax(0.0);
    }
    if (S_.free_time) {
      out.z_lower[S_.time_index] = inv * it_.zTl(0, 0);
      out.z_upper[S_.time_index] = inv * it_.zTu(0, 0);
    }
    for (int i : S_.free0) {  // a free one's: its own
      out.z_lower[S_.state_off[0] + i] = S_.has_state_multipliers() ? inv * it_.zxl(i, 0) : 0.0;
      out.z_upper[S_.state_off[0] + i] = S_.has_state_multipliers() ? inv * it_.zxu(i, 0) : 0.0;
    }
  }
  out.stats["riccati_ip_iterations"] = iterations_;
  out.stats["riccati_ip_regularizations"] = regularizations_;
  out.stats["riccati_ip_factorizations"] = factorizations_;
  out.stats["riccati_ip_line_search_trials"] = trials_;
  out.stats["riccati_ip_refinement_steps"] = refinement_steps_;
  out.stats["riccati_ip_soc_trials"] = soc_trials_;
  out.stats["riccati_ip_soc_accepted"] = soc_accepted_;
  out.stats["riccati_ip_restoration_phases"] = restoration_phases_;
  out.stats["riccati_ip_restoration_iterations"] = restoration_iterations_;
  out.stats["riccati_ip_restoration_damped_steps"] = restoration_damped_;
  out.stats["riccati_ip_kkt_cpu_seconds"] = kkt_cpu_;
  out.stats["riccati_ip_callback_cpu_seconds"] = callback_cpu_;
  out.stats["riccati_ip_cpu_seconds"] = watch_.cpu();
  out.stats["riccati_ip_kkt_error"] = E0_;
  out.stats["riccati_ip_dual_inf"] = dual_inf_ * inv;
  out.stats["riccati_ip_constr_viol"] = constr_viol_;
  out.stats["riccati_ip_complementarity"] = compl_ * inv;
  out.stats["riccati_ip_mu"] = mu_;
  out.stats["riccati_ip_objective_scale"] = sigma_;
  return out;
}

NlpSolution NotApplicableSolution(const std::string& why) {
  NlpSolution out;
  out.status = SolveStatus::kNotApplicable;
  out.solver_status = "not_applicable";
  out.message = why;
  out.iterations = 0;
  return out;
}

}  // namespace

NlpSolution SolveEulerNlpWithRiccatiIp(const TranscribedNlp& nlp, const RiccatiIpOptions& options) {
  std::string why;
  const std::unique_ptr<EulerStages> stages = EulerStages::From(nlp, &why);
  if (!stages) return NotApplicableSolution(why);
  stages->Relax(options.bound_relax_factor);
  RiccatiInteriorPoint ip(*stages, options);
  NlpSolution out = ip.Run(nlp.StartingPoint());
  if (out.z.size() != nlp.num_variables()) out.z = nlp.StartingPoint();
  return out;
}

std::string RiccatiIpNotApplicable(const Ocp& ocp, const SolveRequest& request) {
  if (request.transcription.empty()) return "";
  const TranscriptionInfo& info = FindTranscription(request.transcription);  // throws if unknown
  if (info.name != "euler" && info.name != "trapezoid") {
    return "riccati-ip solves the euler and trapezoid transcriptions only in this version (not '" +
           info.name + "'); use ipopt for the others";
  }
  ProblemFeatures takes;      // x(t0)'s free components and T are stage-0 variables (T carried as
  takes.state_bounds = true;  // an augmented state); states have bounds
  takes.free_initial_state = true;
  takes.free_final_time = true;
  takes.boundary_constraints = true;  // equalities and inequalities (slacks)
  if (std::string why = UnsupportedFeature(ocp, "riccati-ip", takes); !why.empty()) return why;
  const TranscriptionOptions options = TranscriptionOptionsFor(request);
  if (!options.scaling.IsIdentity()) {
    return "riccati-ip works in the problem's units: the transcription options objective_scale, "
           "state_scale and control_scale must be left at 1";
  }
  if (options.mesh.enabled()) return "riccati-ip does not run mesh refinement";
  for (int i = 0; i < ocp.num_boundary(); ++i) {
    // A row bounded on neither side constrains nothing; its slack would be free, which the
    // elimination in the Riccati solve does not take (D = 1 / (Sigma + delta_w) needs Sigma > 0).
    if (ocp.boundary_bounds().lower[i] <= -kRipInfBound &&
        ocp.boundary_bounds().upper[i] >= kRipInfBound) {
      return "problem '" + ocp.name() + "' has a boundary row bounded on neither side (row " +
             std::to_string(i) +
             " of b(x(t0), x(tf))), which riccati-ip does not take: drop the row, or use ipopt";
    }
  }
  return "";
}

SolveResult RiccatiIpSolver::Solve(const Ocp& ocp, const SolveRequest& request) const {
  const RiccatiIpOptions options = RiccatiIpOptions::Apply(request.options, RiccatiIpOptions());
  const std::string why = RiccatiIpNotApplicable(ocp, request);
  if (!why.empty()) return NotApplicableResult(name(), why);
  return SolveTranscribed(
      name(), ocp, request, [&](const TranscribedNlp& nlp, const Vec&, const NlpMultipliers&) {
        return SolveEulerNlpWithRiccatiIp(nlp, options);
      });
}

bool EulerStageLagrangian(const TranscribedNlp& nlp,
                          const Vec& z,
                          const Vec& lambda,
                          double* value,
                          Vec* gradient,
                          Mat* hessian) {
  std::string why;
  const std::unique_ptr<EulerStages> S = EulerStages::From(nlp, &why);
  if (!S || z.size() != nlp.num_variables() || lambda.size() != nlp.num_constraints()) {
    return false;
  }
  const int N = S->N, nx = S->nx, nu = S->nu, nc = S->nc;
  Iterate it;
  S->ToIterate(z, &it);
  it.lam.resize(nx, N);
  for (int k = 0; k < N; ++k) it.lam.col(k) = lambda.segment(S->nlp.defect_row(k), nx);
  it.y.resize(N + 1);
  for (int k = 0; k <= N; ++k) {
    it.y[k] = Vec::Zero(S->ni(k));
    if (nc > 0 && S->ni(k) > 0)
      it.y[k].head(nc) = lambda.segment(S->nlp.path_row_begin() + k * nc, nc);
    for (int b = 0; k < S->nctl() && b < S->nball; ++b) {
      it.y[k][nc + b] = lambda[S->nlp.ball_row_begin() + k * S->nball + b];
    }
  }
  it.nu.resize(S->nterm());
  if (S->npsi > 0) it.nu.head(S->npsi) = lambda.segment(S->nlp.terminal_row_begin(), S->npsi);
  if (S->nb > 0) it.nu.tail(S->nb) = lambda.segment(S->nlp.boundary_row_begin(), S->nb);
  it.lamV = Vec::Zero(S->copy ? nu : 0);
  it.SB.setZero(S->nbi(), 1);  // the inequality rows read b, as the NLP's
  Values v;
  S->EvalValues(it, &v);
  std::vector<StageEval> st;
  TerminalEval te;
  if (!v.ok || !S->EvalDerivatives(it, &st, &te) || !S->EvalHessians(it, 1.0, &st, &te)) {
    return false;
  }
  // The NLP's constraint rows with their right-hand sides (balls: |u - c|^2 - r^2 + r^2).
  double L = v.f;
  for (int k = 0; k < N; ++k) L += lambda.segment(S->nlp.defect_row(k), nx).dot(v.defects.col(k));
  for (int k = 0; k <= N; ++k) {
    if (S->ni(k) > 0) L += it.y[k].dot(v.c[k]);
    for (int b = 0; k < S->nctl() && b < S->nball; ++b) {
      L += it.y[k][nc + b] * S->balls[b].radius * S->balls[b].radius;
    }
  }
  if (S->nterm() > 0) L += it.nu.dot(v.psi);
  if (S->nb > 0) L += it.nu.tail(S->nb).dot(S->blo);  // the NLP's rows are b, not b - b_lo
  *value = L;
  // Gradient; with the copy v = u_{N-1} at a point where it holds, its multiplier drops out:
  // the copy's stationarity gives lamV = -cu_N^T y_N, so u_{N-1} gains cu_N^T y_N.
  Mat rx, ru;
  Vec rv;
  if (S->copy) it.lamV = -st[N].cu.transpose() * it.y[N];
  double rT = 0.0;
  S->LagrangianGradient(it, 1.0, st, te, &rx, &ru, &rv, &rT);
  Vec g = Vec::Zero(nlp.num_variables());
  for (int k = 0; k <= N; ++k) g.segment(S->state_off[k], nx) = rx.col(k);
  for (int k = 0; k < S->nctl(); ++k) g.segment(S->control_off[k], nu) = ru.col(k);
  if (S->free_time) g[S->time_index] = rT;
  *gradient = g;
  // Hessian: stage blocks, the terminal block, and the t_N path block on (x_N, u_{N-1}).
  Mat H = Mat::Zero(nlp.num_variables(), nlp.num_variables());
  for (int k = 0; k < S->nctl(); ++k) {  // the trapezoid's node N: (x_N, u_N)
    const int xo = S->state_off[k], uo = S->control_off[k];
    const Mat& Hk = st[k].H;
    H.block(xo, xo, nx, nx) += Hk.topLeftCorner(nx, nx);
    H.block(xo, uo, nx, nu) += Hk.topRightCorner(nx, nu);
    H.block(uo, xo, nu, nx) += Hk.bottomLeftCorner(nu, nx);
    H.block(uo, uo, nu, nu) += Hk.bottomRightCorner(nu, nu);
    if (S->free_time) {  // T's row and column (L is linear in T: no T-T entry)
      const int T = S->time_index;
      for (int j = 0; j < nx; ++j) H(T, xo + j) += st[k].HT[j];
      for (int j = 0; j < nu; ++j) H(T, uo + j) += st[k].HT[nx + j];
    }
  }
  if (S->free_time) {
    const int T = S->time_index;
    H.col(T) = H.row(T).transpose();
  }
  const int xN = S->state_off[N];
  H.block(xN, xN, nx, nx) += te.H;
  if (S->initial_cost) H.block(S->state_off[0], S->state_off[0], nx, nx) += te.H0;
  if (S->nb > 0) {  // b's Hessian in (x_0, x_N)
    const int x0 = S->state_off[0];
    H.block(x0, x0, nx, nx) += te.Hb.topLeftCorner(nx, nx);
    H.block(x0, xN, nx, nx) += te.Hb.topRightCorner(nx, nx);
    H.block(xN, x0, nx, nx) += te.Hb.bottomLeftCorner(nx, nx);
    H.block(xN, xN, nx, nx) += te.Hb.bottomRightCorner(nx, nx);
  }
  if (S->copy) {
    const int uo = S->control_off[N - 1];
    const Mat& Hk = st[N].H;
    H.block(xN, xN, nx, nx) += Hk.topLeftCorner(nx, nx);
    H.block(xN, uo, nx, nu) += Hk.topRightCorner(nx, nu);
    H.block(uo, xN, nu, nx) += Hk.bottomLeftCorner(nu, nx);
    H.block(uo, uo, nu, nu) += Hk.bottomRightCorner(nu, nu);
  }
  *hessian = H;
  return true;
}

}  // namespace ocpb
