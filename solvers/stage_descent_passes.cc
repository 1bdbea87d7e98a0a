#include "solvers/stage_descent_passes.h"

#include <cmath>
#include <stdexcept>

namespace ocpb {

StageDescentPasses::StageDescentPasses(const StageRkOcp& srk,
                                       const ProximalHamiltonianMinimizer* proximal)
    : srk_(&srk), ocp_(srk.ocp()), proximal_(proximal), f_(srk.ocp().nx()) {}

double StageDescentPasses::Start(const Mat& U) {
  if (U.rows() != ocp_.nu() || U.cols() != srk_->controls()) {
    throw std::invalid_argument("StageDescentPasses::Start: U must be nu x sN");
  }
  U_ = U;
  ++work_.simulations;
  J_ = srk_->Simulate(U_, &X_);
  return J_;
}

double StageDescentPasses::Backward(double* theta_scale, double eps) {
  if (!(eps > 0.0)) throw std::invalid_argument("StageDescentPasses::Backward: eps must be > 0");
  srk_->Adjoint(U_, X_, &Lambda_, &Y_, &P_, &G_);
  const int s = srk_->stages(), N = srk_->intervals();
  const bool proximal = std::isfinite(eps);
  D_.resize(ocp_.nu(), s * N);
  double theta = 0.0, scale = 0.0, stationarity = 0.0;
  for (int k = 0; k < N; ++k) {
    for (int i = 0; i < s; ++i) {
      const int col = k * s + i;
      const double t = srk_->StageTime(k, i), w = srk_->StageWeight(k, i);
      const auto y = Y_.col(col);
      const auto p = P_.col(col);
      const auto u = U_.col(col);
      auto d = D_.col(col);
      double h_star = 0.0, h_now = 0.0;
      ocp_.MinimizeAndCompareHamiltonian(t, y, p, u, d, &h_star, &h_now, f_);
      const double h_min = h_star;
      if (proximal) {
        if (proximal_) {
          proximal_->MinimizeProximalHamiltonian(t, y, p, u, eps, d);
        } else {
          if (!generic_) generic_ = std::make_unique<ConvexPointMinimizer>(ocp_);
          generic_->Minimize(t, y, p, u, eps, u, d);
        }
        h_star = ocp_.Hamiltonian(t, y, d, p);
      }
      d -= u;
      theta += w * (h_star - h_now);
      stationarity += w * (h_min - h_now);
      scale += w * (std::abs(h_min) + std::abs(h_now));
    }
  }
  if (theta_scale) *theta_scale = scale;
  stationarity_theta_ = stationarity;
  return theta;
}

int StageDescentPasses::Armijo(const ArmijoRule& rule, double theta, const CpuLimit& limit) {
  double step = 1.0;
  for (int j = 0; j <= rule.max_exponent; ++j, step *= rule.beta) {
    if (j > 0 && limit.Reached()) return kOutOfTime;
    trial_U_.noalias() = U_ + step * D_;
    const double J_trial = srk_->Simulate(trial_U_, &X_trial_);
    ++work_.simulations;
    if (std::isfinite(J_trial) && J_trial - J_ <= rule.alpha * step * theta) {
      U_.swap(trial_U_);
      X_.swap(X_trial_);
      J_ = J_trial;
      return j;
    }
  }
  return -1;
}

}  // namespace ocpb
