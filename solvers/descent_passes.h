// The passes of one Hamiltonian-descent iteration (simulation, backward sweep, Armijo trials)
// with their workspace, shared by the descent and the methods built on it.
#pragma once

#include <optional>
#include <vector>

#include "core/discrete_ocp.h"
#include "core/euler_stage_model.h"

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
class DescentPasses {
 public:
  /// `docp` must outlive this object. `prefilter`: use the lower bounds above (Euler only).
  DescentPasses(const DiscreteOcp& docp, bool prefilter);

  /// U (nu x N, in U) becomes the iterate; returns J(U) (NaN/inf when not finite).
  double Start(const Mat& U);
  /// Fills Lambda and D at the iterate and returns theta; *theta_scale (may be null) receives
  /// sum_k h_k (|H(u*_k)| + |H(u_k)|).
  double Backward(double* theta_scale);
  /// The Armijo search along D (Backward first). Returns the accepted exponent, or -1 when no
  /// exponent <= rule.max_exponent gives sufficient decrease (the iterate is then unchanged).
  int Armijo(const ArmijoRule& rule, double theta);

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
  bool euler() const { return docp_.integrator() == Integrator::kEuler; }
  // J of the trial controls trial_U_ into X_trial_ and cache_trial_; false when a bound rejected
  // it (then *J is not set).
  bool EvaluateTrial(double step, double threshold, double* J);
  // The running cost of (trial_U_, X_trial_) with caching; with `exit_above` finite it stops and
  // returns false once the partial sum plus suffix_[k + 1] plus phi exceeds it.
  bool TrialRunningCost(double phi, double exit_above, double* sum);
  double BackwardEuler(double* theta_scale);
  // The Euler states of trial_U_ into X_trial_ (the model's EulerStep, or SimulateStates).
  void TrialStates();

  const DiscreteOcp& docp_;
  const Ocp& ocp_;
  const EulerStageModel* model_;  // null when the problem offers none (or not Euler)
  std::optional<double> bound_;   // Ocp::RunningCostLowerBound() (prefilter, Euler only)
  bool pointwise_;                // the model's pointwise bound is used (prefilter, Euler)
  bool affine_final_state_;       // x_N of every trial from one simulation (constant bound)
  int nx_, nu_, N_, cache_size_;
  double running_bound_ = 0.0;  // sum_k h_k m

  Mat U_, X_, Lambda_, D_;
  double J_ = 0.0;
  Mat trial_U_, X_trial_, cache_, cache_trial_, G_;
  Vec final_step_, x_bound_;    // x_N(U + D) - x_N(U), and a trial's x_N (affine_final_state_)
  std::vector<double> suffix_;  // suffix_[k] = sum_{j>=k} h_j m_j of the current trial
  std::vector<double> terms_, scales_;
  Vec lam_, tmp_x_, f_, Lx_, Lu_;
  Mat fx_, fu_;
  DescentWork work_;
};

}  // namespace ocpb
