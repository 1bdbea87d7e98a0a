#include "solvers/indirect_newton.h"

#include <cmath>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/KLUSupport>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/UmfPackSupport>

#include "core/control_set.h"
#include "core/evaluator.h"
#include "core/timer.h"
#include "solvers/pmp_residual.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

constexpr const char* kName = "indirect-newton";
constexpr const char* kValidKeys =
    "max_iterations, tolerance, sufficient_decrease, backtrack, min_step, linear_solver, "
    "warm_start, costates, path_penalty, regularization, hamiltonian.<key>";
constexpr const char* kWarmPrefix = "hamiltonian.";

[[noreturn]] void BadOption(const std::string& key, const std::string& rule) {
  throw std::invalid_argument(std::string(kName) + " option '" + key + "': " + rule);
}

double ParseDouble(const std::string& key, const std::string& text) {
  size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || std::isnan(v))
    BadOption(key, "'" + text + "' is not a number");
  return v;
}

int ParseInt(const std::string& key, const std::string& text) {
  const double v = ParseDouble(key, text);
  if (!std::isfinite(v) || v != std::round(v) || std::abs(v) > 1e9) {
    BadOption(key, "'" + text + "' is not an integer");
  }
  return static_cast<int>(v);
}

std::string Format(double v) {
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

std::unique_ptr<SparseLu> MakeLu(IndirectNewtonOptions::LinearSolver solver) {
  using Sparse = Eigen::SparseMatrix<double>;
  if (solver == IndirectNewtonOptions::LinearSolver::kKlu) {
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

// The components of u strictly inside U (see IndirectNewton::CostatesFromControls).
void FreeComponents(const ControlSet& set, ConstVecRef u, std::vector<int>* free) {
  free->clear();
  if (set.blocks().empty()) {
    for (int i = 0; i < u.size(); ++i) free->push_back(i);
    return;
  }
  constexpr double kMargin = 1e-6;
  for (const ControlSet::Block& b : set.blocks()) {
    if (b.kind == ControlSet::Kind::kBox) {
      for (int i = 0; i < b.size; ++i) {
        const double lo = b.lower[i], hi = b.upper[i], v = u[b.offset + i];
        const double margin = kMargin * (std::isfinite(hi - lo) ? hi - lo : 1.0);
        if (v > lo + margin && v < hi - margin) free->push_back(b.offset + i);
      }
    } else {
      const auto ub = u.segment(b.offset, b.size);
      const double r = b.center.size() > 0 ? (ub - b.center).norm() : ub.norm();
      if (r < (1.0 - kMargin) * b.radius) {
        for (int i = 0; i < b.size; ++i) free->push_back(b.offset + i);
      }
    }
  }
}

// The kFit terminal costate of IndirectNewton::CostatesFromControls, given p_k = M_k q + c_k
// and the adjoint's q0: least squares on the stacked rows sqrt(w_k) (H_uu)_F^-1 (H_u)_F(q) of
// every node, plus the ridge rows delta (q - q0).
Vec FitTerminalCostate(const Ocp& ocp,
                       const TimeGrid& grid,
                       const ControlTrajectory& controls,
                       const Mat& X,
                       const std::vector<Mat>& M,
                       const std::vector<Vec>& c,
                       const Vec& q0) {
  const int nx = ocp.nx(), nu = ocp.nu(), N = grid.intervals();
  std::vector<double> values;  // rows of [A | b], row-major
  Vec f(nx), Lx(nx), Lu(nu), u(nu), p0(nx);
  Mat fx(nx, nx), fu(nx, nu), hess(nx + nu, nx + nu);
  double L = 0.0;
  std::vector<int> free;
  for (int k = 0; k <= N; ++k) {
    const double t = grid.t(k);
    controls.Evaluate(
        t, k < N ? ControlTrajectory::Side::kRight : ControlTrajectory::Side::kLeft, u);
    FreeComponents(ocp.control_set(), u, &free);
    if (free.empty()) continue;
    ocp.DynamicsJacobian(t, X.col(k), u, f, fx, fu);
    ocp.RunningCostGradient(t, X.col(k), u, &L, Lx, Lu);
    p0 = M[k] * q0 + c[k];
    ocp.PointHessian(t, X.col(k), u, 1.0, p0, Vec(), hess);
    const int m = static_cast<int>(free.size());
    Mat Huu(m, m), G(m, nx);
    Vec g(m);
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) Huu(a, b) = hess(nx + free[a], nx + free[b]);
      // H_u,a(q) = Lu_a + fu_a^T (M_k q + c_k) = G_a q + g_a.
      G.row(a) = fu.col(free[a]).transpose() * M[k];
      g[a] = Lu[free[a]] + fu.col(free[a]).dot(c[k]);
    }
    const Eigen::LLT<Mat> llt(Huu);
    if (llt.info() == Eigen::Success && Huu.allFinite()) {
      G = llt.solve(G);
      g = llt.solve(g);
    }
    const double hw = 0.5 * ((k > 0 ? grid.h(k - 1) : 0.0) + (k < N ? grid.h(k) : 0.0));
    const double w = std::sqrt(hw);
    for (int a = 0; a < m; ++a) {
      for (int j = 0; j < nx; ++j) values.push_back(w * G(a, j));
      values.push_back(-w * g[a]);
    }
  }
  const int rows = static_cast<int>(values.size()) / (nx + 1);
  if (rows == 0) return q0;
  Mat A(rows + nx, nx);
  Vec b(rows + nx);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < nx; ++j) A(i, j) = values[static_cast<size_t>(i) * (nx + 1) + j];
    b[i] = values[static_cast<size_t>(i) * (nx + 1) + nx];
  }
  const double delta = 1e-8 * A.topRows(rows).colwise().norm().maxCoeff();
  A.bottomRows(nx) = delta * Mat::Identity(nx, nx);
  b.tail(nx) = delta * q0;
  if (!A.allFinite() || !b.allFinite() || !(delta > 0.0)) return q0;
  const Vec q = A.householderQr().solve(b);
  return q.allFinite() ? q : q0;
}

std::string FormatExact(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

// The problem the method solves: the problem's Hamiltonian reformulation when it offers one.
struct Target {
  std::unique_ptr<Ocp> reformulated;
  const Ocp* ocp = nullptr;
  std::string note;  // says which problem was solved when it is a reformulation
  std::optional<SolveResult> not_applicable;
};

Target Resolve(const Ocp& original, const IndirectNewtonOptions& o) {
  Target t;
  HamiltonianReformulationOptions options;
  options.path_penalty = o.path_penalty;
  options.regularization = o.regularization;
  t.reformulated = original.HamiltonianReformulation(options);
  t.ocp = t.reformulated ? t.reformulated.get() : &original;
  if (t.reformulated) {
    t.note = "solved the problem's Hamiltonian reformulation '" + t.ocp->name() + "'";
    if (t.ocp->nx() != original.nx() || t.ocp->nu() != original.nu() ||
        t.ocp->free_final_time().has_value() != original.free_final_time().has_value()) {
      throw std::logic_error("problem '" + original.name() +
                             "': its Hamiltonian reformulation changed nx, nu or the free final "
                             "time");
    }
  }
  const std::string prefix = t.note.empty() ? "" : t.note + "; ";
  if (!t.ocp->HasHamiltonianMinimizer()) {
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
void RunNewton(const NewtonRun& run, const Mat& X0, const Mat& P0, const Vec* nu0, SolveResult* r) {
  const Ocp& ocp = run.ocp;
  const IndirectNewtonOptions& o = run.options;
  const TimeGrid& grid = run.request.grid;
  const double newton_cpu0 = CpuSeconds();
  PmpResidual pmp(ocp,
                  grid,
                  run.request.terminal,
                  o.scheme == IndirectNewtonOptions::Scheme::kEuler
                      ? PmpResidual::Scheme::kEuler
                      : PmpResidual::Scheme::kTrapezoid);
  const int N = grid.intervals();
  if (X0.rows() != ocp.nx() || X0.cols() != N + 1 || P0.rows() != ocp.nx() || P0.cols() != N + 1) {
    throw std::invalid_argument(std::string(kName) +
                                ": the start X and P must be nx x (N+1) on the request's grid");
  }
  Vec nu;
  if (pmp.num_multipliers() > 0) {
    if (nu0) {
      if (nu0->size() != pmp.num_multipliers()) {
        throw std::invalid_argument(std::string(kName) + ": the start nu must have size npsi");
      }
      nu = *nu0;
    } else {
      nu = EstimateMultipliers(ocp, X0.col(N), P0.col(N));
    }
  }
  Vec z = pmp.Pack(X0, P0, nu);
  const int n = pmp.size();
  Vec F(n), F_trial(n), d(n), z_trial(n), rhs(n);
  double J = 0.0, J_trial = 0.0;
  double assembly = 0.0, factorization = 0.0, solve = 0.0;
  int residual_evaluations = 0, jacobian_evaluations = 0;
  auto evaluate = [&](const Vec& at, Vec* out, double* cost, bool with_jacobian) {
    const double t0 = CpuSeconds();
    const bool ok = pmp.Evaluate(at, *out, cost, with_jacobian);
    assembly += CpuSeconds() - t0;
    ++(with_jacobian ? jacobian_evaluations : residual_evaluations);
    return ok;
  };
  auto failure_status = [&]() {
    switch (pmp.failure()) {
      case PmpResidual::Failure::kSingularMinimizer:
        return "singular_minimizer";
      case PmpResidual::Failure::kBadFinalTime:
        return "bad_final_time";
      default:
        return "nonfinite_residual";
    }
  };
  std::unique_ptr<SparseLu> lu = MakeLu(o.linear_solver);
  const char* lu_name = ToString(o.linear_solver);

  SolveStatus status = SolveStatus::kError;
  std::string solver_status, message;
  int iterations = 0;
  int backtracks = -1;
  if (!evaluate(z, &F, &J, false)) {
    status = SolveStatus::kNumericalFailure;
    solver_status = failure_status();
    message = "at the start: " + pmp.FailureMessage();
    J = -1.0;  // not computed
    r->history.push_back({0, J, NAN, -1, NAN, NAN, run.watch.cpu()});
  } else {
    bool have_jacobian = false;
    for (;;) {
      const double residual = F.lpNorm<Eigen::Infinity>();
      IterationRecord rec;
      rec.iteration = iterations;
      rec.J = J;
      rec.armijo_j = backtracks;
      rec.primal_inf = residual;
      rec.cpu_seconds = run.watch.cpu();
      r->history.push_back(rec);
      if (residual <= o.tolerance) {
        status = SolveStatus::kConverged;
        solver_status = "converged";
        message = "||F||_inf = " + Format(residual) + " <= " + Format(o.tolerance) + " after " +
                  std::to_string(iterations) + " Newton steps (" + lu_name + ")";
        break;
      }
      if (iterations >= o.max_iterations) {
        status = SolveStatus::kMaxIterations;
        solver_status = "max_iterations";
        message = "||F||_inf = " + Format(residual) +
                  " after max_iterations = " + std::to_string(o.max_iterations) + " Newton steps";
        break;
      }
      if (!have_jacobian) {
        if (!evaluate(z, &F, &J, true)) {
          status = SolveStatus::kNumericalFailure;
          solver_status = failure_status();
          message =
              "Jacobian at iterate " + std::to_string(iterations) + ": " + pmp.FailureMessage();
          break;
        }
      }
      double t0 = CpuSeconds();
      bool factored = true;
      if (iterations == 0) factored = lu->Analyze(pmp.jacobian());
      factored = factored && lu->Factorize(pmp.jacobian());
      factorization += CpuSeconds() - t0;
      if (!factored) {
        status = SolveStatus::kNumericalFailure;
        solver_status = "singular_jacobian";
        message = std::string(lu_name) + " reports the Newton matrix singular at iterate " +
                  std::to_string(iterations);
        break;
      }
      t0 = CpuSeconds();
      rhs = -F;
      lu->Solve(rhs, &d);
      solve += CpuSeconds() - t0;
      if (!d.allFinite()) {
        status = SolveStatus::kNumericalFailure;
        solver_status = "nonfinite_step";
        message = std::string(lu_name) + " returned a non-finite Newton step at iterate " +
                  std::to_string(iterations);
        break;
      }
      // Backtracking on 1/2 |F|^2. A full step after a full step is tried with the Jacobian
      // (usually accepted near the solution, which saves an evaluation).
      const double merit = 0.5 * F.squaredNorm();
      double step = 1.0;
      int j = 0;
      bool accepted = false;
      have_jacobian = false;
      while (step >= o.min_step) {
        z_trial = z + step * d;
        const bool with_jacobian = j == 0 && backtracks <= 0;
        bool ok = evaluate(z_trial, &F_trial, &J_trial, with_jacobian);
        bool trial_jacobian = ok && with_jacobian;
        if (!ok && with_jacobian && pmp.failure() == PmpResidual::Failure::kSingularMinimizer) {
          ok = evaluate(z_trial, &F_trial, &J_trial, false);
        }
        if (ok &&
            0.5 * F_trial.squaredNorm() <= (1.0 - 2.0 * o.sufficient_decrease * step) * merit) {
          accepted = true;
          have_jacobian = trial_jacobian;
          break;
        }
        step *= o.backtrack;
        ++j;
      }
      if (!accepted) {
        status = SolveStatus::kStepTooSmall;
        solver_status = "line_search_failed";
        message = "no step >= min_step = " + Format(o.min_step) +
                  " decreased 1/2 ||F||^2 enough at iterate " + std::to_string(iterations) +
                  " (||F||_inf = " + Format(residual) + ")";
        break;
      }
      z.swap(z_trial);
      F.swap(F_trial);
      J = J_trial;
      backtracks = j;
      ++iterations;
    }
  }

  const double final_time = pmp.FinalTime(z);
  Mat X, P;
  pmp.Unpack(z, &X, &P, nullptr);
  const TimeGrid solution_grid = pmp.GridOf(z);
  r->status = status;
  r->solver_status = solver_status;
  r->message = r->message.empty() ? message : r->message + "; Newton: " + message;
  r->controls = pmp.ControlFunction(z);
  r->state_grid = solution_grid;
  r->states = std::move(X);
  r->costates = std::move(P);
  r->objective = J;
  r->iterations = iterations;
  r->cpu_seconds = run.watch.cpu();
  r->wall_seconds = run.watch.wall();
  auto& s = r->solver_stats;
  s["assembly_seconds"] = assembly;
  s["factorization_seconds"] = factorization;
  s["solve_seconds"] = solve;
  s["newton_cpu_seconds"] = CpuSeconds() - newton_cpu0;
  s["residual_inf"] = r->history.back().primal_inf;
  if (pmp.free_final_time()) s["final_time"] = final_time;
  s["unknowns"] = n;
  s["jacobian_nonzeros"] = static_cast<double>(pmp.jacobian().nonZeros());
  s["residual_evaluations"] = residual_evaluations;
  s["jacobian_evaluations"] = jacobian_evaluations;
}

}  // namespace

const char* ToString(IndirectNewtonOptions::LinearSolver solver) {
  return solver == IndirectNewtonOptions::LinearSolver::kKlu ? "klu" : "umfpack";
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

bool IndirectNewtonOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& why) {
    if (error) *error = why;
    return false;
  };
  if (max_iterations < 0) return fail("max_iterations must be >= 0");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    return fail("tolerance must be finite and > 0");
  if (!(sufficient_decrease > 0.0 && sufficient_decrease < 0.5)) {
    return fail("sufficient_decrease must lie in (0, 0.5)");
  }
  if (!(backtrack > 0.0 && backtrack < 1.0)) return fail("backtrack must lie in (0, 1)");
  if (!(min_step > 0.0 && min_step <= 1.0)) return fail("min_step must lie in (0, 1]");
  if (path_penalty && !(*path_penalty > 0.0 && std::isfinite(*path_penalty))) {
    return fail("path_penalty must be finite and > 0");
  }
  if (regularization && !(*regularization > 0.0 && std::isfinite(*regularization))) {
    return fail("regularization must be finite and > 0");
  }
  if (warm_start != WarmStart::kHamiltonian && !warm_start_options.empty()) {
    return fail("hamiltonian.<key> options need warm_start = hamiltonian");
  }
  return true;
}

IndirectNewton::IndirectNewton(const Options& options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument(std::string(kName) + ": " + error);
}

IndirectNewton::Options IndirectNewton::ParseOptions(
    const std::map<std::string, std::string>& options, const Options& base) {
  Options o = base;
  for (const auto& [key, value] : options) {
    if (key == "max_iterations") {
      o.max_iterations = ParseInt(key, value);
      if (o.max_iterations < 0) BadOption(key, "must be an integer >= 0");
    } else if (key == "tolerance") {
      o.tolerance = ParseDouble(key, value);
      if (!(o.tolerance > 0.0) || !std::isfinite(o.tolerance))
        BadOption(key, "must be finite and > 0");
    } else if (key == "sufficient_decrease") {
      o.sufficient_decrease = ParseDouble(key, value);
      if (!(o.sufficient_decrease > 0.0 && o.sufficient_decrease < 0.5)) {
        BadOption(key, "must lie in (0, 0.5)");
      }
    } else if (key == "backtrack") {
      o.backtrack = ParseDouble(key, value);
      if (!(o.backtrack > 0.0 && o.backtrack < 1.0)) BadOption(key, "must lie in (0, 1)");
    } else if (key == "min_step") {
      o.min_step = ParseDouble(key, value);
      if (!(o.min_step > 0.0 && o.min_step <= 1.0)) BadOption(key, "must lie in (0, 1]");
    } else if (key == "linear_solver") {
      if (value == "umfpack") {
        o.linear_solver = Options::LinearSolver::kUmfpack;
      } else if (value == "klu") {
        o.linear_solver = Options::LinearSolver::kKlu;
      } else {
        BadOption(key, "'" + value + "' is not one of umfpack, klu");
      }
    } else if (key == "warm_start") {
      if (value == "none") {
        o.warm_start = Options::WarmStart::kNone;
      } else if (value == "hamiltonian") {
        o.warm_start = Options::WarmStart::kHamiltonian;
      } else if (value == "ipopt") {
        o.warm_start = Options::WarmStart::kIpopt;
      } else {
        BadOption(key, "'" + value + "' is not one of none, hamiltonian, ipopt");
      }
    } else if (key == "costates") {
      if (value == "fit") {
        o.costates = Options::Costates::kFit;
      } else if (value == "adjoint") {
        o.costates = Options::Costates::kAdjoint;
      } else if (value == "default") {
        o.costates = Options::Costates::kDefault;
      } else {
        BadOption(key, "'" + value + "' is not one of fit, adjoint, default");
      }
    } else if (key == "path_penalty") {
      o.path_penalty = ParseDouble(key, value);
      if (!(*o.path_penalty > 0.0) || !std::isfinite(*o.path_penalty)) {
        BadOption(key, "must be finite and > 0");
      }
    } else if (key == "regularization") {
      o.regularization = ParseDouble(key, value);
      if (!(*o.regularization > 0.0) || !std::isfinite(*o.regularization)) {
        BadOption(key, "must be finite and > 0");
      }
    } else if (key.rfind(kWarmPrefix, 0) == 0 && key.size() > std::string(kWarmPrefix).size()) {
      o.warm_start_options[key.substr(std::string(kWarmPrefix).size())] = value;
    } else {
      BadOption(key, std::string("unknown key (valid: ") + kValidKeys + ")");
    }
  }
  std::string error;
  if (!o.IsValid(&error)) throw std::invalid_argument(std::string(kName) + " options: " + error);
  return o;
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
                                          Mat* P) {
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
  if (how != Options::Costates::kAdjoint) q = FitTerminalCostate(ocp, grid, controls, X, M, c, q);
  P->resize(nx, N + 1);
  for (int k = 0; k <= N; ++k) P->col(k) = M[k] * q + c[k];
}

SolveResult IndirectNewton::Solve(const Ocp& original, const SolveRequest& request) const {
  const Stopwatch watch;
  const Options o = ParseOptions(request.options, options_);
  Target target = Resolve(original, o);
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
  if (o.warm_start != Options::WarmStart::kNone) {
    const bool descent = o.warm_start == Options::WarmStart::kHamiltonian;
    const std::string warm_name = descent ? "hamiltonian" : "ipopt";
    const SolverInfo& info = FindSolver(warm_name);
    SolveRequest warm = request;
    if (descent) {
      warm.terminal = TerminalMode::kPenalty;
      warm.options = o.warm_start_options;
      // The descent reformulates the problem itself; give it the same reformulation.
      if (o.path_penalty && !warm.options.count("path_penalty")) {
        warm.options["path_penalty"] = FormatExact(*o.path_penalty);
      }
      if (o.regularization && !warm.options.count("regularization")) {
        warm.options["regularization"] = FormatExact(*o.regularization);
      }
    } else {
      // Ipopt's defaults on the trapezoid transcription of the same grid and terminal form:
      // the NLP whose KKT conditions are closest to this trapezoidal BVP.
      warm.transcription = "trapezoid";
      warm.options.clear();
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
                                " iterations, J = " + Format(start.objective);
    const int N = request.grid.intervals();
    if (start.states.rows() != ocp.nx() || start.states.cols() != N + 1 ||
        start.state_grid.size() != N + 1 || !ocp.AdmitsFinalTime(start.state_grid.tf()) ||
        start.costates.rows() != ocp.nx() || start.costates.cols() != N + 1 ||
        !start.states.allFinite() || !start.costates.allFinite() ||
        start.controls.nu() != ocp.nu()) {
      SolveResult failed = Result(SolveStatus::kError,
                                  "warm_start_failed",
                                  (target.note.empty() ? "" : target.note + "; ") + summary +
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
      CostatesFromControls(
          ocp, start.state_grid, request.terminal, start.controls, X, Options::Costates::kFit, &P);
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
    const double start_cpu0 = CpuSeconds();
    StartFromControls(ocp, request.grid, request.terminal, guess, &X, &P, o.EffectiveCostates());
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
  const Options o = ParseOptions(request.options, options_);
  Target target = Resolve(original, o);
  if (target.not_applicable) return *target.not_applicable;
  SolveResult r;
  r.solver = kName;
  r.message = target.note;
  r.solver_stats["reformulated"] = target.reformulated ? 1.0 : 0.0;
  RunNewton({*target.ocp, request, o, watch}, X, P, nu, &r);
  return r;
}

}  // namespace ocpb
