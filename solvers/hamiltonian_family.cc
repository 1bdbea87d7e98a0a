#include "solvers/hamiltonian_family.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/discrete_ocp.h"
#include "core/rk_tableau.h"
#include "core/stage_rk_ocp.h"
#include "solvers/constant_costate_start.h"
#include "solvers/descent_rate.h"
#include "solvers/euler_costate_fit.h"
#include "solvers/grid_sequence.h"
#include "solvers/hamiltonian_target.h"
#include "solvers/indirect_newton.h"
#include "solvers/message_number.h"
#include "solvers/stage_descent_passes.h"
#include "solvers/stage_newton.h"

namespace ocpb {
namespace {

void CheckRequest(const std::string& name, const Ocp& ocp, const SolveRequest& request) {
  const TimeGrid& grid = request.grid;
  if (grid.size() < 2) throw std::invalid_argument(name + ": the request's grid is empty");
  if (const std::string off = ocp.GridOffHorizon(grid, Ocp::HorizonEnd::kNominal); !off.empty()) {
    throw std::invalid_argument(name + ": " + off);
  }
  if (request.initial_guess && request.initial_guess->nu() != ocp.nu()) {
    throw std::invalid_argument(name + ": the initial guess has the wrong number of controls");
  }
}

const char* SchemeName(HamiltonianFamilyOptions::Scheme scheme) {
  switch (scheme) {
    case HamiltonianFamilyOptions::Scheme::kRk2:
      return "rk2";
    case HamiltonianFamilyOptions::Scheme::kRk4:
      return "rk4";
    case HamiltonianFamilyOptions::Scheme::kEuler:
      break;
  }
  return "euler";
}

RkTableau SchemeTableau(HamiltonianFamilyOptions::Scheme scheme) {
  switch (scheme) {
    case HamiltonianFamilyOptions::Scheme::kRk2:
      return RkTableau::Heun();
    case HamiltonianFamilyOptions::Scheme::kRk4:
      return RkTableau::Classical4();
    case HamiltonianFamilyOptions::Scheme::kEuler:
      break;
  }
  return RkTableau::ForwardEuler();
}

// The stage controls U (nu x sN) as a control trajectory: per interval the polynomial through
// the stage controls at their abscissae c_i (equal c_i averaged), projected onto U.
ControlTrajectory StageControls(const TimeGrid& grid,
                                const RkTableau& tableau,
                                const Mat& U,
                                const ControlSet& set) {
  const int s = tableau.stages, N = grid.intervals(), nu = static_cast<int>(U.rows());
  // The distinct abscissae and, per interval, the mean control at each.
  std::vector<double> nodes;
  std::vector<int> which(static_cast<size_t>(s));
  for (int i = 0; i < s; ++i) {
    const double c = tableau.c[static_cast<size_t>(i)];
    size_t m = 0;
    while (m < nodes.size() && nodes[m] != c) ++m;
    if (m == nodes.size()) nodes.push_back(c);
    which[static_cast<size_t>(i)] = static_cast<int>(m);
  }
  const int m = static_cast<int>(nodes.size());
  Mat V = Mat::Zero(nu, m * N);
  std::vector<int> count(static_cast<size_t>(m), 0);
  for (int i = 0; i < s; ++i) ++count[static_cast<size_t>(which[static_cast<size_t>(i)])];
  for (int k = 0; k < N; ++k) {
    for (int i = 0; i < s; ++i) {
      const int j = which[static_cast<size_t>(i)];
      V.col(k * m + j) += U.col(k * s + i) / count[static_cast<size_t>(j)];
    }
  }
  auto fn = [grid, nodes, V, m, set](double t, ControlTrajectory::Side side, VecRef u) {
    int k = grid.Locate(t);
    if (side == ControlTrajectory::Side::kLeft && k > 0 && t <= grid.t(k)) --k;
    const double tau = std::clamp((t - grid.t(k)) / grid.h(k), 0.0, 1.0);
    u.setZero();
    for (int j = 0; j < m; ++j) {
      double l = 1.0;
      for (int q = 0; q < m; ++q) {
        if (q != j)
          l *= (tau - nodes[static_cast<size_t>(q)]) /
               (nodes[static_cast<size_t>(j)] - nodes[static_cast<size_t>(q)]);
      }
      u += l * V.col(k * m + j);
    }
    set.Project(u);
  };
  return ControlTrajectory::Custom(
      nu,
      grid,
      fn,
      std::string(tableau.name) +
          " stage controls: per interval the polynomial through them at their c_i, projected "
          "onto U");
}

// The problem the descent works on (before any augmented Lagrangian): the original, or its
// Hamiltonian reformulation, or the reason neither applies.
HamiltonianTarget ResolveFamilyTarget(const std::string& name,
                                      const Ocp& original,
                                      const SolveRequest& request,
                                      const HamiltonianFamilyOptions& o) {
  const bool path_al = o.path == HamiltonianFamilyOptions::PathConstraints::kAugmentedLagrangian &&
                       original.num_path() > 0;
  // The outer loop takes the path constraints itself; otherwise the problem's reformulation
  // (path penalty, or the regularization of an H linear in u), as the paper's method.
  HamiltonianReformulationOptions ro;
  ro.path_penalty = o.path_penalty;
  ro.regularization = o.regularization;
  HamiltonianTarget t = ResolveHamiltonianTarget(original, ro, /*reformulate=*/!path_al);
  auto refuse = [&](const std::string& why) {
    t.not_applicable = NotApplicableResult(name, t.NotePrefix() + why);
    return std::move(t);
  };
  ProblemFeatures takes;
  takes.free_final_time = true;
  takes.free_initial_state = true;  // forward Euler only (below)
  if (const std::string why = UnsupportedFeature(original, name, takes); !why.empty()) {
    return refuse(why);
  }
  if (!t.ocp->HasHamiltonianMinimizer()) {
    return refuse("problem '" + t.ocp->name() + "' has no pointwise Hamiltonian minimizer");
  }
  if (t.ocp->num_path() > 0 && !path_al) {
    return refuse(
        "path constraints c <= 0 remain and the problem offers no reformulation; the "
        "augmented-Lagrangian option (path = kAugmentedLagrangian) handles them");
  }
  if (o.scheme != HamiltonianFamilyOptions::Scheme::kEuler) {
    const std::string scheme = std::string("scheme=") + SchemeName(o.scheme);
    if (request.integrator != Integrator::kEuler) {
      return refuse(scheme + " replaces the request's integrator (" + ToString(request.integrator) +
                    "): request integrator euler");
    }
    if (o.polish && t.ocp->free_final_time()) {
      return refuse(scheme +
                    ": the polish (projected Newton on the stage controls) keeps the horizon "
                    "fixed; a free final time needs scheme=euler");
    }
    if (path_al) {
      return refuse(scheme +
                    ": path constraints by the augmented-Lagrangian loop need "
                    "scheme=euler (the loop's path multipliers pair with the grid's "
                    "intervals; path = reformulation runs)");
    }
  }
  if (original.HasFreeInitialState() && o.scheme != HamiltonianFamilyOptions::Scheme::kEuler) {
    return refuse(std::string("scheme=") + SchemeName(o.scheme) +
                  ": a free initial state (or static parameters) needs scheme=euler (the stage "
                  "schemes' descent and polish do not carry x(t0) as a variable yet)");
  }
  if (original.HasFreeInitialState() && request.integrator != Integrator::kEuler) {
    return refuse(
        "a free initial state (or static parameters) needs forward Euler (the descent moves "
        "x(t0) on the Euler grid only)");
  }
  if (t.ocp->free_final_time() && request.integrator != Integrator::kEuler) {
    return refuse("a free final time needs forward Euler (the exact dJ/dT is Euler's)");
  }
  if (t.ocp->free_final_time() && path_al) {
    return refuse("a free final time with path constraints in the outer loop is not supported");
  }
  if (o.polish && path_al) {
    return refuse("the Newton polish takes no path constraints (use path = kReformulation)");
  }
  return t;
}

// What every phase of one Solve shares.
struct FamilyRun {
  const std::string& name;
  const HamiltonianFamilyOptions& o;
  const Ocp& original;
  const HamiltonianTarget& target;
  const Stopwatch& clock;
};

// A solve on one grid, and whether its polish (when on) converged.
struct GridSolve {
  SolveResult result;
  bool polished = false;
  /// The polish's last Newton attempt (its own states and costates on the grid, whether it
  /// converged or not); empty when Newton did not run.
  SolveResult last_newton;
};

IndirectNewtonOptions PolishNewtonOptions(const HamiltonianFamilyOptions& o) {
  IndirectNewtonOptions no;
  no.scheme = IndirectNewtonOptions::Scheme::kEuler;
  no.max_iterations = o.newton_max_iterations;
  no.tolerance = o.newton_tolerance;
  no.linear_solver = o.newton_linear_solver;
  no.stall_steps = o.newton_stall_steps;
  no.backtrack = o.newton_backtrack;
  no.sufficient_decrease = o.newton_sufficient_decrease;
  no.path_penalty = o.path_penalty;  // SolveFrom resolves the same reformulation
  no.regularization = o.regularization;
  return no;
}

// `options` with max_cpu_seconds = what is left of `limit` on `clock` (at least the smallest
// positive double: Newton then stops at its first test).
IndirectNewtonOptions WithCpuLeft(IndirectNewtonOptions options,
                                  double limit,
                                  const Stopwatch& clock) {
  if (std::isfinite(limit)) {
    options.max_cpu_seconds = std::max(limit - clock.cpu(), std::numeric_limits<double>::min());
  }
  return options;
}

// The descent loop's options from the family's, with the given stopping tolerance on theta.
DescentLoopOptions FamilyLoopOptions(const HamiltonianFamilyOptions& o, double theta_tolerance) {
  DescentLoopOptions loop;
  loop.armijo = ArmijoRule{o.alpha, o.beta, o.max_armijo_exponent};
  loop.max_iterations = o.max_iterations;
  loop.relative_theta_tolerance = theta_tolerance;
  loop.max_cpu_seconds = o.max_cpu_seconds;
  if (o.direction == HamiltonianFamilyOptions::Direction::kProximal) loop.proximal = o.proximal;
  return loop;
}

// The augmented-Lagrangian loop's outcome in the result's stats: its outer iterations, final
// residuals, penalty and terminal multipliers (nu_i), on the Euler grid and the stage schemes.
void RecordAugmentedLagrangianOutcome(const AugmentedLagrangianOutcome& outcome,
                                      const AugmentedLagrangianOcp& al,
                                      std::map<std::string, double>* stats) {
  (*stats)["outer_iterations"] = outcome.outer_iterations;
  (*stats)["terminal_residual"] = outcome.terminal_residual;
  (*stats)["path_violation"] = outcome.path_violation;
  (*stats)["penalty"] = al.rho();
  for (int i = 0; i < al.terminal_multipliers().size(); ++i) {
    (*stats)["nu_" + std::to_string(i)] = al.terminal_multipliers()[i];
  }
}

// Newton's outcome in the result: its status and its own stats (prefixed "newton_"), its final
// residual.
void RecordNewtonOutcome(const SolveResult& n, SolveResult* r) {
  auto& stats = r->solver_stats;
  if (!n.history.empty()) stats["newton_residual_inf"] = n.history.back().primal_inf;
  for (const auto& [key, value] : n.solver_stats) stats["newton_" + key] = value;
  r->status = n.status;
  r->solver_status = n.solver_status;
}

// Newton's solution as the result's: trajectory, costates, J, and T for a free final time.
void TakeNewtonSolution(const SolveResult& n, SolveResult* r) {
  r->controls = n.controls;
  r->state_grid = n.state_grid;
  r->states = n.states;
  r->costates = n.costates;
  r->objective = n.objective;
  const auto final_time = n.solver_stats.find("final_time");
  if (final_time != n.solver_stats.end()) r->solver_stats["final_time"] = final_time->second;
}

// J of `problem` in the request's terminal form (hard: no penalty, no multiplier terms) at the
// passes' iterate: its controls, and its x(t0) for a free initial state.
double DiscreteObjective(const Ocp& problem,
                         const SolveRequest& request,
                         const DescentPasses& passes) {
  DiscreteOcp docp(problem, passes.grid(), request.integrator, request.terminal);
  docp.SetInitialState(passes.x0());
  return docp.Simulate(passes.U(), nullptr);
}

// The polish stage after the descent: fitted costates, Newton on the Euler maximum principle,
// and on failure more descent and another attempt (polish_attempts). Updates *r and keeps the
// last attempt's result in *last_newton; true when Newton converged.
bool Polish(const FamilyRun& run,
            const Ocp& problem,
            const SolveRequest& request,
            DescentLoopOptions loop,
            DescentPasses* passes,
            SolveResult* r,
            SolveResult* last_newton) {
  const HamiltonianFamilyOptions& o = run.o;
  const Stopwatch& clock = run.clock;
  auto& stats = r->solver_stats;
  const IndirectNewtonOptions no = PolishNewtonOptions(o);
  int descent_iterations = static_cast<int>(stats["descent_iterations"]);
  int newton_iterations = 0;
  double newton_cpu = 0.0;
  for (int attempt = 1;; ++attempt) {
    if (!std::isfinite(passes->J()) || !passes->X().allFinite()) return false;
    const double cpu0 = clock.cpu();
    SolveRequest newton_request;
    newton_request.grid = passes->grid();
    newton_request.terminal = request.terminal;
    Mat X = passes->X();
    bool adjoint_start = false;
    Mat P =
        FitEulerCostates(problem, passes->grid(), request.terminal, passes->U(), X, &adjoint_start);
    stats["start_adjoint_fallback"] = adjoint_start ? 1.0 : 0.0;
    if (o.polish_constant_costate_start) {
      const ConstantCostateStartOutcome start =
          ConstantCostateStart(problem, passes->grid(), request.terminal, passes->U(), &X, &P);
      stats["start_constant_costates"] = start.solved;
      stats["start_constant_costate_evaluations"] += start.evaluations;
    }
    *last_newton = IndirectNewton(WithCpuLeft(no, o.max_cpu_seconds, clock))
                       .SolveFrom(run.original, newton_request, X, P);
    const SolveResult& n = *last_newton;
    newton_cpu += clock.cpu() - cpu0;
    newton_iterations += n.iterations;
    const int offset = static_cast<int>(r->history.size());
    for (IterationRecord rec : n.history) {
      rec.iteration = offset + rec.iteration;
      rec.cpu_seconds += cpu0;
      r->history.push_back(rec);
    }
    stats["newton_attempts"] = attempt;
    stats["newton_iterations"] = newton_iterations;
    stats["newton_cpu_seconds"] = newton_cpu;
    RecordNewtonOutcome(n, r);
    r->iterations = descent_iterations + newton_iterations;
    r->message += "; Newton " + std::to_string(attempt) + " (Euler maximum principle, " +
                  (adjoint_start ? "adjoint costates (Mayer cost: the fit is degenerate)"
                                 : "fitted costates") +
                  ", after " + std::to_string(descent_iterations) + " descent steps): " + n.message;
    const bool converged = n.status == SolveStatus::kConverged &&
                           n.states.cols() == passes->grid().size() &&
                           n.controls.nu() == problem.nu();
    if (converged) {
      TakeNewtonSolution(n, r);
      return true;
    }
    // The result keeps the descent's iterate; continue the descent (its budget doubles) unless
    // the attempts, the CPU limit or the descent itself are done.
    if (attempt >= o.polish_attempts || clock.cpu() >= o.max_cpu_seconds ||
        descent_iterations == 0) {
      return false;
    }
    loop.max_iterations = descent_iterations;
    // Rows are numbered by their place in the history (descent and Newton rows interleave).
    const double descent_cpu0 = clock.cpu();
    const DescentLoopOutcome more = RunDescentLoop(loop,
                                                   clock,
                                                   passes,
                                                   &r->history,
                                                   static_cast<int>(r->history.size()) - 1,
                                                   -1,
                                                   /*record_first=*/false);
    stats["descent_cpu_seconds"] += clock.cpu() - descent_cpu0;
    if (more.iterations == 0) return false;  // the descent cannot move: Newton would start alike
    descent_iterations += more.iterations;
    if (loop.proximal && std::isfinite(more.eps)) loop.proximal->initial_eps = more.eps;
    stats["descent_iterations"] = descent_iterations;
    stats["final_theta"] = more.theta;
    r->controls = ControlTrajectory::PiecewiseConstant(passes->grid(), passes->U());
    r->state_grid = passes->grid();
    r->states = passes->X();
    r->costates = passes->Lambda();
    r->objective = DiscreteObjective(problem, request, *passes);
    r->iterations = descent_iterations + newton_iterations;
  }
}

// A descent stopped by its iteration or CPU limit: the rate it was converging at and the steps
// that rate still needed to the loop's tolerance (DescentRateNote); "" for any other stop.
std::string LimitRateNote(const DescentLoopOptions& loop,
                          const DescentStop& stop,
                          double J,
                          const std::vector<IterationRecord>& history,
                          std::size_t begin = 0) {
  if (stop.code != "max_iterations" && stop.code != "max_cpu_seconds") return "";
  const double target =
      std::max(loop.theta_tolerance, loop.relative_theta_tolerance * (1.0 + std::abs(J)));
  return DescentRateNote(MeasureDescentRate(history, begin, target), target);
}

// The polish on a Runge-Kutta scheme's stage controls (solvers/stage_newton.h): projected
// truncated Newton on the discrete problem from the descent's controls U, in the hard form inside
// a multiplier loop. Its iterate becomes the result's whether it converged or not (its line
// search accepts decreases of J, or J_A, up to J's rounding); the status and message say which.
// True when converged.
bool StagePolish(const FamilyRun& run,
                 const SolveRequest& request,
                 const TimeGrid& grid,
                 const RkTableau& tableau,
                 Mat U,
                 int descent_iterations,
                 SolveResult* r) {
  const HamiltonianFamilyOptions& o = run.o;
  const Ocp& problem = *run.target.ocp;
  auto& stats = r->solver_stats;
  StageNewtonOptions no;
  no.max_iterations = o.newton_max_iterations;
  no.tolerance = o.newton_tolerance;
  no.backtrack = o.newton_backtrack;
  no.sufficient_decrease = o.newton_sufficient_decrease;
  const CpuLimit limit{&run.clock, o.max_cpu_seconds};
  const double cpu0 = run.clock.cpu();
  const bool hard = request.terminal == TerminalMode::kHard && problem.num_terminal() > 0;
  StageAugmentedLagrangianOutcome a;
  Mat X, Lambda, Y, P, G;
  if (hard) {
    AugmentedLagrangianOcp al(problem, grid);
    const StageRkOcp srk(al, grid, tableau, TerminalMode::kHard);
    const AugmentedLagrangianRule& rule = o.augmented_lagrangian;
    // Newton's tolerance is the polish's on psi too (as the Euler polish's ||F||_inf, which
    // holds psi): with the loop's 1e-8 the J of the double integrator stayed 1.3e-8 off.
    a = StageNewtonAugmentedLagrangian(srk,
                                       &al,
                                       problem.control_set(),
                                       no,
                                       rule.initial_penalty,
                                       rule.penalty_growth,
                                       rule.max_penalty,
                                       o.newton_tolerance,
                                       rule.max_outer_iterations,
                                       limit,
                                       &U);
    stats["outer_iterations"] = a.outer_iterations;
    stats["terminal_residual"] = a.terminal_residual;
    stats["penalty"] = al.rho();
    for (int i = 0; i < a.multipliers.size(); ++i) {
      stats["nu_" + std::to_string(i)] = a.multipliers[i];
    }
    // Costates of the hard form: al holds the last solve's (nu, rho), so lambda_N = grad phi +
    // psi_x^T (nu + rho psi) = grad phi + psi_x^T multipliers.
    if (std::isfinite(srk.Simulate(U, &X))) srk.Adjoint(U, X, &Lambda, &Y, &P, &G);
  } else {
    const StageRkOcp srk(problem, grid, tableau, request.terminal);
    a = SingleSolveOutcome(StageNewton(srk, problem.control_set(), no, limit, &U));
    if (std::isfinite(srk.Simulate(U, &X))) srk.Adjoint(U, X, &Lambda, &Y, &P, &G);
  }
  stats["newton_iterations"] = a.newton_iterations;
  stats["newton_hessian_products"] = a.hessian_products;
  stats["newton_cg_iterations"] = a.cg_iterations;
  stats["newton_residual_inf"] = a.last.residual;
  stats["newton_cpu_seconds"] = run.clock.cpu() - cpu0;
  r->status = a.converged                                       ? SolveStatus::kConverged
              : a.code == "max_cpu_seconds"                     ? SolveStatus::kMaxTime
              : a.code == "line_search" || a.code == "rounding" ? SolveStatus::kStepTooSmall
              : a.code == "not_finite"                          ? SolveStatus::kNumericalFailure
                                                                : SolveStatus::kMaxIterations;
  r->solver_status = "stage_newton_" + a.code;
  r->iterations = descent_iterations + a.newton_iterations;
  r->message += "; Newton (projected, truncated, on the " + std::string(SchemeName(o.scheme)) +
                " stage controls" + (hard ? ", in a multiplier loop" : "") + ", after " +
                std::to_string(descent_iterations) + " descent steps): " + a.why;
  if (X.allFinite() && X.cols() == grid.size()) {
    r->controls = StageControls(grid, tableau, U, problem.control_set());
    r->states = X;
    r->costates = Lambda;
    r->objective = StageRkOcp(problem, grid, tableau, request.terminal).Simulate(U, nullptr);
    r->history.push_back({static_cast<int>(r->history.size()),
                          r->objective,
                          NAN,
                          -1,
                          hard ? stats["terminal_residual"] : NAN,
                          a.last.residual,
                          run.clock.cpu()});
  } else {
    r->message += " (the controls are the descent's)";
  }
  return a.converged;
}

// The family's descent on a Runge-Kutta scheme with one control per stage (scheme rk2, rk4;
// ResolveFamilyTarget left no path constraints for the outer loop and no polish with a free
// final time): the penalty form, or the hard terminal form by the outer loop on the terminal
// multipliers; then the polish when it is on (StagePolish).
GridSolve SolveOnStageGrid(const FamilyRun& run, const SolveRequest& request) {
  const HamiltonianFamilyOptions& o = run.o;
  const Stopwatch& clock = run.clock;
  const double cpu_start = clock.cpu();
  const Ocp& problem = *run.target.ocp;
  // The hard form by the outer loop, unless Newton finishes: then, as on Euler, the descent runs
  // on the penalty form and the polish solves the hard form.
  const bool use_al = request.terminal == TerminalMode::kHard && !o.polish;
  std::unique_ptr<AugmentedLagrangianOcp> al;
  if (use_al) al = std::make_unique<AugmentedLagrangianOcp>(problem, request.grid);
  const Ocp& descended = use_al ? static_cast<const Ocp&>(*al) : problem;
  const StageRkOcp srk(descended,
                       request.grid,
                       SchemeTableau(o.scheme),
                       use_al ? TerminalMode::kHard : TerminalMode::kPenalty);
  // The outer loop changes the terminal cost only: the problem's proximal minimizer holds.
  StageDescentPasses passes(srk, dynamic_cast<const ProximalHamiltonianMinimizer*>(&problem));
  if (problem.free_final_time()) {
    passes.EnableFreeFinalTime(problem.free_final_time()->lower,
                               problem.free_final_time()->upper,
                               o.free_time_initial_fraction);
  }
  // The initial control of each interval at every one of its stages.
  const Mat U0 = request.initial_guess ? request.initial_guess->SampleIntervals(request.grid)
                                       : DefaultInitialGuess(problem, request.grid).values();
  const int s = srk.stages(), N = srk.intervals();
  Mat U(U0.rows(), s * N);
  for (int k = 0; k < N; ++k) {
    for (int i = 0; i < s; ++i) {
      U.col(k * s + i) = U0.col(k);
      problem.control_set().Project(U.col(k * s + i));
    }
  }
  passes.Start(U);

  const DescentLoopOptions loop =
      FamilyLoopOptions(o, o.polish ? o.polish_switch : o.relative_theta_tolerance);

  GridSolve out;
  SolveResult& r = out.result;
  r.solver = run.name;
  auto& stats = r.solver_stats;
  DescentLoopOutcome outcome;
  if (use_al) {
    const AugmentedLagrangianOutcome al_outcome =
        RunAugmentedLagrangian(o.augmented_lagrangian, loop, clock, al.get(), &passes, &r.history);
    outcome.stop = al_outcome.stop;
    outcome.iterations = al_outcome.descent_iterations;
    outcome.theta = al_outcome.theta;
    outcome.have_costates = al_outcome.have_costates;
    RecordAugmentedLagrangianOutcome(al_outcome, *al, &stats);
  } else {
    outcome = RunDescentLoop(loop, clock, &passes, &r.history);
    if (!o.polish) outcome.stop.why += LimitRateNote(loop, outcome.stop, passes.J(), r.history);
  }
  stats["descent_iterations"] = outcome.iterations;
  stats["descent_cpu_seconds"] = clock.cpu() - cpu_start;
  stats["final_theta"] = outcome.theta;
  stats["simulations"] = passes.work().simulations;
  stats["prefilter_rejections"] = 0;
  stats["reformulated"] = run.target.reformulated ? 1.0 : 0.0;
  stats["scheme_stages"] = s;
  stats["stage_controls"] = s * N;
  if (passes.free_final_time()) {
    stats["final_time"] = passes.T();
    stats["dJdT"] = passes.dJdT();
  }
  const TimeGrid grid = passes.grid();
  r.status = outcome.stop.status;
  r.solver_status = outcome.stop.code;
  r.message = run.target.NotePrefix() + "descent on " + SchemeName(o.scheme) +
              " stage controls: " + outcome.stop.why;
  r.iterations = outcome.iterations;
  r.controls = StageControls(grid, srk.tableau(), passes.U(), problem.control_set());
  r.state_grid = grid;
  r.states = passes.X();
  if (outcome.have_costates) r.costates = passes.Lambda();
  // J of the problem in the request's terminal form (hard: no penalty, no multiplier terms).
  r.objective =
      use_al || o.polish
          ? StageRkOcp(problem, grid, srk.tableau(), request.terminal).Simulate(passes.U(), nullptr)
          : passes.J();
  // No Newton once the CPU limit is reached (the descent's stop says so), nor from a start
  // whose J is not finite.
  if (o.polish && clock.cpu() < o.max_cpu_seconds && std::isfinite(passes.J())) {
    out.polished =
        StagePolish(run, request, grid, srk.tableau(), passes.U(), outcome.iterations, &r);
  }
  return out;
}

// The family on request.grid: the descent (or the outer loop), then the polish when it is on.
GridSolve SolveOnGrid(const FamilyRun& run, const SolveRequest& request) {
  const HamiltonianFamilyOptions& o = run.o;
  if (o.scheme != HamiltonianFamilyOptions::Scheme::kEuler) return SolveOnStageGrid(run, request);
  const Stopwatch& clock = run.clock;
  const double cpu_start = clock.cpu();
  const Ocp& problem = *run.target.ocp;
  const bool path_al =
      problem.num_path() > 0;  // ResolveFamilyTarget left them only for the outer loop
  // The hard form by the outer loop, unless Newton finishes: then the descent runs on the
  // problem's penalty form (a better start than the loop's first, weaker, penalties) and Newton
  // solves the hard form.
  const bool use_al = (request.terminal == TerminalMode::kHard && !o.polish) || path_al;

  // The problem the descent minimizes and its discrete form.
  std::unique_ptr<AugmentedLagrangianOcp> al;
  if (use_al) al = std::make_unique<AugmentedLagrangianOcp>(problem, request.grid);
  const Ocp& descended = use_al ? static_cast<const Ocp&>(*al) : problem;
  const DiscreteOcp docp(descended,
                         request.grid,
                         request.integrator,
                         use_al ? TerminalMode::kHard : TerminalMode::kPenalty);
  // Without path terms the outer loop's problem differs from `problem` only in its terminal
  // cost: the problem's fast paths stay valid.
  const Ocp& fast = path_al ? descended : problem;
  DescentPasses passes(docp,
                       o.armijo_prefilter,
                       dynamic_cast<const EulerStageModel*>(&fast),
                       dynamic_cast<const ProximalHamiltonianMinimizer*>(&fast));
  if (problem.free_final_time()) {
    passes.EnableFreeFinalTime(problem.free_final_time()->lower,
                               problem.free_final_time()->upper,
                               o.free_time_initial_fraction);
  }
  if (problem.HasFreeInitialState()) {
    const VectorBounds bounds = problem.InitialNodeBounds();
    passes.EnableFreeInitialState(bounds.lower, bounds.upper);
  }
  Mat U0 = request.initial_guess ? request.initial_guess->SampleIntervals(request.grid)
                                 : DefaultInitialGuess(problem, request.grid).values();
  for (int k = 0; k < U0.cols(); ++k) problem.control_set().Project(U0.col(k));
  passes.Start(U0);

  const DescentLoopOptions loop =
      FamilyLoopOptions(o, o.polish ? o.polish_switch : o.relative_theta_tolerance);

  GridSolve out;
  SolveResult& r = out.result;
  r.solver = run.name;
  auto& stats = r.solver_stats;
  int descent_iterations = 0;
  double theta = NAN;
  bool have_costates = false;
  DescentStop stop;
  if (use_al) {
    const AugmentedLagrangianRule& rule = o.augmented_lagrangian;
    const AugmentedLagrangianOutcome outcome =
        RunAugmentedLagrangian(rule, loop, clock, al.get(), &passes, &r.history);
    stop = outcome.stop;
    descent_iterations = outcome.descent_iterations;
    theta = outcome.theta;
    have_costates = outcome.have_costates;
    RecordAugmentedLagrangianOutcome(outcome, *al, &stats);
  } else {
    const std::size_t begin = r.history.size();
    const DescentLoopOutcome outcome = RunDescentLoop(loop, clock, &passes, &r.history);
    stop = outcome.stop;
    // With the polish on, Newton takes over from a limited descent: no rate to report.
    if (!o.polish) stop.why += LimitRateNote(loop, stop, passes.J(), r.history, begin);
    descent_iterations = outcome.iterations;
    theta = outcome.theta;
    have_costates = outcome.have_costates;
  }
  stats["descent_iterations"] = descent_iterations;
  stats["descent_cpu_seconds"] = clock.cpu() - cpu_start;
  stats["final_theta"] = theta;
  stats["simulations"] = passes.work().simulations;
  stats["prefilter_rejections"] = passes.work().rejections;
  stats["reformulated"] = run.target.reformulated ? 1.0 : 0.0;
  if (passes.free_final_time()) {
    stats["final_time"] = passes.T();
    stats["dJdT"] = passes.dJdT();
  }
  if (passes.free_initial_state()) {
    stats["initial_state_stationarity"] = passes.InitialStateStationarity();
  }

  const TimeGrid grid = passes.grid();
  r.status = stop.status;
  r.solver_status = stop.code;
  r.message = run.target.NotePrefix() + "descent: " + stop.why;
  r.iterations = descent_iterations;
  r.controls = ControlTrajectory::PiecewiseConstant(grid, passes.U());
  r.state_grid = grid;
  r.states = passes.X();
  if (have_costates) r.costates = passes.Lambda();
  r.objective = DiscreteObjective(problem, request, passes);

  // No Newton attempt once the CPU limit is reached (the descent's stop says so).
  if (o.polish && clock.cpu() < o.max_cpu_seconds) {
    out.polished = Polish(run, problem, request, loop, &passes, &r, &out.last_newton);
  }
  return out;
}

// The result of a polish whose Newton ran and never converged is the descent's iterate.
SolveResult ResultOf(GridSolve g) {
  const bool newton_ran = !g.last_newton.solver.empty();
  if (newton_ran && !g.polished) g.result.message += " (the controls are the descent's)";
  return std::move(g.result);
}

// The polish with grid sequencing: the whole polish (descent, fitted costates, one Newton
// attempt) on the coarsest grid, Newton on each finer grid from the coarser solution
// (NewtonOnFinerGrids); where that fails, the request's grid is solved as without sequencing
// and the record says so. The finer grids start from the coarsest grid's last Newton iterate
// even when that Newton did not converge: it fails mostly in its line search at a kink of the
// semismooth residual close to the solution (comm-path2d, N = 100, ||F||_inf 1.4e-5 .. 0.1 where
// it started at 1.5), which is a different kink, or none, on the finer grid
// (solvers/README-family.md).
SolveResult SolveSequenced(const FamilyRun& run, const SolveRequest& request, int levels) {
  const Stopwatch& clock = run.clock;
  std::vector<TimeGrid> grids{request.grid};  // fine to coarse
  for (int l = 0; l < levels; ++l) grids.push_back(grids.back().Coarsened(2));
  const int coarse_intervals = grids.back().intervals();
  HamiltonianFamilyOptions first = run.o;
  first.polish_attempts = 1;
  SolveRequest coarse_request = request;
  coarse_request.grid = grids.back();
  const double cpu0 = clock.cpu();
  GridSolve coarse =
      SolveOnGrid({run.name, first, run.original, run.target, clock}, coarse_request);
  const double coarse_cpu = clock.cpu() - cpu0;
  std::vector<IterationRecord> history = std::move(coarse.result.history);
  for (IterationRecord& row : history) row.intervals = coarse_intervals;
  GridSequenceOutcome finer;
  const SolveResult& seed = coarse.last_newton;
  const bool seeded = seed.states.cols() == coarse_request.grid.size() &&
                      seed.costates.cols() == seed.states.cols() && seed.states.allFinite() &&
                      seed.costates.allFinite();
  if (seeded) {
    finer = NewtonOnFinerGrids(run.original,
                               PolishNewtonOptions(run.o),
                               request.terminal,
                               seed,
                               std::vector<TimeGrid>(grids.rbegin() + 1, grids.rend()),
                               clock,
                               &history,
                               run.o.max_cpu_seconds);
  }
  const double fine_cpu = clock.cpu() - cpu0 - coarse_cpu;
  const auto coarse_newton_stat = coarse.result.solver_stats.find("newton_iterations");
  const double coarse_newton =
      coarse_newton_stat == coarse.result.solver_stats.end() ? 0.0 : coarse_newton_stat->second;
  std::string coarse_message =
      "on " + std::to_string(coarse_intervals) + " intervals: " + coarse.result.message;
  if (seeded) {
    if (!coarse.polished) coarse_message += " (its last iterate starts the finer grids)";
    coarse_message += "; " + finer.message;
  }

  SolveResult r;
  if (finer.converged) {
    r = std::move(coarse.result);
    RecordNewtonOutcome(finer.last, &r);
    TakeNewtonSolution(finer.last, &r);
    r.iterations += finer.newton_iterations;
    r.message = "grid sequencing, " + coarse_message;
    auto& stats = r.solver_stats;
    stats["newton_iterations"] += finer.newton_iterations;
    stats["newton_cpu_seconds"] += finer.newton_cpu_seconds;
    stats["coarse_fallback"] = 0;
  } else if (clock.cpu() >= run.o.max_cpu_seconds) {
    // No time left for the request's grid alone: the finest grid's solution the sequence
    // reached (a finer grid's Newton solution, else the coarsest grid's: Newton's where it
    // converged, else the descent's), judged on the request's grid, where its controls are
    // piecewise constant too: each of its intervals is 2^l of the request's.
    const bool finer_solved = finer.last.status == SolveStatus::kConverged;
    const SolveResult& best = finer_solved ? finer.last : coarse.result;
    const Mat& Ub = best.controls.values();
    const int N = request.grid.intervals();
    Mat U(Ub.rows(), N);
    for (int k = 0; k < N; ++k) U.col(k) = Ub.col(k / (N / static_cast<int>(Ub.cols())));
    TimeGrid grid = request.grid;
    if (best.state_grid.tf() != grid.tf()) grid = grid.StretchedTo(best.state_grid.tf());
    const std::string from =
        std::to_string(best.state_grid.intervals()) + "-interval grid's controls";
    r = std::move(coarse.result);
    Mat X;
    DiscreteOcp docp(*run.target.ocp, grid, request.integrator, request.terminal);
    // A free initial state starts where the solution the controls come from starts.
    if (run.original.HasFreeInitialState() && best.states.cols() > 0) {
      docp.SetInitialState(best.states.col(0));
    }
    r.objective = docp.Simulate(U, &X);
    r.controls = ControlTrajectory::PiecewiseConstant(grid, U);
    r.state_grid = grid;
    r.states = X;
    r.costates = Mat();
    r.status = SolveStatus::kMaxTime;
    r.solver_status = "max_cpu_seconds";
    r.iterations += finer.newton_iterations;
    r.message =
        "grid sequencing ended at max_cpu_seconds = " + MessageNumber(run.o.max_cpu_seconds) +
        ", " + coarse_message + "; the " + from + " on the request's grid";
    auto& stats = r.solver_stats;
    stats["newton_iterations"] += finer.newton_iterations;
    stats["newton_cpu_seconds"] += finer.newton_cpu_seconds;
    if (finer_solved && best.solver_stats.count("final_time")) {
      stats["final_time"] = best.solver_stats.at("final_time");
    }
    stats["coarse_fallback"] = 0;
  } else {
    // The request's grid as without sequencing, after the failed sequence (whose rows stay in
    // the history, first, and whose steps count in `iterations`).
    r = ResultOf(SolveOnGrid(run, request));
    const int failed_rows = static_cast<int>(history.size());
    for (IterationRecord row : r.history) {
      row.iteration += failed_rows;
      history.push_back(row);
    }
    const int failed_iterations = coarse.result.iterations + finer.newton_iterations;
    r.iterations += failed_iterations;
    r.message = "grid sequencing failed, " + coarse_message +
                "; then on the request's grid alone: " + r.message;
    auto& stats = r.solver_stats;
    stats["coarse_fallback"] = 1;
    stats["coarse_fallback_intervals"] = seeded ? finer.failed_intervals : coarse_intervals;
    stats["coarse_failed_iterations"] = failed_iterations;
  }
  r.history = std::move(history);
  auto& stats = r.solver_stats;
  stats["coarse_levels"] = levels;
  stats["coarse_intervals"] = coarse_intervals;
  stats["coarse_newton_iterations"] = coarse_newton;
  stats["coarse_newton_converged"] = coarse.polished ? 1 : 0;
  stats["fine_newton_iterations"] = finer.newton_iterations;
  stats["coarse_cpu_seconds"] = coarse_cpu;
  stats["fine_cpu_seconds"] = fine_cpu;
  return r;
}

}  // namespace

HamiltonianFamily::HamiltonianFamily(Preset preset) : HamiltonianFamily(Defaults(preset), preset) {}

HamiltonianFamily::HamiltonianFamily(const Options& options, Preset preset)
    : preset_(preset), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument(name() + ": " + error);
}

HamiltonianFamily::Options HamiltonianFamily::Proximal() {
  Options o;
  o.direction = Options::Direction::kProximal;
  return o;
}

HamiltonianFamily::Options HamiltonianFamily::AugmentedLagrangian() {
  Options o;
  o.path = Options::PathConstraints::kAugmentedLagrangian;
  return o;
}

HamiltonianFamily::Options HamiltonianFamily::Polished() {
  Options o;
  o.polish = true;
  // Newton's first attempt after 250 descent steps (then 500, 1000, ...): on comm-path2d's hard
  // form (N = 400, seeds 1-5, gamma = 1e-2 .. 1e-5) every case converged within two attempts
  // (BM_HardFormFamilyPolish; figures in solvers/README-family.md).
  o.max_iterations = 250;
  return o;
}

SolveResult HamiltonianFamily::Solve(const Ocp& original, const SolveRequest& request) const {
  const Options o = ApplyOptions(preset_, request.options, options_);
  const std::string name = this->name();
  CheckRequest(name, original, request);
  const Stopwatch clock;
  HamiltonianTarget target = ResolveFamilyTarget(name, original, request, o);
  if (target.not_applicable) return *target.not_applicable;
  const FamilyRun run{name, o, original, target, clock};
  SolveResult r;
  if (o.polish) {
    // Without Newton steps (newton_max_iterations = 0) there is nothing to refine; the stage
    // schemes' polish is not grid-sequenced.
    const int levels =
        o.newton_max_iterations == 0 || o.scheme != HamiltonianFamilyOptions::Scheme::kEuler
            ? 0
            : GridSequenceLevels(
                  request.grid, o.polish_coarse_levels, o.polish_coarse_min_intervals);
    if (levels > 0) {
      r = SolveSequenced(run, request, levels);
    } else {
      r = ResultOf(SolveOnGrid(run, request));
      r.solver_stats["coarse_levels"] = 0;
    }
  } else {
    r = ResultOf(SolveOnGrid(run, request));
  }
  if (std::isfinite(r.objective)) r.message += "; final J = " + MessageNumber(r.objective);
  // The x(t0) the result's states start from (the judge re-simulates from it).
  if (original.HasFreeInitialState() && r.states.rows() == original.nx() && r.states.cols() > 0) {
    r.initial_state = r.states.col(0);
  }
  r.cpu_seconds = clock.cpu();
  r.wall_seconds = clock.wall();
  return r;
}

}  // namespace ocpb
