#include "solvers/hamiltonian_descent.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/option_binding.h"
#include "core/timer.h"
#include "solvers/descent_loop.h"
#include "solvers/descent_passes.h"
#include "solvers/hamiltonian_target.h"
#include "solvers/message_number.h"

namespace ocpb {
namespace {

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

const OptionBinding<HamiltonianDescentOptions>& DescentBinding() {
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
  return DescentBinding().Check(*this, error);
}

HamiltonianDescent::HamiltonianDescent(const Options& options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument(error);
}

const OptionSchema& HamiltonianDescent::Schema() { return DescentBinding().schema(); }

HamiltonianDescent::Options HamiltonianDescent::ApplyOptions(const OptionMap& options,
                                                             const Options& base) {
  return DescentBinding().ApplyValidated(options, base);
}

namespace {

// The request's checks that throw (options are parsed by the caller).
void CheckRequest(const Ocp& ocp, const SolveRequest& request) {
  const TimeGrid& grid = request.grid;
  if (grid.size() < 2) throw std::invalid_argument("hamiltonian: the request's grid is empty");
  if (const std::string off = ocp.GridOffHorizon(grid, Ocp::HorizonEnd::kNominal); !off.empty()) {
    throw std::invalid_argument("hamiltonian: " + off);
  }
  if (request.initial_guess && request.initial_guess->nu() != ocp.nu()) {
    throw std::invalid_argument("hamiltonian: the initial guess has " +
                                std::to_string(request.initial_guess->nu()) +
                                " control components, the problem " + std::to_string(ocp.nu()));
  }
}

// The problem the descent solves (the original or its Hamiltonian reformulation), or the
// reason it cannot.
HamiltonianTarget ResolveDescentTarget(const Ocp& original,
                                       const SolveRequest& request,
                                       const HamiltonianDescentOptions& opt) {
  if (auto refused = FeaturesNotApplicable(original, "hamiltonian", ProblemFeatures())) {
    HamiltonianTarget t;
    t.not_applicable = std::move(refused);
    return t;
  }
  if (request.terminal != TerminalMode::kPenalty) {
    HamiltonianTarget t;
    t.not_applicable = NotApplicable(
        "the Hamiltonian descent handles terminal constraints only in penalty form "
        "(terminal = penalty); the hard form psi(x(tf)) = 0 is not applicable");
    return t;
  }
  HamiltonianReformulationOptions reformulation_options;
  reformulation_options.path_penalty = opt.path_penalty;
  reformulation_options.regularization = opt.regularization;
  HamiltonianTarget t = ResolveHamiltonianTarget(original, reformulation_options);
  if (!t.ocp->HasHamiltonianMinimizer()) {
    t.not_applicable = NotApplicable(t.NotePrefix() + "problem '" + t.ocp->name() +
                                     "' has no pointwise Hamiltonian minimizer "
                                     "(Ocp::MinimizeHamiltonian)");
  } else if (t.ocp->num_path() > 0) {
    t.not_applicable =
        NotApplicable(t.NotePrefix() +
                      "path constraints c(t, x, u) <= 0 are not handled by the Hamiltonian "
                      "descent, and the problem offers no reformulation that folds them into L");
  }
  return t;
}

}  // namespace

SolveResult HamiltonianDescent::Solve(const Ocp& original, const SolveRequest& request) const {
  const Options opt = ApplyOptions(request.options, options_);
  CheckRequest(original, request);
  const Stopwatch clock;
  HamiltonianTarget target = ResolveDescentTarget(original, request, opt);
  if (target.not_applicable) return *target.not_applicable;
  const Ocp& ocp = *target.ocp;
  const TimeGrid& grid = request.grid;
  const DiscreteOcp docp(ocp, grid, request.integrator, TerminalMode::kPenalty);

  Mat U0 = request.initial_guess ? request.initial_guess->SampleIntervals(grid)
                                 : DefaultInitialGuess(ocp, grid).values();
  for (int k = 0; k < grid.intervals(); ++k) ocp.control_set().Project(U0.col(k));
  DescentPasses passes(docp, opt.armijo_prefilter);
  passes.Start(U0);

  SolveResult result;
  result.solver = "hamiltonian";
  result.history.reserve(static_cast<size_t>(opt.max_iterations) + 1);
  DescentLoopOptions loop;
  loop.armijo = ArmijoRule{opt.alpha, opt.beta, opt.max_armijo_exponent};
  loop.max_iterations = opt.max_iterations;
  loop.theta_tolerance = opt.theta_tolerance;
  loop.max_cpu_seconds = opt.max_cpu_seconds;
  const DescentLoopOutcome outcome = RunDescentLoop(loop, clock, &passes, &result.history);
  const double theta = outcome.theta;
  const bool have_costates = outcome.have_costates;
  result.status = outcome.stop.status;
  result.solver_status = outcome.stop.code;
  result.message = outcome.stop.why;
  result.iterations = outcome.iterations;

  const double J = passes.J();
  if (std::isfinite(theta)) {
    result.message += "; final J = " + MessageNumber(J) + ", theta = " + MessageNumber(theta);
  }
  result.message = target.NotePrefix() + result.message;
  const DescentWork work = passes.work();
  result.controls = ControlTrajectory::PiecewiseConstant(grid, passes.TakeU());
  result.state_grid = grid;
  result.states = passes.TakeX();
  if (have_costates) {
    result.costates = passes.TakeLambda();
    result.costate_source = "discrete adjoint (" + std::string(ToString(request.integrator)) + ")";
  }
  result.objective = J;
  result.solver_stats["final_theta"] = theta;
  result.solver_stats["simulations"] = work.simulations;
  result.solver_stats["prefilter_rejections"] = work.rejections;
  result.solver_stats["constant_bound_rejections"] = work.constant_bound_rejections;
  result.solver_stats["pointwise_bound_rejections"] = work.pointwise_bound_rejections;
  result.solver_stats["partial_rejections"] = work.partial_rejections;
  result.solver_stats["cost_point_evaluations"] = static_cast<double>(work.cost_points);
  result.solver_stats["reformulated"] = target.reformulated ? 1.0 : 0.0;
  result.cpu_seconds = clock.cpu();
  result.wall_seconds = clock.wall();
  return result;
}

}  // namespace ocpb
