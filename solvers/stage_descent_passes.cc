#include "solvers/stage_descent_passes.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace ocpb {

StageDescentPasses::StageDescentPasses(const StageRkOcp& srk,
                                       const ProximalHamiltonianMinimizer* proximal)
    : srk_(&srk), ocp_(srk.ocp()), proximal_(proximal), f_(srk.ocp().nx()) {}

void StageDescentPasses::EnableFreeFinalTime(double lower,
                                             double upper,
                                             double initial_fraction,
                                             double growth) {
  const TimeGrid& grid = srk_->grid();
  if (!(grid.t0() < lower && lower <= grid.tf() && grid.tf() <= upper) || !std::isfinite(upper)) {
    throw std::invalid_argument("StageDescentPasses: need t0 < lower <= T <= upper (finite)");
  }
  if (!(initial_fraction > 0.0) || !(growth >= 1.0) || !std::isfinite(growth)) {
    throw std::invalid_argument("StageDescentPasses: initial_fraction > 0 and growth >= 1");
  }
  free_time_ = true;
  base_grid_ = grid;
  T_lower_ = lower;
  T_upper_ = upper;
  initial_fraction_ = initial_fraction;
  growth_ = growth;
}

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
  srk_->Adjoint(U_, X_, &Lambda_, &Y_, &P_, &G_, free_time_ ? &dJdh_ : nullptr);
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
  others_theta_ = 0.0;
  if (free_time_) {
    const TimeGrid& grid = srk_->grid();
    const double duration = grid.tf() - grid.t0(), T = grid.tf();
    dJdT_ = 0.0;
    for (int k = 0; k < N; ++k) dJdT_ += grid.h(k) / duration * dJdh_[k];
    // T's share: min over T' in [lower, upper] of dJ/dT (T' - T) (DescentPasses::Backward).
    others_theta_ = std::min(dJdT_ * (T_lower_ - T), dJdT_ * (T_upper_ - T));
    stationarity_theta_ += others_theta_;
  }
  return theta;
}

int StageDescentPasses::Armijo(const ArmijoRule& rule, double theta, const CpuLimit& limit) {
  // Free final time: the projected gradient step on T and its share of the descent bound.
  double dT = 0.0;
  if (free_time_) {
    const double T = srk_->grid().tf(), t0 = base_grid_.t0();
    if (!std::isfinite(sigma_)) {
      sigma_ = dJdT_ != 0.0 ? initial_fraction_ * (T - t0) / std::abs(dJdT_) : 1.0;
    }
    dT = std::clamp(T - sigma_ * dJdT_, T_lower_, T_upper_) - T;
    theta += dJdT_ * dT;
  }
  double step = 1.0;
  for (int j = 0; j <= rule.max_exponent; ++j, step *= rule.beta) {
    if (j > 0 && limit.Reached()) return kOutOfTime;
    std::unique_ptr<StageRkOcp> trial;
    if (free_time_) {
      const double T_trial = std::clamp(srk_->grid().tf() + step * dT, T_lower_, T_upper_);
      trial = std::make_unique<StageRkOcp>(
          ocp_, base_grid_.StretchedTo(T_trial), srk_->tableau(), srk_->terminal_mode());
    }
    trial_U_.noalias() = U_ + step * D_;
    const double J_trial = (trial ? *trial : *srk_).Simulate(trial_U_, &X_trial_);
    ++work_.simulations;
    if (std::isfinite(J_trial) && J_trial - J_ <= rule.alpha * step * theta) {
      U_.swap(trial_U_);
      X_.swap(X_trial_);
      J_ = J_trial;
      if (free_time_) {
        owned_ = std::move(trial);
        srk_ = owned_.get();
        sigma_ = j == 0 ? growth_ * sigma_ : std::pow(rule.beta, j) * sigma_;
      }
      return j;
    }
  }
  return -1;
}

}  // namespace ocpb
