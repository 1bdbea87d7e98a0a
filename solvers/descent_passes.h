// The passes of one Hamiltonian-descent iteration (simulation, backward sweep, Armijo trials)
// with their workspace, shared by the descent and the methods built on it.
#pragma once

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "core/discrete_ocp.h"
#include "core/euler_stage_model.h"
#include "core/proximal_hamiltonian.h"
#include "core/timer.h"
#include "solvers/convex_point_minimizer.h"

namespace ocpb {

/// The Armijo rule: step sizes 1, beta, beta^2, ..., beta^max_exponent; a step s is accepted
/// when J(U + s D) - J(U) <= alpha s theta.
struct ArmijoRule {
  double alpha = 0.1;
  double beta = 0.5;
  int max_exponent = 50;
};

/// Work counters of DescentPasses (cumulative).
struct DescentWork {
  /// Full evaluations of J: the start and every Armijo trial that was not rejected early.
  int simulations = 0;
  /// Trials rejected before a full evaluation: by the constant bound, by the pointwise bound,
  /// or part-way through the running cost (their sum).
  int rejections = 0;
  int constant_bound_rejections = 0;
  int pointwise_bound_rejections = 0;
  int partial_rejections = 0;
  /// Grid points at which the running cost L was evaluated (by simulations and partial trials).
  long cost_points = 0;
};

/// One iterate U of the descent on a DiscreteOcp, with its states X, cost J, costates Lambda and
/// direction D, and the passes that produce them:
///
///  - Start(U): simulate; J(U) and X.
///  - Backward(): the exact discrete adjoint Lambda and the direction of the paper's method,
///    d_k = u*_k - u_k with u*_k = argmin_{w in U} H(t_k, x_k, w, lambda_{k+1}), and
///    theta = sum_k h_k [H(u*_k) - H(u_k)], in one backward sweep (forward Euler; RK4 uses
///    DiscreteOcp::Adjoint and HamiltonianDescent::Direction).
///  - Armijo(rule, theta): the Armijo search along D; on success U, X, J move to the trial.
///
/// Forward Euler gets these savings; none changes a number (the iterates, costs and theta are
/// bitwise those of DiscreteOcp::Simulate, DiscreteOcp::Adjoint and HamiltonianDescent::Direction;
/// tests compare them with values recorded before this class existed):
///  - A lower bound on L (with `prefilter`): Ocp::RunningCostLowerBound() m gives, from the trial's
///    x_N alone, J(trial) >= sum_k h_k m + Phi(x_N); an EulerStageModel's pointwise bound m_k
///    (comm-path2d: no channel) gives J(trial) >= sum_k h_k m_k + Phi(x_N); and during the
///    running-cost pass J(trial) >= sum_{j<=k} h_j L_j + sum_{j>k} h_j m_j + Phi(x_N) after each
///    point. A trial whose bound exceeds J + alpha s theta (plus 1e-10 relative, for the
///    different summation orders) fails the Armijo test and is rejected without its cost (or
///    the rest of it). With affine dynamics (Ocp::HasAffineDynamics) the Euler x_N is affine in
///    U, so x_N(U + s D) = x_N + s (x_N(U + D) - x_N) for every trial from one states-only
///    simulation per iteration; used for the first bound only (the trial's own states, for its
///    cost, come from the Euler recursion, so they are bitwise those of Simulate).
///  - An EulerStageModel: the trials' states come from its EulerStep, the running-cost pass
///    caches what the problem wants per point, and the backward sweep at the accepted trial's
///    points reuses it (comm-path2d: the channel is evaluated once per accepted point, not three
///    times).
/// Without the model the backward sweep is the generic Ocp calls of Adjoint and Direction.
///
/// Free final time (EnableFreeFinalTime, forward Euler only): T is a variable too. The grid keeps
/// its nodes' relative positions s_k and stretches to [t0, T] (h_k = (T - t0)(s_{k+1} - s_k)), and
/// for an autonomous problem (Ocp's contract for a free final time) the exact derivative of the
/// discrete J is
///   dJ/dT = sum_k (s_{k+1} - s_k) [L(x_k, u_k) + lambda_{k+1}^T f(x_k, u_k)]
///         = sum_k (s_{k+1} - s_k) H(x_k, u_k, lambda_{k+1})
/// (differentiate J = sum_k h_k L_k + Phi(x_N) through x_{k+1} = x_k + h_k f_k with the discrete
/// adjoint). Backward computes it from the sweep's H(u_k) values; Armijo then moves (U, T) along
/// (D, d_T), d_T = P_[lower, upper](T - sigma dJ/dT) - T (a projected gradient step on T), and
/// accepts J(U + s D, T + s d_T) - J <= alpha s (theta + dJ/dT d_T); dJ/dT d_T <= -d_T^2 / sigma
/// <= 0, so this is a descent test on the joint variable. sigma follows the proximal schedule's
/// rule (grow after a full step, shrink to the accepted step).
///
/// Free initial state (EnableFreeInitialState, forward Euler only; static parameters are such
/// components, Ocp::SetStaticParameters): x_0 is a variable in the initial-state bounds
/// [l0, u0] too, and J counts phi0(x_0) (DiscreteOcp). The exact gradient is
///   g_0 = dJ/dx_0 = lambda_0 + grad phi0(x_0)
/// (lambda_0 from the sweep's recursion; for a static parameter it sums h_k H_p along the
/// grid, its adjoint), and x_0 moves as T does: d_0 = P_[l0, u0](x_0 - sigma_0 g_0) - x_0, its
/// share g_0^T d_0 <= -|d_0|^2 / sigma_0 of the Armijo test's bound; its first sigma_0 moves x_0
/// by at most `initial_fraction` of max(1, |x_0|_inf), then sigma_0 is Barzilai and Borwein's
/// spectral step from the last move of x_0 and of g_0 (SpectralInitialStep). At a
/// stationary x_0 the transversality conditions hold: p(t0) = -grad phi0 on the free components
/// inside their bounds. The stationarity measure gains min over x' in the bounds, within
/// max(1, |x_0,i|) of x_0,i where a bound is infinite, of g_0^T (x' - x_0) (<= 0, 0 exactly where
/// x_0 is stationary).
class DescentPasses {
 public:
  /// `docp` must outlive this object. `prefilter`: use the lower bounds above (Euler only).
  DescentPasses(const DiscreteOcp& docp, bool prefilter);
  /// The same with the fast paths given explicitly instead of found by dynamic_cast on docp's
  /// problem (a wrapper that changes only the terminal cost, such as AugmentedLagrangianOcp
  /// without path terms, passes its inner problem's); either may be null. They must describe
  /// docp's running cost, dynamics and Hamiltonian exactly.
  DescentPasses(const DiscreteOcp& docp,
                bool prefilter,
                const EulerStageModel* model,
                const ProximalHamiltonianMinimizer* proximal);

  /// Makes the final time a variable in [lower, upper] (docp's grid gives the start T = its tf
  /// and the relative positions). `initial_fraction` > 0: the first T step moves T by at most
  /// that fraction of T - t0; `growth` >= 1. Throws std::invalid_argument unless the integrator
  /// is Euler and t0 < lower <= T <= upper. Call before Start.
  void EnableFreeFinalTime(double lower,
                           double upper,
                           double initial_fraction = 0.1,
                           double growth = 2.0);
  bool free_final_time() const { return free_time_; }
  /// Makes x_0 a variable in [lower, upper] (nx entries each; lower == upper fixes a component),
  /// starting at docp's initial_state() projected onto them. `initial_fraction` > 0, `growth`
  /// >= 1 as for the final time. Throws std::invalid_argument unless the integrator is Euler,
  /// lower <= upper and the sizes match. Call before Start.
  void EnableFreeInitialState(const Vec& lower,
                              const Vec& upper,
                              double initial_fraction = 0.1,
                              double growth = 2.0);
  bool free_initial_state() const { return free_initial_; }
  /// The current x_0 (docp's initial_state() for a fixed one).
  const Vec& x0() const { return x0_; }
  /// dJ/dx_0 at the iterate (the last Backward; free initial state only; every component, the
  /// fixed ones included).
  const Vec& dJdx0() const { return g0_; }
  /// max_i |P_[l0, u0](x_0 - g_0)_i - x_0,i|: 0 exactly where x_0 is stationary (the projected
  /// gradient's norm; fixed components count 0). Free initial state only.
  double InitialStateStationarity() const;
  /// The current final time (the grid's tf for a fixed horizon).
  double T() const { return docp_->grid().tf(); }
  /// dJ/dT at the iterate (the last Backward; free final time only).
  double dJdT() const { return dJdT_; }
  /// The current grid (stretched to T() for a free final time).
  const TimeGrid& grid() const { return docp_->grid(); }

  /// U (nu x N, in U) becomes the iterate; returns J(U) (NaN/inf when not finite).
  double Start(const Mat& U);
  /// Fills Lambda and D at the iterate and returns theta; *theta_scale (may be null) receives
  /// sum_k h_k (|H(u*_k)| + |H(u_k)|).
  ///
  /// With a finite eps > 0 the direction is the proximal one of Sakawa and Shindo's successive
  /// approximations: d_k = w_k - u_k with
  ///   w_k = argmin_{w in U} H(t_k, x_k, w, lambda_{k+1}) + |w - u_k|^2 / (2 eps)
  /// (the problem's ProximalHamiltonianMinimizer or EulerStageModel when it has one, otherwise
  /// ConvexPointMinimizer), and theta = sum_k h_k [H(w_k) - H(u_k)] <= -sum_k h_k |d_k|^2 /
  /// (2 eps). H is convex in u (Assumption 1), so on a forward-Euler grid the directional
  /// derivative of J along d is at most theta and the Armijo search ends when theta < 0.
  /// stationarity_theta() then holds the paper's theta at the iterate (equal to the return value
  /// for eps infinite): the proximal theta shrinks with eps whether or not the iterate is
  /// stationary, so stopping tests use the paper's. With a free final time it also holds T's
  /// share, min over T' in [lower, upper] of dJ/dT (T' - T) <= 0 (0 only at a stationary T).
  double Backward(double* theta_scale, double eps = std::numeric_limits<double>::infinity());
  double stationarity_theta() const { return stationarity_theta_; }
  /// The share of stationarity_theta() that is not the controls': a free final time's and a
  /// free initial state's (<= 0; 0 when neither is free or both are stationary). The loop
  /// goes on while it is negative, whatever the controls' theta (they may be stationary while
  /// T or x(t0) are not).
  double others_theta() const { return others_theta_; }
  /// The Armijo search along D (Backward first). Returns the accepted exponent, or -1 when no
  /// exponent <= rule.max_exponent gives sufficient decrease, or kOutOfTime when `limit` was
  /// reached before a trial after the first (checked before each one: the search ends within
  /// one trial's cost of the limit); the iterate is then unchanged.
  int Armijo(const ArmijoRule& rule, double theta, const CpuLimit& limit = {});
  static constexpr int kOutOfTime = -2;

  const Mat& U() const { return U_; }
  const Mat& X() const { return X_; }
  const Mat& Lambda() const { return Lambda_; }
  const Mat& D() const { return D_; }
  double J() const { return J_; }
  const DescentWork& work() const { return work_; }
  /// Moves the states and costates out (the object is then only good for destruction).
  Mat TakeX() { return std::move(X_); }
  Mat TakeLambda() { return std::move(Lambda_); }
  Mat TakeU() { return std::move(U_); }

 private:
  bool euler() const { return docp_->integrator() == Integrator::kEuler; }
  // J of the trial controls trial_U_ into X_trial_ and cache_trial_ on trial_docp_'s grid; false
  // when a bound rejected it (then *J is not set).
  bool EvaluateTrial(double step, double threshold, double* J);
  // The constant bound's sum and suffix sums on `grid`.
  void ConstantBound(const TimeGrid& grid);
  // The running cost of (trial_U_, X_trial_) with caching; with `exit_above` finite it stops and
  // returns false once the partial sum plus suffix_[k + 1] plus phi exceeds it.
  bool TrialRunningCost(double phi, double exit_above, double* sum);
  double BackwardEuler(double* theta_scale, double eps);
  // The generic pointwise direction at one point: w (u* or the proximal minimizer) and the two
  // Hamiltonian values; f_ is scratch.
  void PointDirection(double t,
                      ConstVecRef x,
                      ConstVecRef u,
                      ConstVecRef p,
                      double eps,
                      VecRef w,
                      double* h_star,
                      double* h_now,
                      double* h_min);
  // The Euler states of trial_U_ from trial_x0_ into X_trial_ (the model's EulerStates, or
  // SimulateStatesFrom).
  void TrialStates();
  // J of the trial's ends: Phi(x_N) of X_trial_ plus phi0(trial_x0_) where it counts.
  double TrialEnds() const;
  // sigma_0 from the last move of x_0 (Backward, after g0_).
  void SpectralInitialStep();
  // nx_ doubles from `from` to `to` (a costate column).
  void CopyCostate(const double* from, double* to) const;

  const DiscreteOcp* docp_;                           // the iterate's discrete problem
  const DiscreteOcp* trial_docp_;                     // the trial's (docp_ unless T moves)
  std::unique_ptr<DiscreteOcp> owned_, owned_trial_;  // free final time: stretched grids
  const Ocp& ocp_;
  const EulerStageModel* model_;  // null when the problem offers none (or not Euler)
  const ProximalHamiltonianMinimizer* proximal_;   // the problem's closed form, or null
  std::unique_ptr<ConvexPointMinimizer> generic_;  // the proximal fallback, made when needed
  std::optional<double> bound_;  // Ocp::RunningCostLowerBound() (prefilter, Euler only)
  bool pointwise_;               // the model's pointwise bound is used (prefilter, Euler)
  bool affine_final_state_;      // x_N of every trial from one simulation (constant bound)
  int nx_, nu_, N_, cache_size_;
  double running_bound_ = 0.0;  // sum_k h_k m

  Mat U_, X_, Lambda_, D_;
  double J_ = 0.0;
  Mat trial_U_, X_trial_, cache_, cache_trial_, G_;
  Vec final_step_, x_bound_;    // x_N(U + D) - x_N(U), and a trial's x_N (affine_final_state_)
  std::vector<double> suffix_;  // suffix_[k] = sum_{j>=k} h_j m_j of the current trial
  std::vector<double> bounds_;  // m_k of the current trial (the pointwise bound)
  std::vector<double> terms_, scales_, mins_;  // mins_: h_k (H(u*_k) - H(u_k)) (proximal)
  double stationarity_theta_ = NAN, others_theta_ = 0.0;
  Vec lam_, tmp_x_, f_, Lx_, Lu_;
  Mat fx_, fu_;
  DescentWork work_;

  // Free final time.
  bool free_time_ = false;
  TimeGrid base_grid_;  // the grid the relative positions come from
  double T_lower_ = 0.0, T_upper_ = 0.0, sigma_ = NAN, initial_fraction_ = 0.1, growth_ = 2.0;
  double dJdT_ = 0.0;
  std::vector<double> nows_;  // H(x_k, u_k, lambda_{k+1}) of the last sweep

  // Free initial state (x0_, trial_x0_ are docp's initial_state() otherwise).
  bool free_initial_ = false;
  Vec x0_, trial_x0_, x0_lower_, x0_upper_, g0_, d0_, previous_x0_, previous_g0_;
  bool have_previous0_ = false;
  double sigma0_ = NAN, initial_fraction0_ = 0.1, growth0_ = 2.0;
};

}  // namespace ocpb
