// What the time-scaled free-final-time problems share (scaled_min_time.h, scaled_free_time.h):
// their parameters and the checks on them.
#pragma once

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/parameters.h"

namespace ocpb {

/// The parameters C, eps, rho, sigma_min and sigma_max with a problem's defaults; `cone_penalty`
/// describes rho's penalty in that problem's terms.
inline std::vector<ParameterSpec> TimeScalingParameterSpecs(
    double C, double eps, double sigma_min, double sigma_max, const std::string& cone_penalty) {
  return {
      {"C", {C}, "terminal penalty weight (penalty form)", 0.0, 1e300, true},
      {"eps",
       {eps},
       "weight of the variance of sigma in J (0: the physical cost alone, degenerate in sigma)",
       0.0,
       1e300},
      {"rho",
       {1e4},
       "weight of the cone penalty " + cone_penalty + " of the Hamiltonian reformulation",
       0.0,
       1e300,
       true},
      {"sigma_min",
       {sigma_min},
       "lower bound of the time dilation sigma = dt/ds",
       0.0,
       1e300,
       true},
      {"sigma_max", {sigma_max}, "upper bound of the time dilation sigma", 0.0, 1e300, true},
  };
}

/// eps, rho and the sigma bounds as read from a problem's parameters.
struct TimeScalingSettings {
  double eps = 1.0;
  double rho = 1e4;
  double sigma_min = 0.0;
  double sigma_max = 1.0;

  /// Reads them; throws std::invalid_argument (naming `problem`) when sigma_min >= sigma_max.
  static TimeScalingSettings Read(const Parameters& params, const std::string& problem) {
    TimeScalingSettings s;
    s.eps = params.Scalar("eps");
    s.rho = params.Scalar("rho");
    s.sigma_min = params.Scalar("sigma_min");
    s.sigma_max = params.Scalar("sigma_max");
    if (!(s.sigma_min < s.sigma_max)) {
      throw std::invalid_argument(problem + ": sigma_min must be < sigma_max");
    }
    return s;
  }
};

/// Throws std::invalid_argument (naming `problem`) unless the Hamiltonian reformulation's cone
/// penalty rho and regularization eps are finite and positive.
inline void CheckReformulationWeights(const std::string& problem, double rho, double eps) {
  if (!std::isfinite(rho) || rho <= 0.0) {
    throw std::invalid_argument(problem + ": the cone penalty rho must be finite and > 0");
  }
  if (!std::isfinite(eps) || eps <= 0.0) {
    throw std::invalid_argument(problem + ": the regularization eps must be finite and > 0");
  }
}

}  // namespace ocpb
