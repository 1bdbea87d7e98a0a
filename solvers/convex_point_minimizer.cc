#include "solvers/convex_point_minimizer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/invalid.h"

namespace ocpb {

bool ConvexPointMinimizerOptions::IsValid(std::string* error) const {
  if (max_iterations < 1) return Invalid(error, "max_iterations must be >= 1");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    return Invalid(error, "tolerance must be finite and > 0");
  }
  if (!(sufficient_decrease > 0.0 && sufficient_decrease < 0.5)) {
    return Invalid(error, "sufficient_decrease must lie in (0, 0.5)");
  }
  return true;
}

ConvexPointMinimizer::ConvexPointMinimizer(const Ocp& ocp, const Options& options)
    : ocp_(ocp), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("ConvexPointMinimizer: " + error);
  const int nx = ocp.nx(), nu = ocp.nu();
  f_.resize(nx);
  Lx_.resize(nx);
  Lu_.resize(nu);
  grad_.resize(nu);
  scale_.resize(nu);
  trial_.resize(nu);
  mu_ = Vec::Zero(ocp.num_path());
  fx_.resize(nx, nx);
  fu_.resize(nx, nu);
  hess_.resize(nx + nu, nx + nu);
}

double ConvexPointMinimizer::Objective(
    double t, ConstVecRef x, ConstVecRef p, ConstVecRef center, double eps, ConstVecRef w) const {
  double value = ocp_.Hamiltonian(t, x, w, p);
  if (std::isfinite(eps)) value += (w - center).squaredNorm() / (2.0 * eps);
  return value;
}

int ConvexPointMinimizer::Minimize(double t,
                                   ConstVecRef x,
                                   ConstVecRef p,
                                   ConstVecRef center,
                                   double eps,
                                   ConstVecRef w_start,
                                   VecRef w) {
  const int nx = ocp_.nx(), nu = ocp_.nu();
  const bool proximal = std::isfinite(eps);
  const ControlSet& set = ocp_.control_set();
  w = proximal ? center : w_start;
  set.Project(w);
  double phi = Objective(t, x, p, center, eps, w);
  for (int it = 0; it < options_.max_iterations; ++it) {
    double L = 0.0;
    ocp_.DynamicsJacobian(t, x, w, f_, fx_, fu_);
    ocp_.RunningCostGradient(t, x, w, &L, Lx_, Lu_);
    grad_.noalias() = fu_.transpose() * p;
    grad_ += Lu_;
    if (proximal) grad_ += (w - center) / eps;
    ocp_.PointHessian(t, x, w, 1.0, p, mu_, hess_);
    const double fallback = proximal ? 1.0 / eps : 1.0;
    for (int i = 0; i < nu; ++i) {
      const double d = hess_(nx + i, nx + i) + (proximal ? 1.0 / eps : 0.0);
      scale_[i] = d > 0.0 && std::isfinite(d) ? d : fallback;
    }
    for (const ControlSet::Block& b : set.blocks()) {
      if (b.kind != ControlSet::Kind::kBall) continue;
      const double s = scale_.segment(b.offset, b.size).maxCoeff();
      scale_.segment(b.offset, b.size).setConstant(s);
    }
    // Backtracking along the projection arc.
    double tau = 1.0, phi_trial = phi;
    bool accepted = false;
    for (int j = 0; j < 60; ++j, tau *= 0.5) {
      trial_ = w - tau * grad_.cwiseQuotient(scale_);
      set.Project(trial_);
      phi_trial = Objective(t, x, p, center, eps, trial_);
      if (phi_trial <= phi + options_.sufficient_decrease * grad_.dot(trial_ - w)) {
        accepted = true;
        break;
      }
    }
    if (!accepted) return it;  // no decrease left at rounding level: w is the minimizer
    const double change = (trial_ - w).lpNorm<Eigen::Infinity>();
    w = trial_;
    phi = phi_trial;
    if (change <= options_.tolerance * (1.0 + w.lpNorm<Eigen::Infinity>())) return it + 1;
  }
  return -1;
}

}  // namespace ocpb
