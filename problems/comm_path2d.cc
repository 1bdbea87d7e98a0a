#include "problems/comm_path2d.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/invalid.h"
#include "problems/channel/channel_memory.h"
#include "problems/channel/measurement_sampling.h"
#include "problems/channel/paper_channel.h"
#include "problems/channel/true_channel.h"
#include "problems/comm_channel_cache.h"

namespace ocpb {
namespace {

constexpr double kLn2 = 0.69314718055994530942;

std::string Str(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// "C1", "k3": built with a stream (GCC 12 warns falsely on "C" + std::to_string(i)).
std::string Indexed(const char* name, int i) {
  std::ostringstream os;
  os << name << i;
  return os.str();
}

bool InSquare(const Eigen::Vector2d& q, double side) {
  return q.allFinite() && q.minCoeff() >= 0.0 && q.maxCoeff() <= side;
}

}  // namespace

// ---- CommPowerModel ---------------------------------------------------------------------

double CommPowerModel::K() const { return -1.5 / std::log(5.0 * bit_error_rate); }

bool CommPowerModel::IsValid(std::string* error) const {
  if (!(gamma > 0.0) || !std::isfinite(gamma)) {
    return Invalid(error, "gamma must be finite and > 0");
  }
  for (int i = 0; i < 6; ++i) {
    if (!(k[i] >= 0.0) || !std::isfinite(k[i])) {
      return Invalid(error, Indexed("k", i + 1) + " must be finite and >= 0");
    }
  }
  if (!(eps > 0.0) || !std::isfinite(eps)) return Invalid(error, "eps must be finite and > 0");
  if (!(bit_error_rate > 0.0 && bit_error_rate < 0.2)) {
    return Invalid(error, "pb (bit error rate) must lie in (0, 0.2) so that K > 0");
  }
  return true;
}

double CommPowerModel::AccelerationMagnitude(double a, double nv, double rmax) const {
  return AccelerationMagnitude(a, nv, rmax, 0.0);
}

double CommPowerModel::AccelerationMagnitude(double a,
                                             double nv,
                                             double rmax,
                                             double extra_curvature) const {
  if (!(a > 0.0)) return a == 0.0 ? 0.0 : a;  // NaN propagates
  const double c2 = 2.0 * gamma * k[0] + extra_curvature;
  const double b = gamma * (k[4] + k[5] * nv);
  if (b == 0.0) return c2 > 0.0 ? std::min(a / c2, rmax) : rmax;
  // Stationarity of the smoothed H along -p_u: g(r) = c2 r + b r / sqrt(r^2 + eps^2) - a = 0.
  const double e2 = eps * eps;
  auto g = [&](double r) { return c2 * r + b * r / std::sqrt(r * r + e2) - a; };
  if (g(rmax) <= 0.0) return rmax;
  double r = c2 > 0.0 ? std::max(a - b, 0.0) / c2 : 0.0;  // soft threshold: g(r) <= 0
  for (int i = 0; i < 100; ++i) {
    const double q = std::sqrt(r * r + e2);
    const double step = -(c2 * r + b * r / q - a) / (c2 + b * e2 / (q * q * q));
    r += step;
    if (step <= 1e-15 * (r + eps)) break;
  }
  return std::clamp(r, 0.0, rmax);
}

double CommPowerModel::Rate(double p3, double s, double rmax) const {
  return Rate(p3, s, rmax, K());
}

double CommPowerModel::Rate(double p3, double s, double rmax, double k_mqam) const {
  if (std::isnan(p3) || std::isnan(s)) return NAN;
  if (s <= 0.0) return p3 < 0.0 ? rmax : 0.0;
  // dH/dR = p3 + ln2 2^R s / K = 0  =>  2^R = -p3 K / (ln2 s).
  const double arg = -p3 * k_mqam / (kLn2 * s);
  if (!(arg > 1.0)) return 0.0;
  return std::min(std::log2(arg), rmax);
}

double CommPowerModel::ProximalRate(
    double p3, double s, double rmax, double k_mqam, double center, double eps) const {
  if (std::isnan(p3) || std::isnan(s) || std::isnan(center)) return NAN;
  const double c = kLn2 * s / k_mqam;  // d/dR (2^R - 1) s / K = c 2^R
  auto slope = [&](double r) { return p3 + c * std::exp2(r) + (r - center) / eps; };
  if (slope(0.0) >= 0.0) return 0.0;
  if (slope(rmax) <= 0.0) return rmax;
  double r = rmax;
  for (int i = 0; i < 100; ++i) {
    const double step = slope(r) / (kLn2 * c * std::exp2(r) + 1.0 / eps);
    r -= step;
    if (!(std::abs(step) > 1e-15 * (1.0 + r))) break;
  }
  return std::clamp(r, 0.0, rmax);
}

double CommPowerModel::Motion(double acc2, double speed2, double nv) const {
  // Motion<double>(acc2, speed2) with SmoothNorm(speed2) replaced by nv: the same operations.
  double m = k[0] * acc2 + k[1] * speed2 + k[3];
  if (k[2] != 0.0 || k[5] != 0.0) {
    if (k[2] != 0.0) m += k[2] * nv;
    if (k[4] != 0.0 || k[5] != 0.0) {
      const double na = SmoothNorm(acc2);
      if (k[4] != 0.0) m += k[4] * na;
      if (k[5] != 0.0) m += k[5] * (na * nv);
    }
  } else if (k[4] != 0.0) {
    m += k[4] * SmoothNorm(acc2);
  }
  return gamma * m;
}

// ---- PathLossChannel ----------------------------------------------------------------------

PathLossChannel::PathLossChannel(
    const Eigen::Vector2d& base, double k_pl, double n_pl, double noise_dbm, double floor)
    : base_(base), k_pl_(k_pl), n_pl_(n_pl), noise_dbm_(noise_dbm), floor_(floor) {
  if (!base.allFinite() || !std::isfinite(k_pl) || !std::isfinite(n_pl) ||
      !std::isfinite(noise_dbm)) {
    throw std::invalid_argument("PathLossChannel: base, K_PL, n_PL and N0 must be finite");
  }
  if (!(floor > 0.0)) throw std::invalid_argument("PathLossChannel: floor must be > 0");
  // s = N0[mW] 10^(-K_PL/10) d^n / 1000.
  scale_ = std::pow(10.0, noise_dbm / 10.0) * std::pow(10.0, -k_pl / 10.0) / 1000.0;
}

void PathLossChannel::Evaluate(const Eigen::Vector2d& q,
                               double* s,
                               Eigen::Vector2d* grad,
                               Eigen::Matrix2d* hess) const {
  const Eigen::Vector2d r = q - base_;
  const double rho = r.squaredNorm() + floor_ * floor_;
  const double half_n = 0.5 * n_pl_;
  const double v = scale_ * std::exp(half_n * std::log(rho));
  *s = v;
  // d/dq rho^(n/2) = n rho^(n/2 - 1) r;  d2 = n rho^(n/2 - 2) (rho I + (n - 2) r r^T).
  if (grad) *grad = (n_pl_ * v / rho) * r;
  if (hess) {
    *hess = (n_pl_ * v / (rho * rho)) *
            (rho * Eigen::Matrix2d::Identity() + (n_pl_ - 2.0) * r * r.transpose());
  }
}

std::string PathLossChannel::Describe() const {
  return "path-loss only: K_PL=" + Str(k_pl_) + " n_PL=" + Str(n_pl_) + " N0=" + Str(noise_dbm_) +
         " dBm base=(" + Str(base_[0]) + "," + Str(base_[1]) + ") floor=" + Str(floor_) + " m";
}

// ---- CommPath2d ---------------------------------------------------------------------------

bool CommPath2d::Options::IsValid(std::string* error) const {
  if (!(workspace > 0.0)) return Invalid(error, "workspace must be > 0");
  if (!InSquare(start, workspace)) {
    return Invalid(error, "S must lie in the workspace [0, " + Str(workspace) + "]^2");
  }
  if (!InSquare(destination, workspace)) {
    return Invalid(error, "D must lie in the workspace [0, " + Str(workspace) + "]^2");
  }
  if (!(bits >= 0.0) || !std::isfinite(bits)) return Invalid(error, "c must be finite and >= 0");
  if (!(tf > 0.0) || !std::isfinite(tf)) return Invalid(error, "tf must be finite and > 0");
  if (!(t0 >= 0.0) || !(t0 < tf)) return Invalid(error, "t0 must satisfy 0 <= t0 < tf");
  if (!v0.allFinite()) return Invalid(error, "v0 must be finite");
  if (!(bits_sent >= 0.0) || !std::isfinite(bits_sent)) {
    return Invalid(error, "x3_0 (bits already sent) must be finite and >= 0");
  }
  if (!(umax > 0.0) || !std::isfinite(umax)) return Invalid(error, "umax must be finite and > 0");
  if (!(rmax > 0.0) || !std::isfinite(rmax)) return Invalid(error, "Rmax must be finite and > 0");
  for (int i = 0; i < 3; ++i) {
    if (!(penalty[i] > 0.0) || !std::isfinite(penalty[i])) {
      return Invalid(error, Indexed("C", i + 1) + " must be finite and > 0");
    }
  }
  return power.IsValid(error);
}

CommPath2d::CommPath2d(const Options& options, std::shared_ptr<const ChannelQuality> channel)
    : options_(options), k_(options.power.K()), inv_k_(1.0 / k_), channel_(std::move(channel)) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("comm-path2d: " + error);
  if (!channel_) throw std::invalid_argument("comm-path2d: channel must not be null");
  SetDimensions(5, 3, 5, 0);
  SetHorizon(options_.t0, options_.tf);
  Vec x0 = Vec::Zero(5);
  x0.head<2>() = options_.start;
  x0.segment<2>(2) = options_.v0;
  x0[4] = options_.bits_sent;
  SetInitialState(x0);
  Vec w(5);
  w << options_.penalty[0], options_.penalty[0], options_.penalty[1], options_.penalty[1],
      options_.penalty[2];
  SetTerminalWeights(w);
  ControlSet set;
  set.AddBall(2, options_.umax);
  set.AddBox(Vec::Zero(1), Vec::Constant(1, options_.rmax));
  SetControlSet(set);
}

void CommPath2d::Dynamics(double, ConstVecRef x, ConstVecRef u, VecRef f) const {
  f[0] = x[2];
  f[1] = x[3];
  f[2] = u[0];
  f[3] = u[1];
  f[4] = u[2];
}

double CommPath2d::RunningCost(double, ConstVecRef x, ConstVecRef u) const {
  double s = 0.0;
  channel_->Evaluate(Eigen::Vector2d(x[0], x[1]), &s, nullptr, nullptr);
  const double acc2 = u[0] * u[0] + u[1] * u[1];
  const double speed2 = x[2] * x[2] + x[3] * x[3];
  return options_.power.Transmission(u[2], s, inv_k_) + options_.power.Motion(acc2, speed2);
}

void CommPath2d::DynamicsJacobian(
    double t, ConstVecRef x, ConstVecRef u, VecRef f, MatRef fx, MatRef fu) const {
  Dynamics(t, x, u, f);
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 5; ++i) fx(i, j) = (i == 0 && j == 2) || (i == 1 && j == 3) ? 1.0 : 0.0;
  }
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 5; ++i) fu(i, j) = i == j + 2 ? 1.0 : 0.0;
  }
}

void CommPath2d::RunningCostGradient(
    double, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const {
  double s = 0.0;
  Eigen::Vector2d grad_s;
  channel_->Evaluate(Eigen::Vector2d(x[0], x[1]), &s, &grad_s, nullptr);
  RunningCostGradientGivenChannel(x, u, s, grad_s, L, Lx, Lu);
}

void CommPath2d::RunningCostGradientGivenChannel(ConstVecRef x,
                                                 ConstVecRef u,
                                                 double s,
                                                 const Eigen::Vector2d& grad_s,
                                                 double* L,
                                                 VecRef Lx,
                                                 VecRef Lu) const {
  const CommPowerModel& m = options_.power;
  // Transmission (2^R - 1)/K s: d/dq = (2^R - 1)/K grad s, d/dR = ln2 2^R s / K.
  const double two_r = std::exp2(u[2]);
  const double factor = (two_r - 1.0) * inv_k_;
  // Motion: n(w) = sqrt(|w|^2 + eps^2) - eps, grad n = w / sqrt(|w|^2 + eps^2).
  const double acc2 = u[0] * u[0] + u[1] * u[1];
  const double speed2 = x[2] * x[2] + x[3] * x[3];
  const double e2 = m.eps * m.eps;
  const double root_v = std::sqrt(speed2 + e2), root_a = std::sqrt(acc2 + e2);
  const double nv = root_v - m.eps, na = root_a - m.eps;
  const auto& k = m.k;
  *L = factor * s + m.Motion(acc2, speed2);  // the same expression as RunningCost
  Lx[0] = factor * grad_s[0];
  Lx[1] = factor * grad_s[1];
  const double cv = m.gamma * (2.0 * k[1]), dv = m.gamma * (k[2] + k[5] * na) / root_v;
  Lx[2] = (cv + dv) * x[2];
  Lx[3] = (cv + dv) * x[3];
  Lx[4] = 0.0;
  const double ca = m.gamma * (2.0 * k[0]), da = m.gamma * (k[4] + k[5] * nv) / root_a;
  Lu[0] = (ca + da) * u[0];
  Lu[1] = (ca + da) * u[1];
  Lu[2] = kLn2 * two_r * s * inv_k_;
}

void CommPath2d::MinimizerGivenChannel(ConstVecRef x, ConstVecRef p, double s, VecRef u) const {
  MinimizerGivenChannel(
      p.data(), s, options_.power.SmoothNorm(x[2] * x[2] + x[3] * x[3]), u.data());
}

void CommPath2d::MinimizerGivenChannel(const double* p, double s, double nv, double* u) const {
  // H = p1.x2 + p2.u + p3 R + (2^R - 1)/K s(x1) + motion(u, x2): separable in u and R.
  const double a = std::sqrt(p[2] * p[2] + p[3] * p[3]);
  const double r = options_.power.AccelerationMagnitude(a, nv, options_.umax);
  if (a > 0.0) {
    u[0] = -r * p[2] / a;
    u[1] = -r * p[3] / a;
  } else {
    u[0] = u[1] = (a == 0.0 ? 0.0 : a);
  }
  u[2] = options_.power.Rate(p[4], s, options_.rmax, k_);
}

void CommPath2d::ProximalMinimizerGivenChannel(
    const double* p, double s, double nv, const double* center, double eps, double* w) const {
  // The u-part of H + |w - center|^2/(2 eps), up to constants: (gamma k1 + 1/(2 eps)) |w_u|^2
  // + q.w_u + gamma (k5 + k6 nv) n(w_u) with q = p2 - center_u / eps: u*'s form with q for p2.
  const double q0 = p[2] - center[0] / eps, q1 = p[3] - center[1] / eps;
  const double a = std::sqrt(q0 * q0 + q1 * q1);
  const double r = options_.power.AccelerationMagnitude(a, nv, options_.umax, 1.0 / eps);
  if (a > 0.0) {
    w[0] = -r * q0 / a;
    w[1] = -r * q1 / a;
  } else {
    w[0] = w[1] = (a == 0.0 ? 0.0 : a);
  }
  w[2] = options_.power.ProximalRate(p[4], s, options_.rmax, k_, center[2], eps);
}

void CommPath2d::MinimizeProximalHamiltonian(
    double, ConstVecRef x, ConstVecRef p, ConstVecRef center, double eps, VecRef w) const {
  double s = 0.0;
  channel_->Evaluate(Eigen::Vector2d(x[0], x[1]), &s, nullptr, nullptr);
  ProximalMinimizerGivenChannel(p.data(),
                                s,
                                options_.power.SmoothNorm(x[2] * x[2] + x[3] * x[3]),
                                center.data(),
                                eps,
                                w.data());
}

double CommPath2d::HamiltonianGivenChannel(ConstVecRef x,
                                           ConstVecRef p,
                                           ConstVecRef u,
                                           double s) const {
  const double acc2 = u[0] * u[0] + u[1] * u[1];
  const double speed2 = x[2] * x[2] + x[3] * x[3];
  const double pf = p[0] * x[2] + p[1] * x[3] + p[2] * u[0] + p[3] * u[1] + p[4] * u[2];
  return pf + options_.power.Transmission(u[2], s, inv_k_) + options_.power.Motion(acc2, speed2);
}

void CommPath2d::MinimizeHamiltonian(double, ConstVecRef x, ConstVecRef p, VecRef u) const {
  double s = 0.0;
  channel_->Evaluate(Eigen::Vector2d(x[0], x[1]), &s, nullptr, nullptr);
  MinimizerGivenChannel(x, p, s, u);
}

void CommPath2d::MinimizeHamiltonianWithGradients(double t,
                                                  ConstVecRef x,
                                                  ConstVecRef p,
                                                  VecRef u,
                                                  VecRef f,
                                                  MatRef fx,
                                                  MatRef fu,
                                                  double* L,
                                                  VecRef Lx,
                                                  VecRef Lu) const {
  // The value s is the same number with or without its gradient (every ChannelQuality computes
  // it first), so u* is MinimizeHamiltonian's bitwise.
  double s = 0.0;
  Eigen::Vector2d grad_s;
  channel_->Evaluate(Eigen::Vector2d(x[0], x[1]), &s, &grad_s, nullptr);
  MinimizerGivenChannel(x, p, s, u);
  DynamicsJacobian(t, x, u, f, fx, fu);
  RunningCostGradientGivenChannel(x, u, s, grad_s, L, Lx, Lu);
}

void CommPath2d::MinimizeAndCompareHamiltonian(double,
                                               ConstVecRef x,
                                               ConstVecRef p,
                                               ConstVecRef u,
                                               VecRef u_star,
                                               double* h_star,
                                               double* h_now,
                                               VecRef) const {
  double s = 0.0;
  channel_->Evaluate(Eigen::Vector2d(x[0], x[1]), &s, nullptr, nullptr);
  MinimizerGivenChannel(x, p, s, u_star);
  *h_star = HamiltonianGivenChannel(x, p, u_star, s);
  *h_now = HamiltonianGivenChannel(x, p, u, s);
}

// ---- EulerStageModel ------------------------------------------------------------------------
// Each value below repeats the operations of RunningCost, RunningCostGradient,
// MinimizeHamiltonian and HamiltonianGivenChannel on the cached numbers, so the descent's
// numbers are bitwise those of the generic path (tests/problems/comm_path2d_test.cc).

void CommPath2d::EulerStep(
    double, double h, const double* x, const double* u, double* x_next) const {
  EulerStepOf(h, x, u, x_next);
}

void CommPath2d::EulerStates(const TimeGrid& grid, int, int, const double* U, double* X) const {
  for (int k = 0; k < grid.intervals(); ++k) {
    EulerStepOf(grid.h(k), X + 5 * k, U + 3 * k, X + 5 * (k + 1));
  }
}

double CommPath2d::RunningCostCaching(double,
                                      const double* x,
                                      const double* u,
                                      double* cache) const {
  double s = 0.0;
  Eigen::Vector2d grad_s;
  channel_->Evaluate(Eigen::Vector2d(x[0], x[1]), &s, &grad_s, nullptr);
  const CommPowerModel& m = options_.power;
  const double acc2 = u[0] * u[0] + u[1] * u[1];
  const double speed2 = x[2] * x[2] + x[3] * x[3];
  const double rate_factor = std::exp2(u[2]) - 1.0;
  const double root_v = std::sqrt(speed2 + m.eps * m.eps);
  const double motion = m.Motion(acc2, speed2, root_v - m.eps);
  cache[0] = s;
  cache[1] = grad_s[0];
  cache[2] = grad_s[1];
  cache[3] = rate_factor;
  cache[4] = motion;
  cache[5] = root_v;
  return rate_factor * (s * inv_k_) + motion;  // Transmission() + Motion()
}

double CommPath2d::PointwiseRunningCostBound(double, const double* x, const double* u) const {
  return options_.power.Motion(u[0] * u[0] + u[1] * u[1], x[2] * x[2] + x[3] * x[3]);
}

void CommPath2d::PointwiseRunningCostBounds(
    const TimeGrid& grid, int, int, const double* X, const double* U, double* m) const {
  for (int k = 0; k < grid.intervals(); ++k) {
    const double* x = X + 5 * k;
    const double* u = U + 3 * k;
    m[k] = options_.power.Motion(u[0] * u[0] + u[1] * u[1], x[2] * x[2] + x[3] * x[3]);
  }
}

void CommPath2d::BackwardPoint(double,
                               double h,
                               const double* x,
                               const double* u,
                               const double* cache,
                               double eps,
                               double* p,
                               double* u_star,
                               double* h_star,
                               double* h_now,
                               double* h_min) const {
  const CommPowerModel& m = options_.power;
  const double s = cache[0], rate_factor = cache[3], motion = cache[4], root_v = cache[5];
  const double nv = root_v - m.eps;
  // HamiltonianGivenChannel(x, p, w, s) with the cached n(x2).
  auto hamiltonian = [&](const double* w) {
    const double pf = p[0] * x[2] + p[1] * x[3] + p[2] * w[0] + p[3] * w[1] + p[4] * w[2];
    return pf + m.Transmission(w[2], s, inv_k_) +
           m.Motion(w[0] * w[0] + w[1] * w[1], x[2] * x[2] + x[3] * x[3], nv);
  };
  if (std::isfinite(eps)) {
    ProximalMinimizerGivenChannel(p, s, nv, u, eps, u_star);
    if (h_min) {
      double w[3];
      MinimizerGivenChannel(p, s, nv, w);
      *h_min = hamiltonian(w);
    }
    *h_star = hamiltonian(u_star);
  } else {
    MinimizerGivenChannel(p, s, nv, u_star);
    *h_star = hamiltonian(u_star);
    if (h_min) *h_min = *h_star;
  }
  const double pf = p[0] * x[2] + p[1] * x[3] + p[2] * u[0] + p[3] * u[1] + p[4] * u[2];
  *h_now = pf + rate_factor * (s * inv_k_) + motion;
  // H_x = f_x^T p + L_x with f_x^T p = (0, 0, p1, p2, 0) and L_x as in RunningCostGradient;
  // then the Euler adjoint step p += h H_x (H_x,4 = 0 leaves p[4]).
  const double factor = rate_factor * inv_k_;
  const auto& k = m.k;
  double na = 0.0;
  if (k[5] != 0.0) na = std::sqrt(u[0] * u[0] + u[1] * u[1] + m.eps * m.eps) - m.eps;
  const double cv = m.gamma * (2.0 * k[1]), dv = m.gamma * (k[2] + k[5] * na) / root_v;
  const double hx0 = factor * cache[1], hx1 = factor * cache[2];
  const double hx2 = p[0] + (cv + dv) * x[2], hx3 = p[1] + (cv + dv) * x[3];
  p[0] += h * hx0;
  p[1] += h * hx1;
  p[2] += h * hx2;
  p[3] += h * hx3;
  p[4] += h * 0.0;
}

// ---- registry support -------------------------------------------------------------------------

std::vector<ParameterSpec> CommParameterSpecs() {
  const double inf = std::numeric_limits<double>::infinity();
  return {
      {"S", {20.0, 40.0}, "start position (m), in the workspace [0, workspace]^2", 0.0, 1e4},
      {"D", {10.0, 5.0}, "destination (m), in the workspace [0, workspace]^2", 0.0, 1e4},
      {"base",
       {5.0, 5.0},
       "base station position (m), in the workspace [0, workspace]^2",
       0.0,
       1e4},
      {"workspace",
       {50.0},
       "side of the square workspace [0, workspace]^2 over which the channel is simulated (m)",
       0.0,
       1e4,
       true},
      {"c", {150.0}, "bits/Hz to transmit, c = Q/B", 0.0, 1e6},
      {"tf", {40.0}, "time horizon (s)", 0.0, 1e5, true},
      {"umax", {0.5}, "acceleration bound |u| <= umax (m/s^2)", 0.0, 1e3, true},
      {"Rmax", {6.0}, "spectral-efficiency bound 0 <= R <= Rmax (bits/s/Hz)", 0.0, 100.0, true},
      {"gamma", {0.01}, "weight of motion power in L", 0.0, 1e6, true},
      {"C",
       {10.0, 50.0, 10.0},
       "penalty weights C1 (position), C2 (velocity), C3 (bits)",
       0.0,
       1e12,
       true},
      {"k", {17.75, 1.16, 10.46, 1175.0, 0.0, 0.0}, "motion power constants k1..k6", 0.0, 1e9},
      {"eps", {1e-3}, "smoothing of |v|: sqrt(|v|^2 + eps^2) - eps", 0.0, 1.0, true},
      {"pb", {2e-6}, "bit error rate threshold, K = -1.5 / ln(5 pb)", 0.0, 0.1, true},
      {"channel",
       {2.0},
       "channel model: 0 path loss only (deterministic), 1 GP prediction (exact), 2 GP "
       "prediction as a bicubic map",
       0.0,
       2.0,
       false,
       true},
      {"samples", {500.0}, "channel measurements for the GP prediction", 3.0, 1e5, false, true},
      {"estimate",
       {1.0},
       "1: the predictor uses parameters estimated from the samples (the paper's procedure); 0: "
       "the true ones",
       0.0,
       1.0,
       false,
       true},
      {"K_PL", {-41.34}, "path-loss constant (dB)", -inf, inf},
      {"n_PL", {3.86}, "path-loss exponent", 0.0, 10.0, true},
      {"xi", {3.20}, "shadowing standard deviation (dB)", 0.0, 30.0},
      {"eta", {3.09}, "shadowing decorrelation distance (m)", 0.0, 100.0, true},
      {"rho",
       {1.64},
       "multipath standard deviation (dB) the predictor assumes with estimate=0 (the simulator "
       "draws Rician fading of K-factor rician_K; 14.56 has dB standard deviation 1.64)",
       0.0,
       30.0},
      {"N0_dBm", {-110.0}, "receiver noise power (dBm)", -300.0, 100.0},
      {"grid_step",
       {0.1},
       "channel simulation grid step (m); channel=2 interpolates s between these points",
       0.0,
       100.0,
       true},
      {"rician_K",
       {14.56},
       "Rician K-factor (linear) of the simulated multipath; 14.56 gives the paper's rho = 1.64 dB",
       0.0,
       1e6,
       true},
      {"distance_floor",
       {0.1},
       "path-loss distance floor (m): log10 max(|q - q_b|, floor) (channel 0: the smooth "
       "sqrt(|q - q_b|^2 + floor^2))",
       0.0,
       100.0,
       true},
      {"estimator",
       {0.0},
       "channel parameter estimator: 0 binned least squares (the companion's), 1 maximum "
       "likelihood, 2 REML",
       0.0,
       2.0,
       false,
       true},
      {"bin_width", {0.2}, "lag-bin width of the binned estimator (m)", 0.0, 100.0, true},
      {"min_pairs",
       {40.0},
       "pairs a lag bin needs to be used by the binned estimator",
       1.0,
       1e9,
       false,
       true},
  };
}

CommPowerModel CommPowerFromParameters(const Parameters& params) {
  CommPowerModel m;
  m.gamma = params.Scalar("gamma");
  const Vec k = params.Vector("k");
  for (int i = 0; i < 6; ++i) m.k[i] = k[i];
  m.eps = params.Scalar("eps");
  m.bit_error_rate = params.Scalar("pb");
  return m;
}

namespace {

// The largest simulation grid a parameter set may ask for: 4000 x 4000 points (each field of
// the simulation and the prediction is 128 MB there).
constexpr double kMaxChannelGridPoints = 1.6e7;

// The base station inside the workspace, and a simulation grid of a sensible size.
void CheckChannelGeometry(const Parameters& params) {
  const double w = params.Scalar("workspace");
  const Eigen::Vector2d base = params.Vector("base");
  if (!(base.x() <= w && base.y() <= w)) {
    throw std::invalid_argument("base must lie in the workspace [0, " + Str(w) + "]^2");
  }
  const double per_side = w / params.Scalar("grid_step");
  if (!(per_side >= 4.0) || per_side * per_side > kMaxChannelGridPoints) {
    throw std::invalid_argument("grid_step: workspace / grid_step = " + Str(per_side) +
                                " points per side; need 4 to 4000");
  }
}

// The options of the paper's channel (models 1 and 2), validated.
PaperChannelOptions CommPaperChannelOptions(const Parameters& params, int model) {
  CheckChannelGeometry(params);
  const double w = params.Scalar("workspace");
  PaperChannelOptions options;
  options.simulation.grid = GridSpec::Workspace(w, w, params.Scalar("grid_step"));
  options.simulation.multipath.rician_k = params.Scalar("rician_K");
  options.truth.distance_floor = params.Scalar("distance_floor");
  options.estimation.method = EstimationMethodFromCode(params.Integer("estimator"));
  options.estimation.bin_width = params.Scalar("bin_width");
  options.estimation.min_pairs = params.Integer("min_pairs");
  options.truth.k_pl = params.Scalar("K_PL");
  options.truth.n_pl = params.Scalar("n_PL");
  options.truth.xi = params.Scalar("xi");
  options.truth.eta = params.Scalar("eta");
  options.truth.rho = params.Scalar("rho");
  options.truth.base_station = params.Vector("base");
  options.estimate = params.Integer("estimate") == 1;
  options.predictor.units.noise_dbm = params.Scalar("N0_dBm");
  options.build_map = model == 2;
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("channel: " + error);
  return options;
}

}  // namespace

std::shared_ptr<const ChannelQuality> MakeCommChannel(const Parameters& params,
                                                      std::uint64_t seed) {
  const Eigen::Vector2d base = params.Vector("base");
  const int model = params.Integer("channel");
  if (model == 0) {
    CheckChannelGeometry(params);
    return std::make_shared<PathLossChannel>(base,
                                             params.Scalar("K_PL"),
                                             params.Scalar("n_PL"),
                                             params.Scalar("N0_dBm"),
                                             params.Scalar("distance_floor"));
  }
  // The paper's experiment: simulate the channel of these parameters (realization `seed`),
  // measure it at `samples` random grid points, estimate the parameters, predict s. Built once
  // per process for every case with the same key (ChannelCache).
  const PaperChannelOptions options = CommPaperChannelOptions(params, model);
  const int samples = params.Integer("samples");
  const double points = std::pow(params.Scalar("workspace") / params.Scalar("grid_step"), 2);
  // The map holds (nx + 2)(ny + 2) spline coefficients; the exact predictor the capacity x
  // capacity Cholesky factor and m x 2 positions (a generous 2 m^2 doubles).
  const double bytes = model == 2 ? 8.0 * (std::sqrt(points) + 2.0) * (std::sqrt(points) + 2.0)
                                  : 16.0 * samples * samples;
  return ChannelCache::Global().GetOrBuild(
      CommChannelKey(params, seed), static_cast<std::size_t>(bytes) + 4096, [&] {
        const PaperChannel channel = MakePaperChannel(seed, samples, options);
        return channel.Quality(model == 2 ? ChannelProvider::kMap : ChannelProvider::kExact);
      });
}

std::shared_ptr<const ChannelQuality> MakeCommTrueChannel(const Parameters& params,
                                                          std::uint64_t seed) {
  const int model = params.Integer("channel");
  if (model == 0) return MakeCommChannel(params, seed);
  const PaperChannelOptions options = CommPaperChannelOptions(params, model);
  // The realization only: the gain grid (one double a cell) and its grid.
  const double bytes = 8.0 * static_cast<double>(options.simulation.grid.num_points());
  return ChannelCache::Global().GetOrBuild(
      "truth;" + CommChannelKey(params, seed), static_cast<std::size_t>(bytes) + 4096, [&] {
        SimulatedChannel truth = SimulateChannel(options.truth, options.simulation, seed);
        // Only the gain is read (GainAt): the components are dropped to keep the cache small.
        truth.path_loss_db.resize(0, 0);
        truth.shadowing_db.resize(0, 0);
        truth.multipath_db.resize(0, 0);
        return std::make_shared<const TrueChannelQuality>(
            std::make_shared<const SimulatedChannel>(std::move(truth)), options.predictor.units);
      });
}

std::string CommChannelKey(const Parameters& params, std::uint64_t seed) {
  // Every shared comm parameter except those of the task and the motion model: a parameter
  // added to CommParameterSpecs later is part of the key unless listed here, so forgetting it
  // costs a rebuild, never a wrong channel.
  static const std::set<std::string> kNotChannel = {
      "S", "D", "c", "tf", "umax", "Rmax", "gamma", "C", "k", "eps", "pb"};
  std::ostringstream key;
  key.precision(17);
  key << "seed=" << seed;
  for (const ParameterSpec& spec : CommParameterSpecs()) {
    if (kNotChannel.count(spec.name)) continue;
    key << ';' << spec.name << '=';
    const char* sep = "";
    for (double v : params.Raw(spec.name)) {
      key << sep << v;
      sep = ",";
    }
  }
  return key.str();
}

std::shared_ptr<const ChannelQuality> MakeCommChannelForChecks(const Parameters& params) {
  const int model = params.Integer("channel");
  CheckChannelGeometry(params);
  if (model != 0) {
    // What MakePaperChannel would refuse or run out of memory on, found before simulating.
    const PaperChannelOptions options = CommPaperChannelOptions(params, model);
    const GridSpec& grid = options.simulation.grid;
    const int samples = params.Integer("samples");
    CheckChannelMemory(samples, "samples", static_cast<double>(grid.num_points()), "grid_step");
    const long eligible = EligibleMeasurementPoints(grid, options.truth);
    if (2L * samples > eligible) {
      throw std::invalid_argument(
          "samples: " + std::to_string(samples) + " measurements need " +
          std::to_string(2L * samples) +
          " grid points beyond the distance floor of the base station (twice as many); the "
          "channel grid (workspace / grid_step) has " +
          std::to_string(eligible));
    }
  }
  return std::make_shared<PathLossChannel>(params.Vector("base"),
                                           params.Scalar("K_PL"),
                                           params.Scalar("n_PL"),
                                           params.Scalar("N0_dBm"),
                                           params.Scalar("distance_floor"));
}

CommPath2d::Options CommPath2dOptionsFromParameters(const Parameters& params) {
  CommPath2d::Options o;
  o.start = params.Vector("S");
  o.destination = params.Vector("D");
  o.bits = params.Scalar("c");
  o.tf = params.Scalar("tf");
  o.umax = params.Scalar("umax");
  o.rmax = params.Scalar("Rmax");
  o.penalty = params.Vector("C");
  o.t0 = params.Scalar("t0");
  o.v0 = params.Vector("v0");
  o.bits_sent = params.Scalar("x3_0");
  o.workspace = params.Scalar("workspace");
  o.power = CommPowerFromParameters(params);
  return o;
}

ProblemInfo CommPath2dProblemInfo() {
  ProblemInfo p;
  p.name = "comm-path2d";
  p.description =
      "robot path, acceleration and transmission rate co-optimized over a predicted channel "
      "(Ali, Cai, Mostofi, Wardi, ACC 2016, Sec. III)";
  p.parameters = CommParameterSpecs();
  // The initial condition of the cost-to-go problem J_{t0} (online re-planning, paper Sec. IV);
  // the defaults are the offline problem from rest.
  p.parameters.push_back(
      {"t0", {0.0}, "initial time (s); the problem is posed on [t0, tf]", 0.0, 1e5});
  p.parameters.push_back({"v0", {0.0, 0.0}, "initial velocity x2(t0) (m/s)", -1e3, 1e3});
  p.parameters.push_back({"x3_0", {0.0}, "bits/Hz already sent at t0, x3(t0)", 0.0, 1e6});
  p.make = [](const Parameters& params, std::uint64_t seed) -> std::unique_ptr<Ocp> {
    return std::make_unique<CommPath2d>(CommPath2dOptionsFromParameters(params),
                                        MakeCommChannel(params, seed));
  };
  p.make_for_checks = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<CommPath2d>(CommPath2dOptionsFromParameters(params),
                                        MakeCommChannelForChecks(params));
  };
  p.default_intervals = 400;
  p.uses_seed = true;
  p.tags = {"paper"};
  return p;
}

}  // namespace ocpb
