#include "solvers/indirect_newton.h"

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/KLUSupport>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/UmfPackSupport>

#include "core/control_set.h"
#include "core/evaluator.h"
#include "core/option_binding.h"
#include "core/timer.h"
#include "solvers/bvp_riccati_solver.h"
#include "solvers/costate_fit.h"
#include "solvers/hamiltonian_descent.h"
#include "solvers/hamiltonian_target.h"
#include "solvers/pmp_residual.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

constexpr const char* kName = "indirect-newton";
std::string NewtonNumber(double v) {
  std::ostringstream os;
  os.precision(3);
  os << v;
  return os.str();
}

// The sparse LU of the Newton matrix: analysis once, numeric factorization every step.
class SparseLu {
 public:
  virtual ~SparseLu() = default;
  virtual bool Analyze(const Eigen::SparseMatrix<double>& A) = 0;
  virtual bool Factorize(const Eigen::SparseMatrix<double>& A) = 0;
  virtual void Solve(const Vec& b, Vec* x) = 0;
};

template <class Lu>
class EigenSparseLu final : public SparseLu {
 public:
  bool Analyze(const Eigen::SparseMatrix<double>& A) override {
    lu_.analyzePattern(A);
    return lu_.info() == Eigen::Success;
  }
  bool Factorize(const Eigen::SparseMatrix<double>& A) override {
    lu_.factorize(A);
    return lu_.info() == Eigen::Success;
  }
  void Solve(const Vec& b, Vec* x) override { *x = lu_.solve(b); }

 private:
  Lu lu_;
};

// kRiccati's fallback is KLU.
std::unique_ptr<SparseLu> MakeLu(IndirectNewtonOptions::LinearSolver solver) {
  using Sparse = Eigen::SparseMatrix<double>;
  if (solver != IndirectNewtonOptions::LinearSolver::kUmfpack) {
    return std::make_unique<EigenSparseLu<Eigen::KLU<Sparse>>>();
  }
  return std::make_unique<EigenSparseLu<Eigen::UmfPackLU<Sparse>>>();
}

SolveResult Result(SolveStatus status, std::string solver_status, std::string message) {
  SolveResult r;
  r.solver = kName;
  r.status = status;
  r.solver_status = std::move(solver_status);
  r.message = std::move(message);
  return r;
}

// nu minimizing |p_N - grad phi(x_N) - psi_x^T nu| (the hard form's multipliers for a given
// terminal costate).
// A trajectory's values at the grid's nodes (the left limit at the last node).
Mat SampleNodes(const ControlTrajectory& trajectory, const TimeGrid& grid) {
  Mat out(trajectory.nu(), grid.size());
  for (int k = 0; k < grid.size(); ++k) {
    const auto side =
        k + 1 == grid.size() ? ControlTrajectory::Side::kLeft : ControlTrajectory::Side::kRight;
    trajectory.Evaluate(grid.t(k), side, out.col(k));
  }
  return out;
}

Vec EstimateMultipliers(const Ocp& ocp, ConstVecRef xN, ConstVecRef pN) {
  const int nx = ocp.nx(), npsi = ocp.num_terminal();
  Vec grad(nx), psi(npsi);
  Mat psix(npsi, nx);
  double phi = 0.0;
  ocp.TerminalCostGradient(xN, &phi, grad);
  ocp.TerminalConstraintsJacobian(xN, psi, psix);
  Vec nu = psix.transpose().colPivHouseholderQr().solve(pN - grad);
  if (!nu.allFinite()) nu.setZero();
  return nu;
}

// The problem the method solves: the problem's Hamiltonian reformulation when it offers one.
HamiltonianTarget ResolveNewtonTarget(const Ocp& original, const IndirectNewtonOptions& o) {
  HamiltonianReformulationOptions options;
  options.path_penalty = o.path_penalty;
  options.regularization = o.regularization;
  HamiltonianTarget t = ResolveHamiltonianTarget(original, options);
  const std::string prefix = t.NotePrefix();
  // H(tf) = 0 closes a free final time, p(t0) = -grad phi0 (clipped by the bounds) a free
  // initial state and static parameters (PmpResidual); no state bounds, no boundary rows.
  ProblemFeatures takes;
  takes.free_final_time = true;
  takes.free_initial_state = true;
  if (std::string why = UnsupportedFeature(original, "indirect-newton", takes); !why.empty()) {
    t.not_applicable = Result(SolveStatus::kNotApplicable, "not_applicable", why);
  } else if (!t.ocp->HasHamiltonianMinimizer()) {
    t.not_applicable =
        Result(SolveStatus::kNotApplicable,
               "not_applicable",
               prefix + "problem '" + t.ocp->name() + "' has no closed-form Hamiltonian minimizer");
  } else if (t.ocp->num_path() > 0) {
    t.not_applicable = Result(SolveStatus::kNotApplicable,
                              "not_applicable",
                              prefix + "problem '" + t.ocp->name() +
                                  "' has path constraints and offers no reformulation that folds "
                                  "them into L");
  }
  if (t.not_applicable) {
    t.not_applicable->iterations = 0;
    t.not_applicable->cpu_seconds = 0.0;
    t.not_applicable->wall_seconds = 0.0;
  }
  return t;
}

struct NewtonRun {
  const Ocp& ocp;
  const SolveRequest& request;
  const IndirectNewtonOptions& options;
  const Stopwatch& watch;
};

// Newton's method from (X, P, nu); fills everything of `r` that Newton knows.
// Newton's method with backtracking on the residual of one PmpResidual: the unknowns z, the
// residual F at z, and the work counters every record reports.
class NewtonIteration {
 public:
  NewtonIteration(const NewtonRun& run, PmpResidual& pmp)
      : run_(run),
        pmp_(pmp),
        lu_(MakeLu(run.options.linear_solver)),
        lu_name_(ToString(run.options.linear_solver)) {
    if (run.options.linear_solver == IndirectNewtonOptions::LinearSolver::kRiccati) {
      riccati_ = std::make_unique<BvpRiccatiSolver>(pmp);
    }
  }

  // z from the start (X0, P0 and the terminal multipliers nu0, or their estimate).
  void Start(const Mat& X0, const Mat& P0, const Vec* nu0) {
    const Ocp& ocp = run_.ocp;
    const int N = run_.request.grid.intervals();
    if (X0.rows() != ocp.nx() || X0.cols() != N + 1 || P0.rows() != ocp.nx() ||
        P0.cols() != N + 1) {
      throw std::invalid_argument(std::string(kName) +
                                  ": the start X and P must be nx x (N+1) on the request's grid");
    }
    Vec nu;
    if (pmp_.num_multipliers() > 0) {
      if (nu0) {
        if (nu0->size() != pmp_.num_multipliers()) {
          throw std::invalid_argument(std::string(kName) + ": the start nu must have size npsi");
        }
        nu = *nu0;
      } else {
        nu = EstimateMultipliers(ocp, X0.col(N), P0.col(N));
      }
    }
    z_ = pmp_.Pack(X0, P0, nu);
    const int n = pmp_.size();
    F_.resize(n);
    F_trial_.resize(n);
    d_.resize(n);
    z_trial_.resize(n);
    rhs_.resize(n);
  }

  // Iterates until convergence or a stop; the history rows go to r.
  void Run(SolveResult* r) {
    if (!Evaluate(z_, &F_, &J_, false)) {
      Stop(SolveStatus::kNumericalFailure,
           FailureStatus(),
           "at the start: " + pmp_.FailureMessage());
      J_ = -1.0;  // not computed
      r->history.push_back({0, J_, NAN, -1, NAN, NAN, run_.watch.cpu()});
      return;
    }
    const IndirectNewtonOptions& o = run_.options;
    for (;;) {
      const double residual = F_.lpNorm<Eigen::Infinity>();
      IterationRecord rec;
      rec.iteration = iterations_;
      rec.J = J_;
      rec.armijo_j = backtracks_;
      rec.primal_inf = residual;
      rec.cpu_seconds = run_.watch.cpu();
      r->history.push_back(rec);
      if (residual <= o.tolerance) {
        Stop(SolveStatus::kConverged,
             "converged",
             "||F||_inf = " + NewtonNumber(residual) + " <= " + NewtonNumber(o.tolerance) +
                 " after " + std::to_string(iterations_) + " Newton steps (" + lu_name_ + ")");
        return;
      }
      if (iterations_ >= o.max_iterations) {
        Stop(SolveStatus::kMaxIterations,
             "max_iterations",
             "||F||_inf = " + NewtonNumber(residual) +
                 " after max_iterations = " + std::to_string(o.max_iterations) + " Newton steps");
        return;
      }
      if (OutOfTime()) {
        Stop(SolveStatus::kMaxTime,
             "max_cpu_seconds",
             "reached max_cpu_seconds = " + NewtonNumber(o.max_cpu_seconds) + " at iterate " +
                 std::to_string(iterations_) + " (||F||_inf = " + NewtonNumber(residual) + ")");
        return;
      }
      if (!Evaluate(z_, &F_, &J_, true)) {
        Stop(SolveStatus::kNumericalFailure,
             FailureStatus(),
             "Jacobian at iterate " + std::to_string(iterations_) + ": " + pmp_.FailureMessage());
        return;
      }
      if (!Direction()) return;
      if (!LineSearch(residual)) return;
      stalled_steps_ = accepted_step_ <= IndirectNewtonOptions::kStallStep ? stalled_steps_ + 1 : 0;
      // A short last step that lands within the tolerance is convergence (the loop's next
      // turn reports it), not a stall.
      if (o.stall_steps > 0 && stalled_steps_ >= o.stall_steps &&
          F_.lpNorm<Eigen::Infinity>() > o.tolerance) {
        ++iterations_;
        rec.iteration = iterations_;
        rec.J = J_;
        rec.armijo_j = backtracks_;
        rec.primal_inf = F_.lpNorm<Eigen::Infinity>();
        rec.cpu_seconds = run_.watch.cpu();
        r->history.push_back(rec);
        Stop(SolveStatus::kStepTooSmall,
             "stalled",
             std::to_string(o.stall_steps) + " steps in a row of length <= 1/256 at iterate " +
                 std::to_string(iterations_) + " (||F||_inf = " + NewtonNumber(rec.primal_inf) +
                 ")");
        return;
      }
      ++iterations_;
    }
  }

  // The result's fields and the work counters.
  void Finish(double newton_cpu0, SolveResult* r) {
    const double final_time = pmp_.FinalTime(z_);
    Mat X, P;
    pmp_.Unpack(z_, &X, &P, nullptr);
    const TimeGrid solution_grid = pmp_.GridOf(z_);
    r->status = status_;
    r->solver_status = solver_status_;
    r->message = r->message.empty() ? message_ : r->message + "; Newton: " + message_;
    r->controls = pmp_.ControlFunction(z_);
    if (pmp_.free_initial_state()) r->initial_state = X.col(0);
    r->state_grid = solution_grid;
    r->states = std::move(X);
    r->costates = std::move(P);
    r->costate_source = "Newton's p (discretized maximum principle)";
    r->objective = J_;
    r->iterations = iterations_;
    r->cpu_seconds = run_.watch.cpu();
    r->wall_seconds = run_.watch.wall();
    auto& s = r->solver_stats;
    s["assembly_seconds"] = assembly_;
    s["factorization_seconds"] = factorization_;
    s["solve_seconds"] = solve_;
    s["newton_cpu_seconds"] = CpuSeconds() - newton_cpu0;
    s["residual_inf"] = r->history.back().primal_inf;
    if (pmp_.free_final_time()) s["final_time"] = final_time;
    s["unknowns"] = pmp_.size();
    s["jacobian_nonzeros"] = pmp_.structural_nonzeros();
    s["residual_evaluations"] = residual_evaluations_;
    s["jacobian_evaluations"] = jacobian_evaluations_;
    if (riccati_) s["riccati_fallbacks"] = riccati_fallbacks_;
  }

 private:
  bool Evaluate(const Vec& at,
                Vec* out,
                double* cost,
                bool with_jacobian,
                double abandon_above = std::numeric_limits<double>::infinity()) {
    const double t0 = CpuSeconds();
    const bool ok = pmp_.Evaluate(at, *out, cost, with_jacobian, abandon_above);
    assembly_ += CpuSeconds() - t0;
    ++(with_jacobian ? jacobian_evaluations_ : residual_evaluations_);
    return ok;
  }
  const char* FailureStatus() const {
    switch (pmp_.failure()) {
      case PmpResidual::Failure::kSingularMinimizer:
        return "singular_minimizer";
      case PmpResidual::Failure::kBadFinalTime:
        return "bad_final_time";
      case PmpResidual::Failure::kAbandoned:  // only a line-search trial, never a reported point
        return "abandoned_trial";
      default:
        return "nonfinite_residual";
    }
  }
  bool OutOfTime() const { return CpuLimit{&run_.watch, run_.options.max_cpu_seconds}.Reached(); }
  void Stop(SolveStatus status, const char* code, std::string message) {
    status_ = status;
    solver_status_ = code;
    message_ = std::move(message);
  }

  // The Newton step d from J(z) d = -F(z) (the Jacobian evaluated at z); false after a stop.
  bool Direction() {
    double t0 = CpuSeconds();
    if (riccati_) {
      // The structured sweep, or the sparse LU when it declines (BvpRiccatiSolver).
      const bool factored = riccati_->Factorize();
      factorization_ += CpuSeconds() - t0;
      t0 = CpuSeconds();
      rhs_ = -F_;
      const bool solved = factored && riccati_->Solve(rhs_, &d_);
      solve_ += CpuSeconds() - t0;
      if (solved) return true;
      ++riccati_fallbacks_;
      t0 = CpuSeconds();
    }
    bool factored = true;
    if (!analyzed_) factored = lu_->Analyze(pmp_.jacobian());
    analyzed_ = true;
    factored = factored && lu_->Factorize(pmp_.jacobian());
    factorization_ += CpuSeconds() - t0;
    if (!factored) {
      Stop(SolveStatus::kNumericalFailure,
           "singular_jacobian",
           (riccati_ ? std::string("klu (the fallback where the Riccati sweep declined)")
                     : std::string(lu_name_)) +
               " reports the Newton matrix singular at iterate " + std::to_string(iterations_));
      return false;
    }
    t0 = CpuSeconds();
    rhs_ = -F_;
    lu_->Solve(rhs_, &d_);
    solve_ += CpuSeconds() - t0;
    if (!d_.allFinite()) {
      Stop(SolveStatus::kNumericalFailure,
           "nonfinite_step",
           std::string(lu_name_) + " returned a non-finite Newton step at iterate " +
               std::to_string(iterations_));
      return false;
    }
    return true;
  }

  // Backtracking on 1/2 |F|^2 along d; moves z on success, false after a stop. Trials are
  // evaluated without the Jacobian, which Run() then evaluates at the accepted point: a rejected
  // trial with the Jacobian costs about ten residual evaluations (comm-path2d; the previous rule,
  // a full step after a full step tried with the Jacobian, wasted 11 of 64 Jacobians on gamma =
  // 1e-4, seed 1), an accepted one would save only one. The iterates do not depend on this.
  // A trial's evaluation is abandoned once its partial sum of squares already fails the test
  // (PmpResidual::Evaluate's abandon_above; the same decision, as the squares are >= 0).
  bool LineSearch(double residual) {
    const IndirectNewtonOptions& o = run_.options;
    const double merit = 0.5 * F_.squaredNorm();
    double step = 1.0;
    int j = 0;
    while (step >= o.min_step) {
      if (j > 0 && OutOfTime()) {
        Stop(SolveStatus::kMaxTime,
             "max_cpu_seconds",
             "reached max_cpu_seconds = " + NewtonNumber(o.max_cpu_seconds) +
                 " in the line search at iterate " + std::to_string(iterations_) + " after " +
                 std::to_string(j) + " trials (||F||_inf = " + NewtonNumber(residual) + ")");
        return false;
      }
      z_trial_ = z_ + step * d_;
      const double bound = (1.0 - 2.0 * o.sufficient_decrease * step) * merit;
      const bool ok = Evaluate(z_trial_, &F_trial_, &J_trial_, false, 2.0 * bound);
      if (ok && 0.5 * F_trial_.squaredNorm() <= bound) {
        z_.swap(z_trial_);
        F_.swap(F_trial_);
        J_ = J_trial_;
        backtracks_ = j;
        accepted_step_ = step;
        return true;
      }
      step *= o.backtrack;
      ++j;
    }
    Stop(SolveStatus::kStepTooSmall,
         "line_search_failed",
         "no step >= min_step = " + NewtonNumber(o.min_step) +
             " decreased 1/2 ||F||^2 enough at iterate " + std::to_string(iterations_) +
             " (||F||_inf = " + NewtonNumber(residual) + ")");
    return false;
  }

  const NewtonRun& run_;
  PmpResidual& pmp_;
  std::unique_ptr<SparseLu> lu_;
  std::unique_ptr<BvpRiccatiSolver> riccati_;  // kRiccati: tried first, lu_ (KLU) its fallback
  bool analyzed_ = false;
  int riccati_fallbacks_ = 0;
  const char* lu_name_;
  Vec z_, F_, F_trial_, d_, z_trial_, rhs_;
  double J_ = 0.0, J_trial_ = 0.0;
  double assembly_ = 0.0, factorization_ = 0.0, solve_ = 0.0;
  int residual_evaluations_ = 0, jacobian_evaluations_ = 0;
  int iterations_ = 0, backtracks_ = -1, stalled_steps_ = 0;
  double accepted_step_ = 1.0;
  SolveStatus status_ = SolveStatus::kError;
  std::string solver_status_, message_;
};

void RunNewton(const NewtonRun& run, const Mat& X0, const Mat& P0, const Vec* nu0, SolveResult* r) {
  const double newton_cpu0 = CpuSeconds();
  PmpResidual pmp(run.ocp,
                  run.request.grid,
                  run.request.terminal,
                  run.options.scheme == IndirectNewtonOptions::Scheme::kEuler
                      ? PmpResidual::Scheme::kEuler
                      : PmpResidual::Scheme::kTrapezoid);
  NewtonIteration newton(run, pmp);
  newton.Start(X0, P0, nu0);
  newton.Run(r);
  newton.Finish(newton_cpu0, r);
}

}  // namespace

const char* ToString(IndirectNewtonOptions::LinearSolver solver) {
  switch (solver) {
    case IndirectNewtonOptions::LinearSolver::kKlu:
      return "klu";
    case IndirectNewtonOptions::LinearSolver::kRiccati:
      return "riccati";
    case IndirectNewtonOptions::LinearSolver::kUmfpack:
      break;
  }
  return "umfpack";
}

const char* ToString(IndirectNewtonOptions::WarmStart warm_start) {
  switch (warm_start) {
    case IndirectNewtonOptions::WarmStart::kHamiltonian:
      return "hamiltonian";
    case IndirectNewtonOptions::WarmStart::kIpopt:
      return "ipopt";
    case IndirectNewtonOptions::WarmStart::kNone:
      break;
  }
  return "none";
}

const char* ToString(IndirectNewtonOptions::Costates costates) {
  switch (costates) {
    case IndirectNewtonOptions::Costates::kFit:
      return "fit";
    case IndirectNewtonOptions::Costates::kAdjoint:
      return "adjoint";
    case IndirectNewtonOptions::Costates::kDefault:
      break;
  }
  return "default";
}

namespace {

const OptionBinding<IndirectNewtonOptions>& NewtonBinding() {
  static const OptionBinding<IndirectNewtonOptions> table = [] {
    using O = IndirectNewtonOptions;
    OptionBinding<O> t(kName);
    t.Integer(
        "max_iterations", &O::max_iterations, "Newton steps at most", OptionBounds::AtLeast(0));
    t.Number(
        "tolerance", &O::tolerance, "converged when ||F||_inf <= this", OptionBounds::Above(0));
    t.Number("max_cpu_seconds",
             &O::max_cpu_seconds,
             "CPU time limit of the solve, warm start included (inf: none)",
             OptionBounds::Above(0).WithInfinity());
    t.Number("sufficient_decrease",
             &O::sufficient_decrease,
             "Armijo constant c of the merit 1/2 ||F||^2",
             OptionBounds::Open(0, 0.5));
    t.Number("backtrack", &O::backtrack, "step reduction factor", OptionBounds::Open(0, 1));
    t.Number("min_step",
             &O::min_step,
             "smallest step tried (else line_search_failed)",
             OptionBounds::OpenClosed(0, 1));
    t.Integer("stall_steps",
              &O::stall_steps,
              "end ('stalled') after this many steps in a row of length <= 1/256 (0: off)",
              OptionBounds::AtLeast(0));
    t.Enum("linear_solver",
           &O::linear_solver,
           {{"umfpack", O::LinearSolver::kUmfpack},
            {"klu", O::LinearSolver::kKlu},
            {"riccati", O::LinearSolver::kRiccati}},
           "the Newton matrix's solver: a sparse LU, or the Riccati sweep (KLU its fallback)");
    t.Enum("warm_start",
           &O::warm_start,
           {{"none", O::WarmStart::kNone},
            {"hamiltonian", O::WarmStart::kHamiltonian},
            {"ipopt", O::WarmStart::kIpopt}},
           "where Newton starts: the request's controls, the descent's solution, Ipopt's");
    t.Enum("costates",
           &O::costates,
           {{"default", O::Costates::kDefault},
            {"fit", O::Costates::kFit},
            {"adjoint", O::Costates::kAdjoint}},
           "how the start's costates are made (default: adjoint after ipopt, else fit)");
    t.OptionalNumber("path_penalty",
                     &O::path_penalty,
                     "rho of the reformulation's path penalty rho max(0, c)^2",
                     OptionBounds::Above(0),
                     "the problem's own default");
    t.OptionalNumber("regularization",
                     &O::regularization,
                     "eps of the reformulation's control regularization eps |u|^2",
                     OptionBounds::Above(0),
                     "the problem's own default");
    t.Nested("hamiltonian",
             &O::warm_start_options,
             HamiltonianDescent::Schema(),
             "options of the warm start's hamiltonian solver (needs warm_start = hamiltonian)");
    return t;
  }();
  return table;
}

}  // namespace

bool IndirectNewtonOptions::IsValid(std::string* error) const {
  if (!NewtonBinding().Check(*this, error)) return false;
  if (warm_start != WarmStart::kHamiltonian && !warm_start_options.empty()) {
    if (error)
      *error = std::string(kName) + ": hamiltonian.<key> options need warm_start = hamiltonian";
    return false;
  }
  return true;
}

IndirectNewton::IndirectNewton(const Options& options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument(error);
}

const OptionSchema& IndirectNewton::Schema() { return NewtonBinding().schema(); }

IndirectNewton::Options IndirectNewton::ApplyOptions(const OptionMap& options,
                                                     const Options& base) {
  return NewtonBinding().ApplyValidated(options, base);
}

void IndirectNewton::StartFromControls(const Ocp& ocp,
                                       const TimeGrid& grid,
                                       TerminalMode mode,
                                       const ControlTrajectory& controls,
                                       Mat* X,
                                       Mat* P,
                                       Options::Costates how) {
  *X = Evaluate(ocp, controls, grid, Integrator::kRk4).X;
  CostatesFromControls(ocp, grid, mode, controls, *X, how, P);
}

void IndirectNewton::CostatesFromControls(const Ocp& ocp,
                                          const TimeGrid& grid,
                                          TerminalMode mode,
                                          const ControlTrajectory& controls,
                                          const Mat& X,
                                          Options::Costates how,
                                          Mat* P,
                                          bool* adjoint_fallback) {
  if (adjoint_fallback) *adjoint_fallback = false;
  const int nx = ocp.nx(), nu = ocp.nu(), N = grid.intervals();
  if (X.rows() != nx || X.cols() != N + 1 || controls.nu() != nu) {
    throw std::invalid_argument(
        std::string(kName) + ": the start's states must be nx x (N+1) and its controls nu-valued");
  }
  // Backward sweep of p_{k+1} - p_k + h/2 (H_x,k + H_x,k+1) = 0, H_x = L_x + f_x^T p, as
  // p_k = M_k q + c_k: (I - h/2 fx_k^T) p_k = (I + h/2 fx_k+1^T) p_{k+1} + h/2 (Lx_k + Lx_k+1).
  std::vector<Mat> M(N + 1);
  std::vector<Vec> c(N + 1);
  M[N] = Mat::Identity(nx, nx);
  c[N] = Vec::Zero(nx);
  Vec f(nx), Lx(nx), Lu(nu), ua(nu), ub(nu), rhs(nx);
  Mat fx(nx, nx), fu(nx, nu), B(nx, nx);
  double L = 0.0;
  for (int k = N - 1; k >= 0; --k) {
    const double hh = 0.5 * grid.h(k);
    controls.Evaluate(grid.t(k + 1), ControlTrajectory::Side::kLeft, ub);
    controls.Evaluate(grid.t(k), ControlTrajectory::Side::kRight, ua);
    ocp.DynamicsJacobian(grid.t(k + 1), X.col(k + 1), ub, f, fx, fu);
    ocp.RunningCostGradient(grid.t(k + 1), X.col(k + 1), ub, &L, Lx, Lu);
    B = Mat::Identity(nx, nx) + hh * fx.transpose();
    rhs = hh * Lx;
    ocp.DynamicsJacobian(grid.t(k), X.col(k), ua, f, fx, fu);
    ocp.RunningCostGradient(grid.t(k), X.col(k), ua, &L, Lx, Lu);
    rhs += hh * Lx;
    const Eigen::PartialPivLU<Mat> A((Mat::Identity(nx, nx) - hh * fx.transpose()).eval());
    M[k] = A.solve(B * M[k + 1]);
    c[k] = A.solve(B * c[k + 1] + rhs);
  }
  Vec q(nx);
  double value = 0.0;
  ocp.TerminalObjectiveGradient(X.col(N), mode, &value, q);
  if (how != Options::Costates::kAdjoint) {
    // The trapezoid's pairing: node k is (t_k, x_k, u(t_k)) with p_k, weight (h_{k-1} + h_k) / 2
    // (u from the right at t_k, from the left at t_N).
    CostateFitNodes nodes;
    Mat U(nu, N + 1);
    nodes.t.resize(static_cast<size_t>(N + 1));
    nodes.weight.resize(static_cast<size_t>(N + 1));
    for (int k = 0; k <= N; ++k) {
      const double t = grid.t(k);
      controls.Evaluate(
          t, k < N ? ControlTrajectory::Side::kRight : ControlTrajectory::Side::kLeft, U.col(k));
      nodes.t[static_cast<size_t>(k)] = t;
      nodes.weight[static_cast<size_t>(k)] =
          0.5 * ((k > 0 ? grid.h(k - 1) : 0.0) + (k < N ? grid.h(k) : 0.0));
    }
    nodes.X = &X;
    nodes.U = &U;
    nodes.costate_offset = 0;
    const CostateFit fit = FitTerminalCostate(ocp, nodes, M, c, q);
    q = fit.q;
    // A Mayer cost: the adjoint sweep's own terminal costate (the penalty form's gradient).
    if (fit.degenerate) ocp.TerminalObjectiveGradient(X.col(N), TerminalMode::kPenalty, &value, q);
    if (adjoint_fallback) *adjoint_fallback = fit.degenerate;
  }
  P->resize(nx, N + 1);
  for (int k = 0; k <= N; ++k) P->col(k) = M[k] * q + c[k];
}

SolveResult IndirectNewton::Solve(const Ocp& original, const SolveRequest& request) const {
  const Stopwatch watch;
  const Options o = ApplyOptions(request.options, options_);
  HamiltonianTarget target = ResolveNewtonTarget(original, o);
  if (target.not_applicable) return *target.not_applicable;
  const Ocp& ocp = *target.ocp;
  // Validates the grid (throws std::invalid_argument) before any work.
  PmpResidual::CheckApplicable(ocp, request.grid);

  SolveResult r;
  r.solver = kName;
  r.message = target.note;
  r.solver_stats["reformulated"] = target.reformulated ? 1.0 : 0.0;
  Mat X, P;
  SolveRequest newton_request = request;  // its grid: the start's (stretched to its T)
  if (o.warm_start == Options::WarmStart::kHamiltonian && ocp.HasFreeInitialState()) {
    // The descent starts every trajectory from x0: it would refuse, and the warm start fail.
    return NotApplicableResult(
        kName,
        target.NotePrefix() +
            "warm_start=hamiltonian: the Hamiltonian descent does not take the "
            "free initial state of problem '" +
            original.name() + "'; use warm_start=none or warm_start=ipopt");
  }
  if (o.warm_start != Options::WarmStart::kNone) {
    const bool descent = o.warm_start == Options::WarmStart::kHamiltonian;
    const std::string warm_name = descent ? "hamiltonian" : "ipopt";
    const SolverInfo& info = FindSolver(warm_name);
    SolveRequest warm = request;
    if (descent) {
      warm.terminal = TerminalMode::kPenalty;
      warm.options = o.warm_start_options;
      // The descent reformulates the problem itself; give it the same reformulation.
      if (o.path_penalty && !warm.options.Has("path_penalty")) {
        warm.options.Set("path_penalty", *o.path_penalty);
      }
      if (o.regularization && !warm.options.Has("regularization")) {
        warm.options.Set("regularization", *o.regularization);
      }
      if (std::isfinite(o.max_cpu_seconds) && !warm.options.Has("max_cpu_seconds")) {
        warm.options.Set("max_cpu_seconds", o.max_cpu_seconds);
      }
    } else {
      // Ipopt's defaults on the trapezoid transcription of the same grid and terminal form:
      // the NLP whose KKT conditions are closest to this trapezoidal BVP.
      warm.transcription = "trapezoid";
      warm.options = OptionMap();
      warm.transcription_options = OptionMap();
      if (std::isfinite(o.max_cpu_seconds)) warm.options.Set("max_cpu_time", o.max_cpu_seconds);
    }
    const double cpu0 = CpuSeconds();
    const Stopwatch warm_watch;
    const SolveResult start = info.make()->Solve(original, warm);
    r.solver_stats["warm_start_cpu_seconds"] = CpuSeconds() - cpu0;
    r.solver_stats["warm_start_wall_seconds"] = warm_watch.wall();
    r.solver_stats["warm_start_iterations"] = start.iterations;
    r.solver_stats["warm_start_objective"] = start.objective;
    const std::string summary = "warm start: " + warm_name + " " + start.solver_status + " after " +
                                std::to_string(start.iterations) +
                                " iterations, J = " + NewtonNumber(start.objective);
    const int N = request.grid.intervals();
    if (start.states.rows() != ocp.nx() || start.states.cols() != N + 1 ||
        start.state_grid.size() != N + 1 || !ocp.AdmitsFinalTime(start.state_grid.tf()) ||
        start.costates.rows() != ocp.nx() || start.costates.cols() != N + 1 ||
        !start.states.allFinite() || !start.costates.allFinite() ||
        start.controls.nu() != ocp.nu()) {
      SolveResult failed = Result(SolveStatus::kError,
                                  "warm_start_failed",
                                  target.NotePrefix() + summary +
                                      " gave no finite states/costates/controls on the grid (" +
                                      ToString(start.status) + ": " + start.message + ")");
      failed.solver_stats = r.solver_stats;
      failed.iterations = 0;
      failed.cpu_seconds = watch.cpu();
      failed.wall_seconds = watch.wall();
      return failed;
    }
    r.message +=
        (r.message.empty() ? "" : "; ") + summary + ", costates " + ToString(o.EffectiveCostates());
    X = start.states;
    newton_request.grid = start.state_grid;
    const double start_cpu0 = CpuSeconds();
    if (o.EffectiveCostates() == Options::Costates::kFit) {
      bool fallback = false;
      CostatesFromControls(ocp,
                           start.state_grid,
                           request.terminal,
                           start.controls,
                           X,
                           Options::Costates::kFit,
                           &P,
                           &fallback);
      r.solver_stats["start_adjoint_fallback"] = fallback ? 1.0 : 0.0;
    } else {
      P = start.costates;
    }
    r.solver_stats["start_cpu_seconds"] = CpuSeconds() - start_cpu0;
  } else {
    const ControlTrajectory guess =
        request.initial_guess ? *request.initial_guess : DefaultInitialGuess(ocp, request.grid);
    if (guess.nu() != ocp.nu()) {
      throw std::invalid_argument(std::string(kName) + ": the initial guess must have nu controls");
    }
    for (const auto* given : {&request.initial_states, &request.initial_costates}) {
      if (*given && (*given)->nu() != ocp.nx()) {
        throw std::invalid_argument(std::string(kName) + ": the initial " +
                                    (given == &request.initial_states ? "states" : "costates") +
                                    " must have nx components");
      }
    }
    // A free final time starts at the guess's own T (a previous solution's), within the bounds.
    const double T = guess.grid().size() >= 2 ? guess.grid().tf() : request.grid.tf();
    if (ocp.free_final_time() && request.initial_guess && T != request.grid.tf() &&
        ocp.AdmitsFinalTime(T)) {
      newton_request.grid = request.grid.StretchedTo(T);
    }
    const TimeGrid& grid = newton_request.grid;
    const double start_cpu0 = CpuSeconds();
    X = request.initial_states ? SampleNodes(*request.initial_states, grid)
                               : Evaluate(ocp, guess, grid, Integrator::kRk4).X;
    if (request.initial_costates) {
      P = SampleNodes(*request.initial_costates, grid);
    } else {
      bool fallback = false;
      CostatesFromControls(
          ocp, grid, request.terminal, guess, X, o.EffectiveCostates(), &P, &fallback);
      if (o.EffectiveCostates() == Options::Costates::kFit) {
        r.solver_stats["start_adjoint_fallback"] = fallback ? 1.0 : 0.0;
      }
    }
    r.solver_stats["start_cpu_seconds"] = CpuSeconds() - start_cpu0;
  }
  RunNewton({ocp, newton_request, o, watch}, X, P, nullptr, &r);
  return r;
}

SolveResult IndirectNewton::SolveFrom(const Ocp& original,
                                      const SolveRequest& request,
                                      const Mat& X,
                                      const Mat& P,
                                      const Vec* nu) const {
  const Stopwatch watch;
  const Options o = ApplyOptions(request.options, options_);
  HamiltonianTarget target = ResolveNewtonTarget(original, o);
  if (target.not_applicable) return *target.not_applicable;
  SolveResult r;
  r.solver = kName;
  r.message = target.note;
  r.solver_stats["reformulated"] = target.reformulated ? 1.0 : 0.0;
  RunNewton({*target.ocp, request, o, watch}, X, P, nu, &r);
  return r;
}

}  // namespace ocpb
