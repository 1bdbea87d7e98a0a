#include "core/solve_result.h"

namespace ocpb {

const char* ToString(SolveStatus status) {
  switch (status) {
    case SolveStatus::kConverged:
      return "converged";
    case SolveStatus::kAcceptable:
      return "acceptable";
    case SolveStatus::kMaxIterations:
      return "max_iterations";
    case SolveStatus::kMaxTime:
      return "max_time";
    case SolveStatus::kStepTooSmall:
      return "step_too_small";
    case SolveStatus::kRoundoffLimited:
      return "roundoff_limited";
    case SolveStatus::kInfeasible:
      return "infeasible";
    case SolveStatus::kNumericalFailure:
      return "numerical_failure";
    case SolveStatus::kInvalidInput:
      return "invalid_input";
    case SolveStatus::kNotApplicable:
      return "not_applicable";
    case SolveStatus::kError:
      return "error";
  }
  return "error";
}

bool IsSuccess(SolveStatus status) {
  return status == SolveStatus::kConverged || status == SolveStatus::kAcceptable;
}

}  // namespace ocpb
