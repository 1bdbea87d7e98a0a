#include "solvers/descent_passes.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "solvers/hamiltonian_descent.h"
#include "solvers/small_dims.h"

namespace ocpb {
namespace {

// The relative margin a bound must clear: the bound and J sum the same terms in different
// orders (suffix sums against the forward sum), which differ by a few ulps of |J|.
double Margin(double threshold) { return 1e-10 * std::max(1.0, std::abs(threshold)); }

}  // namespace

DescentPasses::DescentPasses(const DiscreteOcp& docp, bool prefilter)
    : DescentPasses(docp,
                    prefilter,
                    dynamic_cast<const EulerStageModel*>(&docp.ocp()),
                    dynamic_cast<const ProximalHamiltonianMinimizer*>(&docp.ocp())) {}

DescentPasses::DescentPasses(const DiscreteOcp& docp,
                             bool prefilter,
                             const EulerStageModel* model,
                             const ProximalHamiltonianMinimizer* proximal)
    : docp_(&docp),
      trial_docp_(&docp),
      ocp_(docp.ocp()),
      model_(docp.integrator() == Integrator::kEuler ? model : nullptr),
      proximal_(proximal),
      bound_(prefilter && euler() ? ocp_.RunningCostLowerBound() : std::nullopt),
      pointwise_(prefilter && model_ != nullptr),
      affine_final_state_(bound_.has_value() && ocp_.HasAffineDynamics()),
      nx_(ocp_.nx()),
      nu_(ocp_.nu()),
      N_(docp.intervals()),
      cache_size_(model_ ? model_->StageCacheSize() : 0) {
  trial_U_.resize(nu_, N_);
  X_trial_.resize(nx_, N_ + 1);
  D_.resize(nu_, N_);
  Lambda_.resize(nx_, N_ + 1);
  cache_.resize(cache_size_, N_);
  cache_trial_.resize(cache_size_, N_);
  suffix_.assign(static_cast<size_t>(N_) + 1, 0.0);
  if (pointwise_) bounds_.resize(N_);
  ConstantBound(docp.grid());
  terms_.resize(N_);
  nows_.resize(N_);
  mins_.resize(N_);
  scales_.resize(N_);
  lam_.resize(nx_);
  x_bound_.resize(nx_);
  final_step_.resize(nx_);
  tmp_x_.resize(nx_);
  f_.resize(nx_);
  Lx_.resize(nx_);
  Lu_.resize(nu_);
  fx_.resize(nx_, nx_);
  fu_.resize(nx_, nu_);
  x0_ = docp.initial_state();
  trial_x0_ = x0_;
}

void DescentPasses::ConstantBound(const TimeGrid& grid) {
  if (!bound_) return;
  running_bound_ = 0.0;
  for (int k = 0; k < N_; ++k) running_bound_ += grid.h(k) * *bound_;
  // The constant bound's suffix sums serve every trial on this grid.
  if (!pointwise_) {
    for (int k = N_ - 1; k >= 0; --k) suffix_[k] = suffix_[k + 1] + grid.h(k) * *bound_;
  }
}

void DescentPasses::EnableFreeFinalTime(double lower,
                                        double upper,
                                        double initial_fraction,
                                        double growth) {
  const TimeGrid& grid = docp_->grid();
  if (!euler()) {
    throw std::invalid_argument(
        "DescentPasses: a free final time needs forward Euler (its dJ/dT is Euler's)");
  }
  if (!(grid.t0() < lower && lower <= grid.tf() && grid.tf() <= upper) || !std::isfinite(upper)) {
    throw std::invalid_argument("DescentPasses: need t0 < lower <= T <= upper (finite)");
  }
  if (!(initial_fraction > 0.0) || !(growth >= 1.0) || !std::isfinite(growth)) {
    throw std::invalid_argument("DescentPasses: initial_fraction > 0 and growth >= 1");
  }
  free_time_ = true;
  base_grid_ = grid;
  T_lower_ = lower;
  T_upper_ = upper;
  initial_fraction_ = initial_fraction;
  growth_ = growth;
  // The affine shortcut gives x_N of trials on one grid only.
  affine_final_state_ = false;
}

void DescentPasses::EnableFreeInitialState(const Vec& lower,
                                           const Vec& upper,
                                           double initial_fraction,
                                           double growth) {
  if (!euler()) {
    throw std::invalid_argument(
        "DescentPasses: a free initial state needs forward Euler (its gradient is Euler's "
        "lambda_0)");
  }
  if (lower.size() != nx_ || upper.size() != nx_ || (lower.array() > upper.array()).any()) {
    throw std::invalid_argument(
        "DescentPasses: the initial-state bounds need nx entries each and lower <= upper");
  }
  if (!(initial_fraction > 0.0) || !(growth >= 1.0) || !std::isfinite(growth)) {
    throw std::invalid_argument("DescentPasses: initial_fraction > 0 and growth >= 1");
  }
  free_initial_ = true;
  x0_lower_ = lower;
  x0_upper_ = upper;
  x0_ = x0_.cwiseMax(lower).cwiseMin(upper);
  trial_x0_ = x0_;
  g0_ = Vec::Zero(nx_);
  d0_ = Vec::Zero(nx_);
  initial_fraction0_ = initial_fraction;
  growth0_ = growth;
  // x_N is affine in (x_0, U), but the shortcut's one simulation moves U alone.
  affine_final_state_ = false;
}

void DescentPasses::SpectralInitialStep() {
  // sigma_0 from the last accepted move of x_0: s = Delta x_0, y = Delta g_0, sigma_0 = s^T s /
  // s^T y (Barzilai and Borwein's step, the spectral projected gradient method of Birgin,
  // Martinez and Raydan), where s^T y > 0; otherwise sigma_0 grows. Changed by at most a factor
  // 10 per iteration: y also holds the controls' move, which can make one quotient meaningless.
  // (The joint Armijo step scales x_0's move with the controls' at every iteration; the final
  // time's rule, sigma shrunk to each accepted step, would shrink sigma_0 geometrically on a
  // problem whose controls need a short step every time.)
  if (have_previous0_ && std::isfinite(sigma0_)) {
    const double ss = (x0_ - previous_x0_).squaredNorm();
    const double sy = (x0_ - previous_x0_).dot(g0_ - previous_g0_);
    if (ss > 0.0) {
      const double next = sy > 0.0 ? ss / sy : growth0_ * sigma0_;
      sigma0_ = std::clamp(next, sigma0_ / 10.0, 10.0 * sigma0_);
    }
  }
  previous_x0_ = x0_;
  previous_g0_ = g0_;
  have_previous0_ = true;
}

double DescentPasses::InitialStateStationarity() const {
  return ((x0_ - g0_).cwiseMax(x0_lower_).cwiseMin(x0_upper_) - x0_).lpNorm<Eigen::Infinity>();
}

double DescentPasses::TrialEnds() const {
  const double phi = ocp_.TerminalObjective(X_trial_.col(N_), docp_->terminal_mode());
  return free_initial_ ? docp_->InitialObjective(trial_x0_) + phi : phi;
}

double DescentPasses::Start(const Mat& U) {
  if (U.rows() != nu_ || U.cols() != N_) {
    throw std::invalid_argument("DescentPasses::Start: U must be nu x N");
  }
  U_ = U;
  ++work_.simulations;
  if (!euler()) {
    J_ = docp_->Simulate(U_, &X_);
    return J_;
  }
  trial_docp_ = docp_;
  trial_U_ = U_;
  trial_x0_ = x0_;
  TrialStates();
  double sum = 0.0;
  const double phi = TrialEnds();
  TrialRunningCost(phi, std::numeric_limits<double>::infinity(), &sum);
  const double J = sum + phi;
  J_ = std::isfinite(J) && X_trial_.col(N_).allFinite() ? J
                                                        : std::numeric_limits<double>::quiet_NaN();
  X_.swap(X_trial_);
  X_trial_.resize(nx_, N_ + 1);
  cache_.swap(cache_trial_);
  return J_;
}

bool DescentPasses::TrialRunningCost(double phi, double exit_above, double* sum) {
  const TimeGrid& grid = trial_docp_->grid();
  const bool exit = std::isfinite(exit_above);
  double s = 0.0;
  for (int k = 0; k < N_; ++k) {
    const double t = grid.t(k), h = grid.h(k);
    s +=
        h *
        (model_ ? model_->RunningCostCaching(
                      t, X_trial_.col(k).data(), trial_U_.col(k).data(), cache_trial_.col(k).data())
                : ocp_.RunningCost(t, X_trial_.col(k), trial_U_.col(k)));
    if (exit && s + suffix_[k + 1] + phi > exit_above) {
      work_.cost_points += k + 1;
      return false;
    }
  }
  work_.cost_points += N_;
  *sum = s;
  return true;
}

void DescentPasses::TrialStates() {
  if (!model_) {
    trial_docp_->SimulateStatesFrom(trial_x0_, trial_U_, &X_trial_);
    return;
  }
  X_trial_.col(0) = trial_x0_;
  model_->EulerStates(trial_docp_->grid(), nx_, nu_, trial_U_.data(), X_trial_.data());
}

bool DescentPasses::EvaluateTrial(double step, double threshold, double* J) {
  if (!euler()) {
    trial_U_.noalias() = U_ + step * D_;
    *J = docp_->Simulate(trial_U_, &X_trial_);
    return true;
  }
  const TerminalMode mode = docp_->terminal_mode();
  const bool prefilter = bound_ || pointwise_;
  const double exit_above =
      prefilter ? threshold + Margin(threshold) : std::numeric_limits<double>::infinity();
  if (affine_final_state_) {
    // The constant bound from x_N alone, before any per-point work.
    x_bound_.noalias() = X_.col(N_) + step * final_step_;
    if (running_bound_ + ocp_.TerminalObjective(x_bound_, mode) > exit_above) {
      ++work_.constant_bound_rejections;
      ++work_.rejections;
      return false;
    }
  }
  trial_U_.noalias() = U_ + step * D_;
  TrialStates();
  const double phi = TrialEnds();
  if (bound_ && !affine_final_state_ && running_bound_ + phi > exit_above) {
    ++work_.constant_bound_rejections;
    ++work_.rejections;
    return false;
  }
  if (pointwise_) {
    const TimeGrid& grid = trial_docp_->grid();
    model_->PointwiseRunningCostBounds(
        grid, nx_, nu_, X_trial_.data(), trial_U_.data(), bounds_.data());
    for (int k = N_ - 1; k >= 0; --k) suffix_[k] = suffix_[k + 1] + grid.h(k) * bounds_[k];
    if (suffix_[0] + phi > exit_above) {
      ++work_.pointwise_bound_rejections;
      ++work_.rejections;
      return false;
    }
  }
  double sum = 0.0;
  if (!TrialRunningCost(phi, exit_above, &sum)) {
    ++work_.partial_rejections;
    ++work_.rejections;
    return false;
  }
  const double value = sum + phi;
  *J = std::isfinite(value) && X_trial_.col(N_).allFinite()
           ? value
           : std::numeric_limits<double>::quiet_NaN();
  return true;
}

int DescentPasses::Armijo(const ArmijoRule& rule, double theta, const CpuLimit& limit) {
  if (affine_final_state_) {
    trial_U_.noalias() = U_ + D_;
    TrialStates();
    final_step_ = X_trial_.col(N_) - X_.col(N_);
  }
  // Free final time: the projected gradient step on T and its share of the descent bound.
  double dT = 0.0;
  if (free_time_) {
    const double T = docp_->grid().tf(), t0 = base_grid_.t0();
    if (!std::isfinite(sigma_)) {
      sigma_ = dJdT_ != 0.0 ? initial_fraction_ * (T - t0) / std::abs(dJdT_) : 1.0;
    }
    dT = std::clamp(T - sigma_ * dJdT_, T_lower_, T_upper_) - T;
    theta += dJdT_ * dT;
  }
  // Free initial state: the same projected gradient step on x_0.
  if (free_initial_) {
    const Vec free = (x0_upper_ - x0_lower_).cwiseSign();  // 1 on a free component, 0 else
    const double g = g0_.cwiseProduct(free).lpNorm<Eigen::Infinity>();
    if (!std::isfinite(sigma0_) && g > 0.0) {
      sigma0_ =
          initial_fraction0_ * std::max(1.0, x0_.cwiseProduct(free).lpNorm<Eigen::Infinity>()) / g;
    }
    // Until x(t0) has a gradient, it stays (sigma_0 is then set at the first one).
    d0_ = std::isfinite(sigma0_)
              ? Vec((x0_ - sigma0_ * g0_).cwiseMax(x0_lower_).cwiseMin(x0_upper_) - x0_)
              : Vec::Zero(nx_);
    theta += g0_.dot(d0_);
  }
  double step = 1.0;
  for (int j = 0; j <= rule.max_exponent; ++j, step *= rule.beta) {
    if (j > 0 && limit.Reached()) {
      trial_docp_ = docp_;
      trial_x0_ = x0_;
      if (free_time_) ConstantBound(docp_->grid());
      return kOutOfTime;
    }
    if (free_initial_) trial_x0_ = (x0_ + step * d0_).cwiseMax(x0_lower_).cwiseMin(x0_upper_);
    if (free_time_) {
      const double T_trial = std::clamp(docp_->grid().tf() + step * dT, T_lower_, T_upper_);
      owned_trial_ = std::make_unique<DiscreteOcp>(
          ocp_, base_grid_.StretchedTo(T_trial), Integrator::kEuler, docp_->terminal_mode());
      trial_docp_ = owned_trial_.get();
      ConstantBound(trial_docp_->grid());
    }
    double J_trial = 0.0;
    if (!EvaluateTrial(step, J_ + rule.alpha * step * theta, &J_trial)) continue;
    ++work_.simulations;
    if (std::isfinite(J_trial) && J_trial - J_ <= rule.alpha * step * theta) {
      U_.swap(trial_U_);
      X_.swap(X_trial_);
      cache_.swap(cache_trial_);
      J_ = J_trial;
      if (free_time_) {
        owned_ = std::move(owned_trial_);
        docp_ = owned_.get();
        sigma_ = j == 0 ? growth_ * sigma_ : std::pow(rule.beta, j) * sigma_;
      }
      if (free_initial_) x0_ = trial_x0_;  // sigma_0 moves in Backward
      trial_docp_ = docp_;
      return j;
    }
  }
  trial_docp_ = docp_;
  trial_x0_ = x0_;
  if (free_time_) ConstantBound(docp_->grid());
  return -1;
}

double DescentPasses::Backward(double* theta_scale, double eps) {
  if (!(eps > 0.0)) throw std::invalid_argument("DescentPasses::Backward: eps must be > 0");
  others_theta_ = 0.0;
  if (euler()) {
    const double theta = BackwardEuler(theta_scale, eps);
    if (free_time_) {
      // dJ/dT = sum_k (s_{k+1} - s_k) H(x_k, u_k, lambda_{k+1}) (the class comment).
      const TimeGrid& grid = docp_->grid();
      const double duration = grid.tf() - grid.t0();
      dJdT_ = 0.0;
      for (int k = 0; k < N_; ++k) dJdT_ += grid.h(k) / duration * nows_[k];
      // T's share of the stationarity measure: min over T' in [lower, upper] of dJ/dT (T' - T),
      // the counterpart of the controls' min H - H (<= 0, and 0 exactly where T is stationary:
      // dJ/dT = 0, or a bound with dJ/dT pointing out of the box). Without it the stopping tests
      // saw the controls only and stopped at a non-stationary T.
      const double T = grid.tf();
      others_theta_ += std::min(dJdT_ * (T_lower_ - T), dJdT_ * (T_upper_ - T));
    }
    if (free_initial_) {
      // g_0 = lambda_0 + grad phi0(x_0), and x_0's share of the stationarity measure (the class
      // comment): the best first-order decrease within the bounds, or within max(1, |x_0,i|)
      // of x_0,i where a bound is infinite (an unbounded direction would make it -inf).
      g0_ = Lambda_.col(0);
      if (ocp_.HasFreeInitialState() && ocp_.HasInitialCost()) {  // as J counts it
        double phi0 = 0.0;
        ocp_.InitialCostGradient(x0_, &phi0, tmp_x_);
        g0_ += tmp_x_;
      }
      SpectralInitialStep();
      for (int i = 0; i < nx_; ++i) {
        if (!(x0_lower_[i] < x0_upper_[i]) || g0_[i] == 0.0) continue;
        const double reach = std::max(1.0, std::abs(x0_[i]));
        const double lo = std::isfinite(x0_lower_[i]) ? x0_lower_[i] : x0_[i] - reach;
        const double hi = std::isfinite(x0_upper_[i]) ? x0_upper_[i] : x0_[i] + reach;
        others_theta_ += std::min(g0_[i] * (lo - x0_[i]), g0_[i] * (hi - x0_[i]));
      }
    }
    stationarity_theta_ += others_theta_;
    return theta;
  }
  docp_->Adjoint(U_, X_, &Lambda_, &G_);
  if (!std::isfinite(eps)) {
    Vec scratch;
    stationarity_theta_ =
        HamiltonianDescent::Direction(*docp_, U_, X_, Lambda_, &D_, &scratch, theta_scale);
    return stationarity_theta_;
  }
  // RK4, proximal: the same left-node pairing as Direction, H(t_k, x_k, ., lambda_{k+1}).
  const TimeGrid& grid = docp_->grid();
  double theta = 0.0, scale = 0.0, stationarity = 0.0;
  for (int k = 0; k < N_; ++k) {
    double h_star = 0.0, h_now = 0.0, h_min = 0.0;
    auto d = D_.col(k);
    PointDirection(
        grid.t(k), X_.col(k), U_.col(k), Lambda_.col(k + 1), eps, d, &h_star, &h_now, &h_min);
    d -= U_.col(k);
    theta += grid.h(k) * (h_star - h_now);
    stationarity += grid.h(k) * (h_min - h_now);
    scale += grid.h(k) * (std::abs(h_min) + std::abs(h_now));
  }
  if (theta_scale) *theta_scale = scale;
  stationarity_theta_ = stationarity;
  return theta;
}

void DescentPasses::PointDirection(double t,
                                   ConstVecRef x,
                                   ConstVecRef u,
                                   ConstVecRef p,
                                   double eps,
                                   VecRef w,
                                   double* h_star,
                                   double* h_now,
                                   double* h_min) {
  ocp_.MinimizeAndCompareHamiltonian(t, x, p, u, w, h_star, h_now, f_);
  *h_min = *h_star;
  if (!std::isfinite(eps)) return;
  if (proximal_) {
    proximal_->MinimizeProximalHamiltonian(t, x, p, u, eps, w);
  } else {
    if (!generic_) generic_ = std::make_unique<ConvexPointMinimizer>(ocp_);
    generic_->Minimize(t, x, p, u, eps, u, w);
  }
  *h_star = ocp_.Hamiltonian(t, x, w, p);
}

void DescentPasses::CopyCostate(const double* from, double* to) const {
  // A copy of a compile-time length is a few moves; of nx_ a call of memmove.
  WithSmallDims(nx_, nu_, [&]<int kNx, int>() {
    if constexpr (kNx > 0) {
      std::memcpy(to, from, sizeof(double) * kNx);
    } else {
      std::copy_n(from, nx_, to);
    }
  });
}

// DiscreteOcp::Adjoint's Euler recursion and HamiltonianDescent::Direction in one sweep: at step
// k the costate lam_ is lambda_{k+1}, the one both need. theta and its scale are summed forward
// afterwards, in Direction's order.
double DescentPasses::BackwardEuler(double* theta_scale, double eps) {
  const TimeGrid& grid = docp_->grid();
  const bool proximal = std::isfinite(eps);
  double phi = 0.0;
  ocp_.TerminalObjectiveGradient(X_.col(N_), docp_->terminal_mode(), &phi, lam_);
  Lambda_.col(N_) = lam_;
  double L = 0.0;
  for (int k = N_ - 1; k >= 0; --k) {
    const double t = grid.t(k), h = grid.h(k);
    double h_star = 0.0, h_now = 0.0, h_min = 0.0;
    if (model_) {
      // lambda_k is computed in place from a copy of lambda_{k+1}.
      double* p = Lambda_.col(k).data();
      CopyCostate(Lambda_.col(k + 1).data(), p);
      double* d = D_.col(k).data();
      const double* u = U_.col(k).data();
      model_->BackwardPoint(t,
                            h,
                            X_.col(k).data(),
                            u,
                            cache_.col(k).data(),
                            eps,
                            p,
                            d,
                            &h_star,
                            &h_now,
                            proximal ? &h_min : nullptr);
      for (int i = 0; i < nu_; ++i) d[i] -= u[i];
    } else {
      const auto x = X_.col(k);
      const auto u = U_.col(k);
      auto d = D_.col(k);
      PointDirection(t, x, u, lam_, eps, d, &h_star, &h_now, &h_min);
      ocp_.DynamicsJacobian(t, x, u, f_, fx_, fu_);
      ocp_.RunningCostGradient(t, x, u, &L, Lx_, Lu_);
      tmp_x_.noalias() = fx_.transpose().lazyProduct(lam_);
      d -= u;
      lam_ += h * (tmp_x_ + Lx_);
      Lambda_.col(k) = lam_;
    }
    terms_[k] = h * (h_star - h_now);
    nows_[k] = h_now;
    if (proximal) {
      mins_[k] = h * (h_min - h_now);
      scales_[k] = h * (std::abs(h_min) + std::abs(h_now));
    } else {
      scales_[k] = h * (std::abs(h_star) + std::abs(h_now));
    }
  }
  double theta = 0.0, scale = 0.0, stationarity = 0.0;
  for (int k = 0; k < N_; ++k) {
    theta += terms_[k];
    scale += scales_[k];
    if (proximal) stationarity += mins_[k];
  }
  if (theta_scale) *theta_scale = scale;
  stationarity_theta_ = proximal ? stationarity : theta;
  return theta;
}

}  // namespace ocpb
