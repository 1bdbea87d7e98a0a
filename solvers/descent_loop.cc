#include "solvers/descent_loop.h"
#include "core/invalid.h"
#include "solvers/message_number.h"
#include "solvers/stage_descent_passes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ocpb {
namespace {

// The stopping tests made before an Armijo search, in HamiltonianDescent's documented order.
std::optional<DescentStop> StopTest(const DescentLoopOptions& opt,
                                    int iteration,
                                    double J,
                                    double theta,
                                    double theta_scale,
                                    double cpu) {
  if (!std::isfinite(theta)) {
    return DescentStop{SolveStatus::kNumericalFailure,
                       "nonfinite_theta",
                       "theta is not finite at iteration " + std::to_string(iteration)};
  }
  // At a stationary point every term H(u*) - H(u) is zero up to rounding, and their sum can
  // come out as +1e-17: that is convergence to machine precision, not a failed minimizer.
  const double roundoff = 64.0 * std::numeric_limits<double>::epsilon() * theta_scale;
  if (theta > 0.0 && theta <= roundoff) {
    return DescentStop{SolveStatus::kConverged,
                       "theta_at_roundoff",
                       "theta = " + MessageNumber(theta) + " is at the rounding level " +
                           MessageNumber(roundoff) +
                           " of the Hamiltonian sums: stationary to machine precision"};
  }
  if (theta > 0.0) {
    return DescentStop{SolveStatus::kError,
                       "theta_positive",
                       "theta = " + MessageNumber(theta) +
                           " > 0: the problem's Hamiltonian minimizer did not minimize H"};
  }
  if (std::abs(theta) <= opt.theta_tolerance) {
    return DescentStop{SolveStatus::kConverged,
                       "theta_below_tolerance",
                       "|theta| = " + MessageNumber(std::abs(theta)) +
                           " <= " + MessageNumber(opt.theta_tolerance)};
  }
  if (opt.relative_theta_tolerance > 0.0 &&
      std::abs(theta) <= opt.relative_theta_tolerance * (1.0 + std::abs(J))) {
    return DescentStop{SolveStatus::kConverged,
                       "theta_below_relative_tolerance",
                       "|theta| = " + MessageNumber(std::abs(theta)) +
                           " <= " + MessageNumber(opt.relative_theta_tolerance) + " (1 + |J|)"};
  }
  if (iteration >= opt.max_iterations) {
    return DescentStop{SolveStatus::kMaxIterations,
                       "max_iterations",
                       "reached max_iterations = " + std::to_string(opt.max_iterations)};
  }
  if (cpu >= opt.max_cpu_seconds) {
    return DescentStop{SolveStatus::kMaxTime,
                       "max_cpu_seconds",
                       "reached max_cpu_seconds = " + MessageNumber(opt.max_cpu_seconds)};
  }
  return std::nullopt;
}

}  // namespace

bool ProximalSchedule::IsValid(std::string* error) const {
  if (!(initial_eps > 0.0)) return Invalid(error, "initial_eps must be > 0");
  if (!(growth >= 1.0) || !std::isfinite(growth)) {
    return Invalid(error, "growth must be finite and >= 1");
  }
  if (!(min_eps > 0.0) || !std::isfinite(min_eps)) {
    return Invalid(error, "min_eps must be finite and > 0");
  }
  if (!(max_eps >= min_eps)) return Invalid(error, "max_eps must be >= min_eps");
  return true;
}

double ProximalSchedule::Next(double eps, int j, double beta) const {
  const double next = j == 0 ? growth * eps : std::pow(beta, j) * eps;
  return std::clamp(next, min_eps, max_eps);
}

template <class Passes>
DescentLoopOutcome RunDescentLoop(const DescentLoopOptions& opt,
                                  const Stopwatch& clock,
                                  Passes* passes,
                                  std::vector<IterationRecord>* history,
                                  int first_iteration,
                                  int first_armijo,
                                  bool record_first) {
  DescentLoopOutcome out;
  const double inf = std::numeric_limits<double>::infinity();
  double eps =
      opt.proximal
          ? std::clamp(opt.proximal->initial_eps, opt.proximal->min_eps, opt.proximal->max_eps)
          : inf;
  int last_j = first_armijo;
  std::optional<DescentStop> stop;
  if (!std::isfinite(passes->J())) {
    stop = DescentStop{SolveStatus::kNumericalFailure,
                       "nonfinite_cost",
                       "the cost of the starting control is not finite"};
    history->push_back({first_iteration, passes->J(), NAN, last_j, NAN, NAN, clock.cpu()});
  }
  while (!stop) {
    double theta_scale = 0.0;
    // The direction's theta for Armijo; the paper's (stationarity) theta for the record and the
    // tests (they differ only for the proximal direction).
    const double direction_theta = passes->Backward(&theta_scale, eps);
    out.theta = passes->stationarity_theta();
    out.eps = opt.proximal ? eps : NAN;
    out.have_costates = true;
    const int iteration = first_iteration + out.iterations;
    if (record_first || out.iterations > 0) {
      history->push_back({iteration, passes->J(), out.theta, last_j, NAN, NAN, clock.cpu()});
    }
    stop = StopTest(opt, out.iterations, passes->J(), out.theta, theta_scale, clock.cpu());
    if (stop) break;
    // A free final time or initial state that is not stationary moves even where the controls'
    // theta is 0 (their direction then adds nothing to the Armijo bound).
    const bool others_move = passes->others_theta() < 0.0;
    if (!(direction_theta < 0.0) && !others_move) {
      stop = DescentStop{SolveStatus::kError,
                         "theta_positive",
                         "the proximal theta " + MessageNumber(direction_theta) +
                             " is not negative: the proximal minimizer did not minimize"};
      break;
    }
    const int accepted =
        passes->Armijo(opt.armijo,
                       others_move ? std::min(direction_theta, 0.0) : direction_theta,
                       CpuLimit{&clock, opt.max_cpu_seconds});
    if (accepted == Passes::kOutOfTime) {
      stop = DescentStop{SolveStatus::kMaxTime,
                         "max_cpu_seconds",
                         "reached max_cpu_seconds = " + MessageNumber(opt.max_cpu_seconds) +
                             " in the Armijo search at iteration " + std::to_string(iteration)};
      break;
    }
    if (accepted < 0) {
      stop = DescentStop{SolveStatus::kStepTooSmall,
                         "armijo_exponent_exceeded",
                         "no Armijo exponent j <= " + std::to_string(opt.armijo.max_exponent) +
                             " gave sufficient decrease at iteration " + std::to_string(iteration)};
      break;
    }
    if (opt.proximal) eps = opt.proximal->Next(eps, accepted, opt.armijo.beta);
    last_j = accepted;
    ++out.iterations;
  }
  out.stop = *stop;
  return out;
}

template DescentLoopOutcome RunDescentLoop<DescentPasses>(const DescentLoopOptions&,
                                                          const Stopwatch&,
                                                          DescentPasses*,
                                                          std::vector<IterationRecord>*,
                                                          int,
                                                          int,
                                                          bool);
template DescentLoopOutcome RunDescentLoop<StageDescentPasses>(const DescentLoopOptions&,
                                                               const Stopwatch&,
                                                               StageDescentPasses*,
                                                               std::vector<IterationRecord>*,
                                                               int,
                                                               int,
                                                               bool);

}  // namespace ocpb
