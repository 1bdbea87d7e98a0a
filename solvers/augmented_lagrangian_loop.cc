#include "solvers/augmented_lagrangian_loop.h"
#include "core/invalid.h"
#include "solvers/descent_rate.h"
#include "solvers/message_number.h"
#include "solvers/stage_descent_passes.h"

#include <algorithm>
#include <cmath>

namespace ocpb {
namespace {

double TerminalResidual(const Ocp& problem, ConstVecRef xN) {
  if (problem.num_terminal() == 0) return 0.0;
  Vec psi(problem.num_terminal());
  problem.TerminalConstraints(xN, psi);
  return psi.lpNorm<Eigen::Infinity>();
}

}  // namespace

bool AugmentedLagrangianRule::IsValid(std::string* error) const {
  if (!(initial_penalty > 0.0) || !std::isfinite(initial_penalty)) {
    return Invalid(error, "initial_penalty must be finite and > 0");
  }
  if (!(penalty_growth > 1.0) || !std::isfinite(penalty_growth)) {
    return Invalid(error, "penalty_growth must be finite and > 1");
  }
  if (!(max_penalty >= initial_penalty) || !std::isfinite(max_penalty)) {
    return Invalid(error, "max_penalty must be finite and >= initial_penalty");
  }
  if (!(initial_feasibility > 0.0)) return Invalid(error, "initial_feasibility must be > 0");
  if (!(feasibility_tolerance > 0.0)) return Invalid(error, "feasibility_tolerance must be > 0");
  if (!(initial_inner_tolerance > 0.0)) {
    return Invalid(error, "initial_inner_tolerance must be > 0");
  }
  if (!(final_inner_tolerance > 0.0 && final_inner_tolerance <= initial_inner_tolerance)) {
    return Invalid(error, "final_inner_tolerance must lie in (0, initial_inner_tolerance]");
  }
  if (max_outer_iterations < 1) return Invalid(error, "max_outer_iterations must be >= 1");
  if (max_inner_iterations < 1) return Invalid(error, "max_inner_iterations must be >= 1");
  return true;
}

template <class Passes>
AugmentedLagrangianOutcome RunAugmentedLagrangian(const AugmentedLagrangianRule& rule,
                                                  const DescentLoopOptions& inner,
                                                  const Stopwatch& clock,
                                                  AugmentedLagrangianOcp* al,
                                                  Passes* passes,
                                                  std::vector<IterationRecord>* history) {
  AugmentedLagrangianOutcome out;
  const int N = static_cast<int>(passes->X().cols()) - 1;  // intervals (U has s N columns)
  double rho = rule.initial_penalty;
  double eta = rule.initial_feasibility;
  double omega = rule.initial_inner_tolerance;
  Vec nu = Vec::Zero(al->num_terminal());
  Mat mu = Mat::Zero(al->inner().num_path(), N);
  bool stopped = false;
  for (int outer = 0; outer < rule.max_outer_iterations && !stopped; ++outer) {
    al->SetTerminal(nu, rho);
    al->SetPath(mu, rho);
    passes->Start(passes->U());  // the cost changed with the multipliers: re-evaluate
    DescentLoopOptions loop = inner;
    loop.theta_tolerance = 0.0;
    loop.relative_theta_tolerance = omega;
    loop.max_iterations =
        std::min(rule.max_inner_iterations, inner.max_iterations - out.descent_iterations);
    const std::size_t inner_begin = history->size();
    const DescentLoopOutcome step =
        RunDescentLoop(loop, clock, passes, history, out.descent_iterations, -1);
    // Why a limit stopped the loop here: the inner solve's rate towards its tolerance.
    const auto rate_note = [&]() -> std::string {
      if (step.stop.status == SolveStatus::kConverged) return "";  // not why the loop stopped
      const double target = omega * (1.0 + std::abs(passes->J()));
      return DescentRateNote(MeasureDescentRate(*history, inner_begin, target), target);
    };
    ++out.outer_iterations;
    out.descent_iterations += step.iterations;
    out.theta = step.theta;
    out.have_costates = step.have_costates;
    // An inner solve that ends at the Armijo floor (no step down to beta^50 decreases J_A) with
    // |theta| already at the final tolerance is stationary to the rounding of J_A: converged.
    const bool at_floor =
        step.stop.code == "armijo_exponent_exceeded" &&
        std::abs(step.theta) <= rule.final_inner_tolerance * (1.0 + std::abs(passes->J()));
    const bool inner_converged = step.stop.status == SolveStatus::kConverged || at_floor;
    out.terminal_residual = TerminalResidual(al->inner(), passes->X().col(N));
    double complementarity = 0.0;
    out.path_violation = 0.0;
    if (al->inner().num_path() > 0) {
      al->PathMeasures(passes->X(), passes->U(), &out.path_violation, &complementarity);
    }
    const double infeasibility = std::max(out.terminal_residual, out.path_violation);
    const bool tight = omega <= rule.final_inner_tolerance || step.stop.code == "theta_at_roundoff";
    if (inner_converged && tight && infeasibility <= rule.feasibility_tolerance) {
      out.stop = {SolveStatus::kConverged,
                  "al_converged",
                  "terminal residual " + MessageNumber(out.terminal_residual, 3) +
                      ", path violation " + MessageNumber(out.path_violation, 3) +
                      " <= " + MessageNumber(rule.feasibility_tolerance, 3) + " after " +
                      std::to_string(out.outer_iterations) + " outer iterations"};
      // The multipliers of the solution: the first-order update at it.
      nu = al->TerminalUpdate(passes->X().col(N));
      if (al->inner().num_path() > 0) mu = al->PathUpdate(passes->X(), passes->U());
      al->SetTerminal(nu, rho);
      al->SetPath(mu, rho);
      return out;
    }
    if (!inner_converged && step.stop.status != SolveStatus::kMaxIterations) {
      out.stop = {step.stop.status,
                  step.stop.code,
                  "inner solve " + std::to_string(out.outer_iterations) + ": " + step.stop.why +
                      (step.stop.code == "max_cpu_seconds" ? rate_note() : std::string())};
      stopped = true;
      break;
    }
    if (out.descent_iterations >= inner.max_iterations) {
      out.stop = {SolveStatus::kMaxIterations,
                  "max_iterations",
                  "reached max_iterations = " + std::to_string(inner.max_iterations) +
                      " descent steps over " + std::to_string(out.outer_iterations) +
                      " outer iterations (terminal residual " +
                      MessageNumber(out.terminal_residual, 3) + ")" + rate_note()};
      stopped = true;
      break;
    }
    if (clock.cpu() >= inner.max_cpu_seconds) {
      out.stop = {SolveStatus::kMaxTime,
                  "max_cpu_seconds",
                  "reached max_cpu_seconds (terminal residual " +
                      MessageNumber(out.terminal_residual, 3) + ")" + rate_note()};
      stopped = true;
      break;
    }
    if (infeasibility <= eta) {
      nu = al->TerminalUpdate(passes->X().col(N));
      if (al->inner().num_path() > 0) mu = al->PathUpdate(passes->X(), passes->U());
      eta = std::max(eta * std::min(0.1, 1.0 / std::pow(rho, 0.9)), rule.feasibility_tolerance);
      omega = std::max(omega * std::min(0.1, 1.0 / rho), rule.final_inner_tolerance);
    } else {
      rho = std::min(rho * rule.penalty_growth, rule.max_penalty);
      eta = std::max(rule.initial_feasibility * std::min(1.0, 1.0 / std::pow(rho, 0.1)),
                     rule.feasibility_tolerance);
      omega = std::max(rule.initial_inner_tolerance * std::min(1.0, 1.0 / rho),
                       rule.final_inner_tolerance);
    }
  }
  if (!stopped) {
    out.stop = {SolveStatus::kMaxIterations,
                "al_max_outer_iterations",
                "reached max_outer_iterations = " + std::to_string(rule.max_outer_iterations) +
                    " (terminal residual " + MessageNumber(out.terminal_residual, 3) +
                    ", path violation " + MessageNumber(out.path_violation, 3) + ")"};
  }
  return out;
}

template AugmentedLagrangianOutcome RunAugmentedLagrangian<DescentPasses>(
    const AugmentedLagrangianRule&,
    const DescentLoopOptions&,
    const Stopwatch&,
    AugmentedLagrangianOcp*,
    DescentPasses*,
    std::vector<IterationRecord>*);
template AugmentedLagrangianOutcome RunAugmentedLagrangian<StageDescentPasses>(
    const AugmentedLagrangianRule&,
    const DescentLoopOptions&,
    const Stopwatch&,
    AugmentedLagrangianOcp*,
    StageDescentPasses*,
    std::vector<IterationRecord>*);

}  // namespace ocpb
