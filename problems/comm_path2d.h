// Motion and communication co-optimization with path planning (OCPBench problem "comm-path2d"),
// and the power model it shares with "comm-fixed-path".
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "core/autodiff_ocp.h"
#include "core/euler_stage_model.h"
#include "core/parameters.h"
#include "core/proximal_hamiltonian.h"
#include "problems/channel/channel_quality.h"
#include "problems/comm_energy_model.h"
#include "problems/registry.h"

namespace ocpb {

/// The power model of Ali, Cai, Mostofi and Wardi (ACC 2016), Section II.A, with gamma on the
/// motion terms (the placement its Hamiltonian, minimizers and costate equations use; its Jbar
/// equation, gamma on communication, reads as a typo -- see problems/README-paper.md):
///
///   L = (2^R - 1)/K s(q)                                                    (transmission, W)
///     + gamma (k1 |u|^2 + k2 |v|^2 + k3 n(v) + k4 + k5 n(u) + k6 n(u) n(v))  (motion)
///
/// with K = -1.5 / ln(5 pb) (MQAM at bit error rate pb; pb = 2e-6 gives K = 0.130288), s(q) the
/// channel quality E[1/CNR] in W (ChannelQuality), and the motion power of Tokekar, Karnad and
/// Isler (ICRA 2011). Smoothing: |v| is not differentiable at v = 0, where the robot starts and
/// should end, so every norm in L is replaced by
///   n(v) = sqrt(|v|^2 + eps^2) - eps,
/// which is C-infinity, convex, 0 at 0, within eps of |v| everywhere, and has curvature at most
/// 1/eps. eps = 1e-3 (m/s or m/s^2) changes Jbar by at most gamma (k3 + k5 + ...) eps tf ~ 4e-3 on
/// the paper's scenario while keeping the Hessian bounded for the NLP methods. The smoothing is
/// part of the problem, so every method optimizes the same cost.
struct CommPowerModel {
  double gamma = 0.01;  ///< weight of motion power (> 0)
  std::array<double, 6> k = {17.75, 1.16, 10.46, 1175.0, 0.0, 0.0};  ///< k1..k6 (>= 0)
  double eps = 1e-3;                                                 ///< norm smoothing (> 0)
  double bit_error_rate = 2e-6;                                      ///< pb in (0, 0.2)

  /// K = -1.5 / ln(5 pb).
  double K() const;
  /// One-line reason in *error when a field violates its rule.
  bool IsValid(std::string* error) const;

  template <class T>
  T SmoothNorm(const T& squared_norm) const {
    return sqrt(squared_norm + eps * eps) - eps;
  }
  /// gamma (k1 |u|^2 + k2 |v|^2 + k3 n(v) + k4 + k5 n(u) + k6 n(u) n(v)) from |u|^2 and |v|^2.
  template <class T>
  T Motion(const T& acc2, const T& speed2) const {
    T m = k[0] * acc2 + k[1] * speed2 + k[3];
    if (k[2] != 0.0 || k[5] != 0.0) {
      const T nv = SmoothNorm(speed2);
      if (k[2] != 0.0) m += k[2] * nv;
      if (k[4] != 0.0 || k[5] != 0.0) {
        const T na = SmoothNorm(acc2);
        if (k[4] != 0.0) m += k[4] * na;
        if (k[5] != 0.0) m += k[5] * (na * nv);
      }
    } else if (k[4] != 0.0) {
      m += k[4] * SmoothNorm(acc2);
    }
    return gamma * m;
  }
  /// (2^R - 1)/K s, given inv_k = 1/K() (cached by the caller).
  template <class T>
  T Transmission(const T& rate, const T& s, double inv_k) const {
    if constexpr (std::is_same_v<T, double>) {
      return (std::exp2(rate) - 1.0) * (s * inv_k);
    } else {
      return (exp(0.69314718055994530942 * rate) - 1.0) * (s * inv_k);
    }
  }

  /// The magnitude r in [0, rmax] minimizing  -a r + gamma (k1 r^2 + (k5 + k6 nv) n(r))  for
  /// a = |p_u| (the part of H that depends on |u| when u = -r p_u/|p_u|). With k5 = k6 = 0 this
  /// is the paper's closed form r = min(a / (2 gamma k1), rmax); otherwise the stationarity
  /// equation 2 gamma k1 r + b r / sqrt(r^2 + eps^2) = a (b = gamma (k5 + k6 nv)) is solved by
  /// Newton's method from the soft-threshold point max(a - b, 0) / (2 gamma k1), which lies
  /// below the root; the left side is concave and increasing, so the iterates increase
  /// monotonically to the root (exact minimizer of the smoothed H, to roundoff).
  double AccelerationMagnitude(double a, double nv, double rmax) const;
  /// The same with `extra_curvature` c added to the quadratic: the minimizer of
  ///   -a r + gamma (k1 r^2 + (k5 + k6 nv) n(r)) + c r^2 / 2  over [0, rmax]
  /// (the proximal direction's magnitude, c = 1/eps; c = 0 gives AccelerationMagnitude's numbers).
  double AccelerationMagnitude(double a, double nv, double rmax, double extra_curvature) const;
  /// R = argmin_{0 <= R <= rmax} p3 R + (2^R - 1)/K s + (R - center)^2 / (2 eps), for eps > 0:
  /// the root of the increasing convex g'(R) = p3 + ln2 2^R s / K + (R - center) / eps, 0 when
  /// g'(0) >= 0, rmax when g'(rmax) <= 0, otherwise by Newton's method from rmax (where g' > 0;
  /// g' convex, so the iterates decrease monotonically to the root) until a step is below
  /// 1e-15 (1 + R). k = K().
  double ProximalRate(double p3, double s, double rmax, double k, double center, double eps) const;
  /// R* = argmin_{0 <= R <= rmax} p3 R + (2^R - 1)/K s = clip(log2(-p3 K / (ln2 s)), 0, rmax)
  /// (0 when p3 >= -ln2 s / K).
  double Rate(double p3, double s, double rmax) const;
  /// Rate() given k = K() (cached by the caller: K() takes a logarithm); the same numbers.
  double Rate(double p3, double s, double rmax, double k) const;
  /// Motion(acc2, speed2) given also nv = n(v) = SmoothNorm(speed2), computed by the caller
  /// (for a double, with the same operations: the same numbers, bitwise).
  double Motion(double acc2, double speed2, double nv) const;
};

/// A deterministic path-loss-only channel (no shadowing, no multipath), for tests and as the
/// `channel = 0` option:
///   Gamma_dB(q) = K_PL - 10 n_PL log10 d(q),  d(q) = sqrt(|q - q_b|^2 + d0^2)  (smooth floor d0),
///   CNR = 10^(Gamma_dB/10) / N0 (mW),  s(q) = 1/CNR / 1000  (W: the transmit power is in watts)
///       = A (|q - q_b|^2 + d0^2)^(n_PL/2),  A = N0 10^(-K_PL/10) / 1000.
/// Defaults: the paper's K_PL = -41.34, n_PL = 3.86, N0 = -110 dBm, base (5, 5), d0 = 0.1 m.
class PathLossChannel final : public ChannelQuality {
 public:
  PathLossChannel(const Eigen::Vector2d& base = Eigen::Vector2d(5.0, 5.0),
                  double k_pl = -41.34,
                  double n_pl = 3.86,
                  double noise_dbm = -110.0,
                  double floor = 0.1);
  void Evaluate(const Eigen::Vector2d& q,
                double* s,
                Eigen::Vector2d* grad,
                Eigen::Matrix2d* hess) const override;
  std::string Describe() const override;

 private:
  Eigen::Vector2d base_;
  double k_pl_, n_pl_, noise_dbm_, floor_, scale_;
};

/// minimize   J = int_0^tf L(x1, x2, u, R) dt
///                + C1 |x1(tf) - D|^2 + C2 |x2(tf)|^2 + C3 (x3(tf) - c)^2
/// subject to x1' = x2, x2' = u, x3' = R,  x1(t0) = S, x2(t0) = v0, x3(t0) = b0,
///            |u| <= umax,  0 <= R <= Rmax,
/// on [t0, tf] (defaults t0 = 0, v0 = 0, b0 = 0: the paper's offline problem from rest; the online
/// re-planning of the paper's Section IV poses the cost-to-go J_{t0} from the current position,
/// velocity and bits already sent, with the same terminal target c),
/// with L of CommPowerModel and s(x1) from a ChannelQuality (Ali, Cai, Mostofi, Wardi, ACC 2016,
/// Sections II-III). State (x1 position in R^2, x2 velocity in R^2, x3 bits/Hz sent): 5; control
/// (u acceleration in R^2, R spectral efficiency): 3. Terminal constraints psi = (x1 - D, x2,
/// x3 - c) with penalty weights (C1, C1, C2, C2, C3): the penalty (paper) and hard forms come from
/// this one definition. Jbar = int L (phi = 0).
///
/// Hamiltonian minimizer (exact for the smoothed L, any k5, k6 >= 0): with p = (p1, p2, p3),
///   u* = -r p2/|p2|, r = CommPowerModel::AccelerationMagnitude(|p2|, n(x2), umax)
///        (= -p2 / (2 gamma k1) clipped to |u| <= umax when k5 = k6 = 0, the paper's formula);
///   R* = log2(-p3 K / (ln2 s(x1))) clipped to [0, Rmax].
/// Paper defaults: S = (20, 40), D = (10, 5), c = 150, tf = 40 s, umax = 0.5, Rmax = 6,
/// gamma = 0.01, C = (10, 50, 10), k = (17.75, 1.16, 10.46, 1175, 0, 0), N = 400 (dt = 0.1).
/// From u = 0, R = 0 the cost is C1 |S - D|^2 + C3 c^2 + gamma k4 tf = 238720 (paper: 2.3872e5).
///
/// EulerStageModel (the descent's fast path on a forward-Euler grid): a trial's running-cost
/// pass keeps, per grid point, s(x1) and grad s (one channel evaluation), 2^R - 1, the motion
/// power and sqrt(|x2|^2 + eps^2); the backward sweep at the accepted points reuses them, so the
/// channel is not evaluated again there. The pointwise bound is the motion power (the
/// transmission term, >= 0 on U, is what it leaves out).
class CommPath2d final : public AutoDiffOcp<CommPath2d, 5, 3, 5, 0>,
                         public EulerStageModel,
                         public ProximalHamiltonianMinimizer,
                         public CommEnergyModel {
 public:
  struct Options {
    Eigen::Vector2d start{20.0, 40.0};          ///< S, in the workspace
    Eigen::Vector2d destination{10.0, 5.0};     ///< D, in the workspace
    double bits = 150.0;                        ///< c = Q/B in bits/Hz (>= 0)
    double tf = 40.0;                           ///< horizon in s (> 0)
    double umax = 0.5;                          ///< acceleration bound in m/s^2 (> 0)
    double rmax = 6.0;                          ///< spectral-efficiency bound in bits/s/Hz (> 0)
    Eigen::Vector3d penalty{10.0, 50.0, 10.0};  ///< C1, C2, C3 (> 0)
    double workspace = 50.0;                    ///< S and D must lie in [0, workspace]^2
    double t0 = 0.0;                            ///< initial time (finite, 0 <= t0 < tf)
    Eigen::Vector2d v0{0.0, 0.0};               ///< x2(t0), initial velocity in m/s (finite)
    double bits_sent = 0.0;                     ///< x3(t0), bits/Hz already sent (finite, >= 0)
    CommPowerModel power;

    bool IsValid(std::string* error) const;
  };

  /// Throws std::invalid_argument (one line naming the field) on invalid options or a null channel.
  CommPath2d(const Options& options, std::shared_ptr<const ChannelQuality> channel);

  std::string name() const override { return "comm-path2d"; }
  const Options& options() const { return options_; }
  const ChannelQuality& channel() const { return *channel_; }

  template <class T>
  void EvalDynamics(double, const VecT<T, 5>& x, const VecT<T, 3>& u, VecT<T, 5>* f) const {
    (*f)[0] = x[2];
    (*f)[1] = x[3];
    (*f)[2] = u[0];
    (*f)[3] = u[1];
    (*f)[4] = u[2];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 5>& x, const VecT<T, 3>& u) const {
    const T s = ChannelAt(x[0], x[1]);
    const T acc2 = u[0] * u[0] + u[1] * u[1];
    const T speed2 = x[2] * x[2] + x[3] * x[3];
    return options_.power.Transmission(u[2], s, inv_k_) + options_.power.Motion(acc2, speed2);
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 5>& x, VecT<T, 5>* psi) const {
    (*psi)[0] = x[0] - options_.destination[0];
    (*psi)[1] = x[1] - options_.destination[1];
    (*psi)[2] = x[2];
    (*psi)[3] = x[3];
    (*psi)[4] = x[4] - options_.bits;
  }

  // Hand-written values and first derivatives (the Hamiltonian descent's hot loops call these;
  // they are about 5x faster than the Jet1 versions and are checked against finite differences
  // and against the template above in tests/problems/comm_path2d_test.cc). The terminal
  // Hessian comes from AD of the template.
  void Dynamics(double t, ConstVecRef x, ConstVecRef u, VecRef f) const override;
  double RunningCost(double t, ConstVecRef x, ConstVecRef u) const override;
  void DynamicsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef f, MatRef fx, MatRef fu) const override;
  void RunningCostGradient(
      double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const override;
  /// sigma L_zz in closed form (comm_path2d_hessian.cc): the dynamics are affine, so lambda
  /// (and mu: there are no path constraints) contribute nothing. 958 instructions per point
  /// with the map's Hessian, against 18,256 for the Jet2 pass (callgrind, Ipopt + Euler at
  /// N = 400); tested against finite differences and the AD Hessian.
  void PointHessian(double t,
                    ConstVecRef x,
                    ConstVecRef u,
                    double sigma,
                    ConstVecRef lambda,
                    ConstVecRef mu,
                    MatRef hess) const override;

  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override;
  /// One channel evaluation at x1 (with its gradient) serves u*, f and L's gradient (the
  /// default makes two); the same numbers bitwise.
  void MinimizeHamiltonianWithGradients(double t,
                                        ConstVecRef x,
                                        ConstVecRef p,
                                        VecRef u,
                                        VecRef f,
                                        MatRef fx,
                                        MatRef fu,
                                        double* L,
                                        VecRef Lx,
                                        VecRef Lu) const override;
  /// One channel evaluation at x1 serves u* and both values of H (the default makes three).
  void MinimizeAndCompareHamiltonian(double t,
                                     ConstVecRef x,
                                     ConstVecRef p,
                                     ConstVecRef u,
                                     VecRef u_star,
                                     double* h_star,
                                     double* h_now,
                                     VecRef f) const override;
  /// x1' = x2, x2' = u, x3' = R.
  bool HasAffineDynamics() const override { return true; }
  /// gamma k4: every other term of L is >= 0 on U (R >= 0, s = E[1/CNR] > 0, k_i >= 0, n >= 0).
  std::optional<double> RunningCostLowerBound() const override {
    return options_.power.gamma * options_.power.k[3];
  }
  /// The straight segment from the start to D at constant speed (BaselineAccelerations: the
  /// shortest speed-up and braking |u| <= umax allows, ending at D at rest on the Euler grid)
  /// and the constant rate that sends the remaining bits by tf (BaselineRate). Needs a uniform
  /// grid spanning [t0, tf] and a start at rest (v0 = 0).
  std::optional<ControlTrajectory> BaselinePlan(const TimeGrid& grid,
                                                std::string* why_not) const override;

  // ---- CommEnergyModel ----
  Eigen::Vector2d Position(ConstVecRef x) const override { return Eigen::Vector2d(x[0], x[1]); }
  double MotionPower(ConstVecRef x, ConstVecRef u) const override {
    return options_.power.Motion(u[0] * u[0] + u[1] * u[1], x[2] * x[2] + x[3] * x[3]);
  }
  double TransmitPower(ConstVecRef u, double s) const override {
    return options_.power.Transmission(u[2], s, inv_k_);
  }

  // ---- EulerStageModel (see the class comment) ----
  /// s, ds/dq1, ds/dq2, 2^R - 1, the motion power, sqrt(|x2|^2 + eps^2).
  int StageCacheSize() const override { return kStageCache; }
  void EulerStep(
      double t, double h, const double* x, const double* u, double* x_next) const override;
  /// EulerStep's arithmetic in one loop (nx = 5, nu = 3).
  void EulerStates(const TimeGrid& grid, int nx, int nu, const double* U, double* X) const override;
  double RunningCostCaching(double t,
                            const double* x,
                            const double* u,
                            double* cache) const override;
  /// The motion power gamma (k1 |u|^2 + ...): L minus the transmission term (2^R - 1)/K s >= 0.
  double PointwiseRunningCostBound(double t, const double* x, const double* u) const override;
  /// PointwiseRunningCostBound's arithmetic in one loop.
  void PointwiseRunningCostBounds(const TimeGrid& grid,
                                  int nx,
                                  int nu,
                                  const double* X,
                                  const double* U,
                                  double* m) const override;
  void BackwardPoint(double t,
                     double h,
                     const double* x,
                     const double* u,
                     const double* cache,
                     double eps,
                     double* p,
                     double* u_star,
                     double* h_star,
                     double* h_now,
                     double* h_min) const override;

  /// The proximal minimizer of the smoothed H (exact, any k5, k6 >= 0): separable like u*, with
  /// q = p2 - center_u / eps in place of p2 and 2 gamma k1 + 1/eps as the quadratic's curvature,
  ///   w_u = -r q/|q|,  r = CommPowerModel::AccelerationMagnitude(|q|, n(x2), umax, 1/eps),
  ///   w_R = CommPowerModel::ProximalRate(p3, s(x1), Rmax, K, center_R, eps).
  void MinimizeProximalHamiltonian(double t,
                                   ConstVecRef x,
                                   ConstVecRef p,
                                   ConstVecRef center,
                                   double eps,
                                   VecRef w) const override;

  /// s(q) as a double or a jet (value, gradient and Hessian from the channel, by the chain rule).
  template <class T>
  T ChannelAt(const T& qx, const T& qy) const {
    const Eigen::Vector2d q(ValueOf(qx), ValueOf(qy));
    double s = 0.0;
    if constexpr (std::is_same_v<T, double>) {
      channel_->Evaluate(q, &s, nullptr, nullptr);
      return s;
    } else {
      Eigen::Vector2d g;
      Eigen::Matrix2d h = Eigen::Matrix2d::Zero();
      if constexpr (requires { qx.h; }) {
        channel_->Evaluate(q, &s, &g, &h);
      } else {
        channel_->Evaluate(q, &s, &g, nullptr);
      }
      return ApplyBinary(qx, qy, s, g, h);
    }
  }

 private:
  static constexpr int kStageCache = 6;
  /// x_next = x + h f(x, u), shared by EulerStep and EulerStates.
  static void EulerStepOf(double h, const double* x, const double* u, double* x_next) {
    x_next[0] = x[0] + h * x[2];
    x_next[1] = x[1] + h * x[3];
    x_next[2] = x[2] + h * u[0];
    x_next[3] = x[3] + h * u[1];
    x_next[4] = x[4] + h * u[2];
  }
  /// u* of MinimizeHamiltonian given s = s(x1).
  void MinimizerGivenChannel(ConstVecRef x, ConstVecRef p, double s, VecRef u) const;
  /// The same given also nv = n(x2), the smoothed speed (p, u: raw arrays of 5 and 3).
  void MinimizerGivenChannel(const double* p, double s, double nv, double* u) const;
  /// MinimizeProximalHamiltonian given s and nv (raw arrays of 5, 3 and 3).
  void ProximalMinimizerGivenChannel(
      const double* p, double s, double nv, const double* center, double eps, double* w) const;
  /// RunningCostGradient given s = s(x1) and its gradient.
  void RunningCostGradientGivenChannel(ConstVecRef x,
                                       ConstVecRef u,
                                       double s,
                                       const Eigen::Vector2d& grad_s,
                                       double* L,
                                       VecRef Lx,
                                       VecRef Lu) const;
  /// H(x, u, p) given s = s(x1), with the operations of Dynamics and RunningCost.
  double HamiltonianGivenChannel(ConstVecRef x, ConstVecRef p, ConstVecRef u, double s) const;

  Options options_;
  double k_, inv_k_;  // K() and 1 / K()
  std::shared_ptr<const ChannelQuality> channel_;
};

// ---- registry support (shared with comm-fixed-path) -----------------------------------------

/// The parameters both communication problems share: S, D, base, c, tf, umax, Rmax, gamma,
/// C (3), k (6), eps, pb, channel (0: PathLossChannel, deterministic; 1: the paper's channel
/// simulated with realization `seed`, measured at `samples` random points and predicted exactly by
/// the Gaussian process; 2: the same prediction through its bicubic map, the default), samples,
/// estimate (1: predictor parameters estimated from the samples; 0: the true ones), the
/// channel constants K_PL, n_PL, xi, eta, rho, N0_dBm, and the experiment's settings: workspace
/// (side of [0, W]^2; S, D and base must lie in it), grid_step (simulation grid), rician_K,
/// distance_floor, estimator (0 binned, 1 ML, 2 REML), bin_width and min_pairs (binned fit).
std::vector<ParameterSpec> CommParameterSpecs();
/// The CommPowerModel and shared fields of `params`.
CommPowerModel CommPowerFromParameters(const Parameters& params);
/// The channel `params` asks for, with realization `seed` (ignored by the path-loss channel).
/// Throws std::invalid_argument naming the field on invalid values.
/// Channels 1 and 2 are kept in ChannelCache::Global() under CommChannelKey: a suite's cases of
/// one seed and channel build it once.
std::shared_ptr<const ChannelQuality> MakeCommChannel(const Parameters& params, std::uint64_t seed);
/// The cache key of the channel `params` and `seed` define: the seed and the values of every
/// shared comm parameter except the task's and the motion model's (S, D, c, tf, umax, Rmax,
/// gamma, C, k, eps, pb).
std::string CommChannelKey(const Parameters& params, std::uint64_t seed);
/// The true channel of `params` and realization `seed`, what plans made on MakeCommChannel's
/// prediction really pay: channel 0 (deterministic path loss) is its own truth; channels 1 and
/// 2 give the TrueChannelQuality of the realization MakeCommChannel simulates (the same
/// SimulateChannel call, so the same cells as the online driver's OnlineChannel of that seed).
/// Cached in ChannelCache::Global() beside the predictions (about 2 MB at the paper's grid).
std::shared_ptr<const ChannelQuality> MakeCommTrueChannel(const Parameters& params,
                                                          std::uint64_t seed);
/// Runs the checks of MakeCommChannel without simulating anything and returns a path-loss
/// stand-in with the same base station and constants (for ProblemInfo::make_for_checks).
std::shared_ptr<const ChannelQuality> MakeCommChannelForChecks(const Parameters& params);
/// CommPath2d::Options from the parameters of comm-path2d (its registry specs), without the
/// channel (not validated here: the CommPath2d constructor does).
CommPath2d::Options CommPath2dOptionsFromParameters(const Parameters& params);
/// The registry entry of comm-path2d.
ProblemInfo CommPath2dProblemInfo();

}  // namespace ocpb
