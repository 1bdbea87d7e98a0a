// The passes of the Hamiltonian descent on a Runge-Kutta discretization with one control per
// stage (StageRkOcp): the family's descent and proximal direction beyond forward Euler.
#pragma once

#include <limits>
#include <memory>

#include "core/proximal_hamiltonian.h"
#include "core/stage_rk_ocp.h"
#include "core/timer.h"
#include "solvers/convex_point_minimizer.h"
#include "solvers/descent_passes.h"

namespace ocpb {

/// One iterate U (nu x sN, the stage controls) of the descent on a StageRkOcp, with its states,
/// cost, node and stage costates and direction; the interface RunDescentLoop uses (Start,
/// Backward, Armijo), as DescentPasses on forward Euler:
///
///  - Backward(): the transformed adjoint (StageRkOcp::Adjoint), then at every stage the pointwise
///    minimization of H with the stage's own state and costate,
///      u*_{k,i} = argmin_{w in U} H(t_{k,i}, y_{k,i}, w, lambda_{k,i}),
///    d_{k,i} = u*_{k,i} - u_{k,i}, and theta = sum_{k,i} h_k b_i [H(u*_{k,i}) - H(u_{k,i})].
///    Since dJ/du_{k,i} = h_k b_i H_u(stage) and H is convex in u, the directional derivative of
///    J along d is <= theta (<= 0, and 0 only where every stage control minimizes its H): the
///    Armijo search ends when theta < 0, exactly as on the Euler grid. With a finite eps the
///    direction is the proximal one, w_{k,i} = argmin_w H(stage) + |w - u_{k,i}|^2 / (2 eps)
///    (the problem's ProximalHamiltonianMinimizer, else ConvexPointMinimizer), and
///    stationarity_theta() holds the paper's theta as for DescentPasses.
///  - Armijo(rule, theta): U + s D with s = 1, beta, ..., J(U + s D) - J(U) <= alpha s theta.
///
/// Free final time (EnableFreeFinalTime): as DescentPasses', T a variable with the grid's relative
/// positions s_k kept, and the exact derivative of the scheme's J (autonomous problem)
///   dJ/dT = sum_k (s_{k+1} - s_k) dJ/dh_k      (StageRkOcp::Adjoint's dJdh),
/// the joint Armijo step on (U, T) with d_T = P_[lower, upper](T - sigma dJ/dT) - T and sigma's
/// schedule, and T's share of the stationarity measure.
///
/// No prefilter and no stage model (forward Euler's fast paths).
class StageDescentPasses {
 public:
  /// `srk` must outlive this object; `proximal` may be null.
  StageDescentPasses(const StageRkOcp& srk, const ProximalHamiltonianMinimizer* proximal);

  /// As DescentPasses::EnableFreeFinalTime (throws std::invalid_argument unless
  /// t0 < lower <= T <= upper, finite; initial_fraction > 0, growth >= 1). Call before Start.
  void EnableFreeFinalTime(double lower,
                           double upper,
                           double initial_fraction = 0.1,
                           double growth = 2.0);
  bool free_final_time() const { return free_time_; }
  double T() const { return srk_->grid().tf(); }
  double dJdT() const { return dJdT_; }

  double Start(const Mat& U);
  double Backward(double* theta_scale, double eps = std::numeric_limits<double>::infinity());
  double stationarity_theta() const { return stationarity_theta_; }
  /// A free final time's share of stationarity_theta() (DescentPasses::others_theta).
  double others_theta() const { return others_theta_; }
  int Armijo(const ArmijoRule& rule, double theta, const CpuLimit& limit = {});
  static constexpr int kOutOfTime = DescentPasses::kOutOfTime;

  const StageRkOcp& srk() const { return *srk_; }
  const TimeGrid& grid() const { return srk_->grid(); }
  const Mat& U() const { return U_; }
  const Mat& X() const { return X_; }
  /// Node costates lambda_k (nx x (N+1)) and stage costates lambda_{k,i} (nx x sN) of the last
  /// Backward.
  const Mat& Lambda() const { return Lambda_; }
  const Mat& StageCostates() const { return P_; }
  /// dJ/dU of the last Backward (nu x sN).
  const Mat& Gradient() const { return G_; }
  const Mat& D() const { return D_; }
  double J() const { return J_; }
  const DescentWork& work() const { return work_; }

 private:
  const StageRkOcp* srk_;  // the iterate's (a stretched copy once T moved)
  const Ocp& ocp_;
  std::unique_ptr<StageRkOcp> owned_;
  bool free_time_ = false;
  TimeGrid base_grid_;
  double T_lower_ = 0.0, T_upper_ = 0.0, sigma_ = NAN, initial_fraction_ = 0.1, growth_ = 2.0;
  double dJdT_ = 0.0;
  Vec dJdh_;
  const ProximalHamiltonianMinimizer* proximal_;
  std::unique_ptr<ConvexPointMinimizer> generic_;
  Mat U_, X_, Lambda_, Y_, P_, G_, D_, trial_U_, X_trial_;
  double J_ = 0.0;
  double stationarity_theta_ = NAN, others_theta_ = 0.0;
  Vec f_;
  DescentWork work_;
};

}  // namespace ocpb
