#include "solvers/hamiltonian_descent.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "core/option_binding.h"
#include "core/timer.h"

namespace ocpb {
namespace {

// A lower bound on the discrete J of U under forward Euler: the states x_N by exactly
// DiscreteOcp's Euler update (x += h f, same calls, so the same x_N), the running part by
// sum_k h_k m with m <= L. `x` and `f` are scratch of size nx.
// The forward-Euler final state x_N of the controls U (states only: no running cost).
void EulerFinalState(const Ocp& ocp, const TimeGrid& grid, const Mat& U, Vec* x, Vec* f) {
  *x = ocp.x0();
  const int N = grid.intervals();
  for (int k = 0; k < N; ++k) {
    const double h = grid.h(k);
    ocp.Dynamics(grid.t(k), *x, U.col(k), *f);
    *x += h * *f;
  }
}

// sum_k h_k m: the running cost's lower bound over the grid.
double RunningLowerBound(const TimeGrid& grid, double m) {
  double running = 0.0;
  for (int k = 0; k < grid.intervals(); ++k) running += grid.h(k) * m;
  return running;
}

std::string Format(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

SolveResult NotApplicable(const std::string& reason) {
  SolveResult r;
  r.solver = "hamiltonian";
  r.status = SolveStatus::kNotApplicable;
  r.solver_status = "not_applicable";
  r.message = reason;
  r.iterations = 0;
  r.cpu_seconds = 0.0;
  r.wall_seconds = 0.0;
  return r;
}

}  // namespace

double HamiltonianDescent::Direction(const DiscreteOcp& docp,
                                     const Mat& U,
                                     const Mat& X,
                                     const Mat& Lambda,
                                     Mat* D,
                                     Vec* scratch,
                                     double* theta_scale) {
  const Ocp& ocp = docp.ocp();
  const TimeGrid& grid = docp.grid();
  const int N = grid.intervals();
  D->resize(ocp.nu(), N);
  Vec& f = *scratch;
  if (f.size() != ocp.nx()) f.resize(ocp.nx());
  double theta = 0.0, scale = 0.0;
  for (int k = 0; k < N; ++k) {
    const double t = grid.t(k), h = grid.h(k);
    const auto x = X.col(k);
    const auto p = Lambda.col(k + 1);
    const auto u = U.col(k);
    auto d = D->col(k);
    double h_star = 0.0, h_now = 0.0;
    ocp.MinimizeAndCompareHamiltonian(t, x, p, u, d, &h_star, &h_now, f);  // d holds u*_k for now
    theta += h * (h_star - h_now);
    scale += h * (std::abs(h_star) + std::abs(h_now));
    d -= u;
  }
  if (theta_scale) *theta_scale = scale;
  return theta;
}

namespace {

const OptionBinding<HamiltonianDescentOptions>& Binding() {
  static const OptionBinding<HamiltonianDescentOptions> table = [] {
    using O = HamiltonianDescentOptions;
    OptionBinding<O> t("hamiltonian");
    t.Number("alpha", &O::alpha, "Armijo sufficient-decrease constant", OptionBounds::Open(0, 1));
    t.Number("beta", &O::beta, "Armijo step reduction", OptionBounds::Open(0, 1));
    t.Integer(
        "max_iterations", &O::max_iterations, "accepted steps at most", OptionBounds::AtLeast(0));
    t.Integer("max_armijo_exponent",
              &O::max_armijo_exponent,
              "largest Armijo exponent j tried (the paper's rule: stop beyond 50)",
              OptionBounds::AtLeast(0));
    t.Number("theta_tolerance",
             &O::theta_tolerance,
             "stop when |theta| <= this (0: off)",
             OptionBounds::AtLeast(0));
    t.Number("max_cpu_seconds",
             &O::max_cpu_seconds,
             "CPU time limit (inf: none)",
             OptionBounds::Above(0).WithInfinity());
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
    t.Bool("armijo_prefilter",
           &O::armijo_prefilter,
           "reject Armijo trials by a states-only lower bound (same iterates, less work)");
    return t;
  }();
  return table;
}

}  // namespace

bool HamiltonianDescentOptions::IsValid(std::string* error) const {
  return Binding().Check(*this, error);
}

HamiltonianDescent::HamiltonianDescent(const Options& options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument(error);
}

const OptionSchema& HamiltonianDescent::Schema() { return Binding().schema(); }

HamiltonianDescent::Options HamiltonianDescent::ApplyOptions(const OptionMap& options,
                                                             const Options& base) {
  return Binding().ApplyValidated(options, base);
}

SolveResult HamiltonianDescent::Solve(const Ocp& original, const SolveRequest& request) const {
  // ---- the request (throws) ------------------------------------------------------------
  const Options opt = ApplyOptions(request.options, options_);
  const TimeGrid& grid = request.grid;
  if (grid.size() < 2) throw std::invalid_argument("hamiltonian: the request's grid is empty");
  const Ocp& ocp = original;  // the request is checked against the problem as given
  const double tol = 1e-9 * std::max(1.0, std::abs(ocp.tf() - ocp.t0()));
  if (std::abs(grid.t0() - ocp.t0()) > tol || std::abs(grid.tf() - ocp.tf()) > tol) {
    throw std::invalid_argument("hamiltonian: the grid [" + Format(grid.t0()) + ", " +
                                Format(grid.tf()) + "] does not span the horizon [" +
                                Format(ocp.t0()) + ", " + Format(ocp.tf()) + "]");
  }
  if (request.initial_guess && request.initial_guess->nu() != ocp.nu()) {
    throw std::invalid_argument("hamiltonian: the initial guess has " +
                                std::to_string(request.initial_guess->nu()) +
                                " control components, the problem " + std::to_string(ocp.nu()));
  }

  // ---- applicability (status) -------------------------------------------------------------
  if (auto refused = FreeFinalTimeNotApplicable(ocp, "hamiltonian")) return *refused;
  if (request.terminal != TerminalMode::kPenalty) {
    return NotApplicable(
        "the Hamiltonian descent handles terminal constraints only in penalty form "
        "(terminal = penalty); the hard form psi(x(tf)) = 0 is not applicable");
  }
  const Stopwatch clock;
  HamiltonianReformulationOptions reformulation_options;
  reformulation_options.path_penalty = opt.path_penalty;
  reformulation_options.regularization = opt.regularization;
  const std::unique_ptr<Ocp> reformulated =
      original.HamiltonianReformulation(reformulation_options);
  const Ocp& target = reformulated ? *reformulated : original;
  const std::string solved =
      reformulated ? "solved the problem's Hamiltonian reformulation '" + target.name() + "'; "
                   : std::string();
  if (!target.HasHamiltonianMinimizer()) {
    return NotApplicable(solved + "problem '" + target.name() +
                         "' has no pointwise Hamiltonian minimizer (Ocp::MinimizeHamiltonian)");
  }
  if (target.num_path() > 0) {
    return NotApplicable(solved +
                         "path constraints c(t, x, u) <= 0 are not handled by the Hamiltonian "
                         "descent, and the problem offers no reformulation that folds them into L");
  }
  if (target.nu() != original.nu() || target.nx() != original.nx()) {
    throw std::logic_error("problem '" + original.name() +
                           "': its Hamiltonian reformulation changed nx or nu");
  }

  const DiscreteOcp docp(target, grid, request.integrator, TerminalMode::kPenalty);
  const int N = grid.intervals(), nu = target.nu(), nx = target.nx();
  const ControlSet& set = target.control_set();

  // Workspace, allocated once.
  Mat U = request.initial_guess ? request.initial_guess->SampleIntervals(grid)
                                : DefaultInitialGuess(target, grid).values();
  for (int k = 0; k < N; ++k) set.Project(U.col(k));
  Mat trial(nu, N), D(nu, N), X(nx, N + 1), X_trial(nx, N + 1), Lambda(nx, N + 1), G(nu, N);
  Vec f(nx), x_bound(nx), f_bound(nx);
  const std::optional<double> lower_bound =
      opt.armijo_prefilter && request.integrator == Integrator::kEuler
          ? target.RunningCostLowerBound()
          : std::nullopt;
  // The prefilter's bound J(U') >= sum_k h m + Phi(x_N(U')). With affine dynamics,
  // x_N(U + s D) = x_N(U) + s (x_N(U + D) - x_N(U)) exactly, so one states-only simulation per
  // iteration serves every trial; otherwise each trial simulates its states.
  const double running_bound = lower_bound ? RunningLowerBound(grid, *lower_bound) : 0.0;
  const bool affine_final_state = lower_bound && target.HasAffineDynamics();
  Vec final_step(nx);

  SolveResult result;
  result.solver = "hamiltonian";
  result.history.reserve(static_cast<size_t>(opt.max_iterations) + 1);

  double J = docp.Simulate(U, &X);
  int iteration = 0, last_j = -1, simulations = 1, rejections = 0;
  double theta = NAN;
  bool have_costates = false;
  auto stop = [&](SolveStatus status, const char* code, const std::string& why) {
    result.status = status;
    result.solver_status = code;
    result.message = why;
  };

  if (!std::isfinite(J)) {
    stop(SolveStatus::kNumericalFailure,
         "nonfinite_cost",
         "the cost of the starting control is not finite");
    result.history.push_back({0, J, NAN, -1, NAN, NAN, clock.cpu()});
  } else {
    for (;;) {
      docp.Adjoint(U, X, &Lambda, &G);
      have_costates = true;
      double theta_scale = 0.0;
      theta = Direction(docp, U, X, Lambda, &D, &f, &theta_scale);
      result.history.push_back({iteration, J, theta, last_j, NAN, NAN, clock.cpu()});

      if (!std::isfinite(theta)) {
        stop(SolveStatus::kNumericalFailure,
             "nonfinite_theta",
             "theta is not finite at iteration " + std::to_string(iteration));
        break;
      }
      // At a stationary point every term H(u*) - H(u) is zero up to rounding, and their sum can
      // come out as +1e-17: that is convergence to machine precision, not a failed minimizer.
      const double roundoff = 64.0 * std::numeric_limits<double>::epsilon() * theta_scale;
      if (theta > 0.0 && theta <= roundoff) {
        stop(SolveStatus::kConverged,
             "theta_at_roundoff",
             "theta = " + Format(theta) + " is at the rounding level " + Format(roundoff) +
                 " of the Hamiltonian sums: stationary to machine precision");
        break;
      }
      if (theta > 0.0) {
        stop(SolveStatus::kError,
             "theta_positive",
             "theta = " + Format(theta) +
                 " > 0: the problem's Hamiltonian minimizer did not minimize H");
        break;
      }
      if (std::abs(theta) <= opt.theta_tolerance) {
        stop(SolveStatus::kConverged,
             "theta_below_tolerance",
             "|theta| = " + Format(std::abs(theta)) + " <= " + Format(opt.theta_tolerance));
        break;
      }
      if (iteration >= opt.max_iterations) {
        stop(SolveStatus::kMaxIterations,
             "max_iterations",
             "reached max_iterations = " + std::to_string(opt.max_iterations));
        break;
      }
      if (clock.cpu() >= opt.max_cpu_seconds) {
        stop(SolveStatus::kMaxTime,
             "max_cpu_seconds",
             "reached max_cpu_seconds = " + Format(opt.max_cpu_seconds));
        break;
      }
      // Armijo search.
      if (affine_final_state) {
        trial.noalias() = U + D;
        EulerFinalState(target, grid, trial, &final_step, &f_bound);
        final_step -= X.col(N);
      }
      int accepted = -1;
      double step = 1.0, J_trial = NAN;
      for (int j = 0; j <= opt.max_armijo_exponent; ++j, step *= opt.beta) {
        if (lower_bound) {
          const double threshold = J + opt.alpha * step * theta;
          if (affine_final_state) {
            x_bound = X.col(N) + step * final_step;
          } else {
            trial.noalias() = U + step * D;
            EulerFinalState(target, grid, trial, &x_bound, &f_bound);
          }
          const double bound =
              running_bound + target.TerminalObjective(x_bound, TerminalMode::kPenalty);
          if (bound > threshold + 1e-10 * std::max(1.0, std::abs(threshold))) {
            ++rejections;  // J(trial) >= bound > threshold: the Armijo test fails
            continue;
          }
        }
        trial.noalias() = U + step * D;
        J_trial = docp.Simulate(trial, &X_trial);
        ++simulations;
        if (std::isfinite(J_trial) && J_trial - J <= opt.alpha * step * theta) {
          accepted = j;
          break;
        }
      }
      if (accepted < 0) {
        stop(SolveStatus::kStepTooSmall,
             "armijo_exponent_exceeded",
             "no Armijo exponent j <= " + std::to_string(opt.max_armijo_exponent) +
                 " gave sufficient decrease at iteration " + std::to_string(iteration));
        break;
      }
      U.swap(trial);
      X.swap(X_trial);
      J = J_trial;
      last_j = accepted;
      ++iteration;
    }
  }

  if (std::isfinite(theta)) {
    result.message += "; final J = " + Format(J) + ", theta = " + Format(theta);
  }
  result.message = solved + result.message;
  result.controls = ControlTrajectory::PiecewiseConstant(grid, U);
  result.state_grid = grid;
  result.states = std::move(X);
  if (have_costates) {
    result.costates = std::move(Lambda);
    result.costate_source = "discrete adjoint (" + std::string(ToString(request.integrator)) + ")";
  }
  result.objective = J;
  result.solver_stats["final_theta"] = theta;
  result.solver_stats["simulations"] = simulations;
  result.solver_stats["prefilter_rejections"] = rejections;
  result.solver_stats["reformulated"] = reformulated ? 1.0 : 0.0;
  result.iterations = iteration;
  result.cpu_seconds = clock.cpu();
  result.wall_seconds = clock.wall();
  return result;
}

}  // namespace ocpb
