// The hand-written second derivatives of comm-path2d (CommPath2d::PointHessian).
//
// Why by hand: the Jet2 pass of AutoDiffOcp carries an 8 x 8 Hessian through every operation
// of L (about 18,000 instructions per grid point), while the closed form below costs one channel
// evaluation with its Hessian plus a few dozen flops, and the dynamics are affine (f'' = 0).
// Checked against finite differences of the hand-written gradient and against the AD Hessian
// in tests/problems/comm_path2d_test.cc.
#include <cmath>

#include "problems/comm_path2d.h"

namespace ocpb {
namespace {

constexpr double kLnTwo = 0.69314718055994530942;

// n(w) = sqrt(|w|^2 + e^2) - e: gradient w / r and Hessian (I - w w^T / r^2) / r, r = sqrt(...).
struct SmoothNormDerivatives {
  double value;
  Eigen::Vector2d grad;
  Eigen::Matrix2d hess;
};

SmoothNormDerivatives NormDerivatives(double w0, double w1, double eps) {
  const double r2 = w0 * w0 + w1 * w1 + eps * eps;
  const double r = std::sqrt(r2);
  SmoothNormDerivatives d;
  d.value = r - eps;
  d.grad = Eigen::Vector2d(w0 / r, w1 / r);
  d.hess << (r2 - w0 * w0) / (r2 * r), -w0 * w1 / (r2 * r), -w0 * w1 / (r2 * r),
      (r2 - w1 * w1) / (r2 * r);
  return d;
}

}  // namespace

// z = (q (2), v (2), b, a (2), R). With T = (2^R - 1)/K s(q) and the motion power
// M = gamma (k1 |a|^2 + k2 |v|^2 + k3 n(v) + k4 + k5 n(a) + k6 n(a) n(v)):
//   T_qq = (2^R - 1)/K Hess s,  T_qR = ln2 2^R / K grad s,  T_RR = ln2^2 2^R / K s,
//   M_vv = gamma (2 k2 I + (k3 + k6 n(a)) Hess n(v)),  M_aa = gamma (2 k1 I + (k5 + k6 n(v)) Hess
//   n(a)), M_va = gamma k6 grad n(v) grad n(a)^T;  b enters nothing, and lambda^T f'' = 0 (f is
//   affine).
void CommPath2d::PointHessian(double,
                              ConstVecRef x,
                              ConstVecRef u,
                              double sigma,
                              ConstVecRef,
                              ConstVecRef,
                              MatRef hess) const {
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 8; ++i) hess(i, j) = 0.0;
  }
  if (sigma == 0.0) return;
  double s = 0.0;
  Eigen::Vector2d gs;
  Eigen::Matrix2d hs;
  channel_->Evaluate(Eigen::Vector2d(x[0], x[1]), &s, &gs, &hs);
  const double two_r = std::exp2(u[2]);
  const double factor = sigma * (two_r - 1.0) * inv_k_;
  const double rate = sigma * kLnTwo * two_r * inv_k_;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) hess(i, j) = factor * hs(i, j);
    hess(7, j) = hess(j, 7) = rate * gs[j];
  }
  hess(7, 7) = rate * kLnTwo * s;

  const CommPowerModel& m = options_.power;
  const auto& k = m.k;
  const SmoothNormDerivatives nv = NormDerivatives(x[2], x[3], m.eps);
  const SmoothNormDerivatives na = NormDerivatives(u[0], u[1], m.eps);
  const double g = sigma * m.gamma;
  const double cv = g * (k[2] + k[5] * na.value), ca = g * (k[4] + k[5] * nv.value);
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      hess(2 + i, 2 + j) = cv * nv.hess(i, j);
      hess(5 + i, 5 + j) = ca * na.hess(i, j);
      hess(2 + i, 5 + j) = hess(5 + j, 2 + i) = g * k[5] * nv.grad[i] * na.grad[j];
    }
    hess(2 + j, 2 + j) += g * 2.0 * k[1];
    hess(5 + j, 5 + j) += g * 2.0 * k[0];
  }
}

}  // namespace ocpb
