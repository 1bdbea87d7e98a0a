#include "solvers/minimizer_derivative.h"

#include <algorithm>
#include <cmath>

#include "solvers/small_dims.h"
#include "solvers/small_lu.h"

namespace ocpb {
namespace {

// du_dx = -Z H_ux and du_dp = -Z f_u^T (Z nu x nu, H_ux the rows nx.. of the PointHessian, all
// column-major with the given leading dimensions), at the compile-time sizes kNx, kNu when
// nonzero (solvers/small_dims.h). False when an entry is not finite: v - v is 0 for a finite v
// and NaN otherwise, and a sum stays NaN once a term is (solvers/all_finite.h), one subtraction
// and addition per entry where a std::isfinite test and flag took eight instructions.
template <int kNx, int kNu>
bool MinimizerDerivativeProducts(int nx_runtime,
                                 int nu_runtime,
                                 const double* __restrict Z,
                                 const double* __restrict hux,
                                 int ld_hess,
                                 const double* __restrict fu,
                                 int ld_fu,
                                 double* __restrict du_dx,
                                 int ld_dx,
                                 double* __restrict du_dp,
                                 int ld_dp) {
  const int nx = SmallDim<kNx>(nx_runtime), nu = SmallDim<kNu>(nu_runtime);
  double check_x = 0.0, check_p = 0.0;
  if constexpr (kNu > 0) {
    // Column j of both products in registers, the terms l = 0, 1, ... added to every entry in
    // turn (each entry's sum in the order of the loop below).
    for (int j = 0; j < nx; ++j) {
      double vx[kNu], vp[kNu];
      for (int i = 0; i < kNu; ++i) vx[i] = vp[i] = 0.0;
      for (int l = 0; l < kNu; ++l) {
        const double h = hux[j * ld_hess + l], f = fu[l * ld_fu + j];
        for (int i = 0; i < kNu; ++i) {
          vx[i] += Z[l * nu + i] * h;
          vp[i] += Z[l * nu + i] * f;
        }
      }
      for (int i = 0; i < kNu; ++i) {
        du_dx[j * ld_dx + i] = -vx[i];
        du_dp[j * ld_dp + i] = -vp[i];
        check_x += vx[i] - vx[i];
        check_p += vp[i] - vp[i];
      }
    }
    return check_x + check_p == 0.0;
  }
  for (int j = 0; j < nx; ++j) {
    for (int i = 0; i < nu; ++i) {
      double vx = 0.0, vp = 0.0;
      for (int l = 0; l < nu; ++l) {
        vx += Z[l * nu + i] * hux[j * ld_hess + l];
        vp += Z[l * nu + i] * fu[l * ld_fu + j];
      }
      du_dx[j * ld_dx + i] = -vx;
      du_dp[j * ld_dp + i] = -vp;
      check_x += vx - vx;
      check_p += vp - vp;
    }
  }
  return check_x + check_p == 0.0;
}

// Factors the n x n column-major KKT matrix K in place and writes Z, the top-left nu x nu block
// of K^-1 (column-major), solving for unit vectors in w (length n); kN > 0 fixes n at compile
// time. False when K is singular (SmallLuFactor).
template <int kN>
bool MinimizerDerivativeInverseBlockOfOrder(
    double* K, int* pivot, int n, int nu, double* w, double* Z) {
  if (!SmallLuFactor<kN>(K, pivot, n)) return false;
  for (int c = 0; c < nu; ++c) {
    std::fill(w, w + n, 0.0);
    w[c] = 1.0;
    SmallLuSolve<kN>(K, pivot, n, w);
    for (int i = 0; i < nu; ++i) Z[c * nu + i] = w[i];
  }
  return true;
}

// |d|^2 and d . g of a ball's d = u_b - c_b (size components). Up to two components by hand:
// a single addition, the number Eigen's reductions give whatever the alignment; Eigen's
// reductions otherwise (their summation order for more components depends on alignment).
void BallProducts(
    const double* u, const double* c, const double* g, int size, double* dd, double* dg) {
  if (size <= 2) {
    const double d0 = u[0] - c[0];
    *dd = d0 * d0;
    *dg = d0 * g[0];
    if (size == 2) {
      const double d1 = u[1] - c[1];
      *dd += d1 * d1;
      *dg += d1 * g[1];
    }
    return;
  }
  using Map = Eigen::Map<const Vec>;
  const Vec d = Map(u, size) - Map(c, size);
  *dd = d.squaredNorm();
  *dg = d.dot(Map(g, size));
}

// The same at the compile-time order n = nu + (active rows) when it is at most 6 (nu <= 3: every
// registered problem with a minimizer), else at runtime size.
bool MinimizerDerivativeInverseBlock(double* K, int* pivot, int n, int nu, double* w, double* Z) {
  switch (n) {
    case 1:
      return MinimizerDerivativeInverseBlockOfOrder<1>(K, pivot, n, nu, w, Z);
    case 2:
      return MinimizerDerivativeInverseBlockOfOrder<2>(K, pivot, n, nu, w, Z);
    case 3:
      return MinimizerDerivativeInverseBlockOfOrder<3>(K, pivot, n, nu, w, Z);
    case 4:
      return MinimizerDerivativeInverseBlockOfOrder<4>(K, pivot, n, nu, w, Z);
    case 5:
      return MinimizerDerivativeInverseBlockOfOrder<5>(K, pivot, n, nu, w, Z);
    case 6:
      return MinimizerDerivativeInverseBlockOfOrder<6>(K, pivot, n, nu, w, Z);
    default:
      return MinimizerDerivativeInverseBlockOfOrder<0>(K, pivot, n, nu, w, Z);
  }
}

}  // namespace

MinimizerDerivative::MinimizerDerivative(const Ocp& ocp)
    : ocp_(ocp), nx_(ocp.nx()), nu_(ocp.nu()), box_active_(ocp.nu(), false) {
  a_.resize(nu_ * nu_);
  m_.resize(nu_ * nu_);
  kkt_.resize(4 * nu_ * nu_);
  pivot_.resize(2 * nu_);
  inverse_.resize(nu_ * nu_);
  work_.resize(2 * nu_);
  f_.resize(nx_);
  Lx_.resize(nx_);
  Lu_.resize(nu_);
  Hu_.resize(nu_);
  fx_.resize(nx_, nx_);
  fu_.resize(nx_, nu_);
  hess_.resize(nx_ + nu_, nx_ + nu_);
}

bool MinimizerDerivative::Compute(
    ConstVecRef u, ConstVecRef Hu, ConstMatRef fu, ConstMatRef hess, MatRef du_dx, MatRef du_dp) {
  const int nx = nx_, nu = nu_;
  // M = H_uu plus the curvature of active spheres (nu x nu, column-major); A = the active
  // constraint rows (row r at a + r nu), in plain loops on raw storage (Eigen's dynamic-size
  // blocks cost more than these few flops). The norm and the dot product of a ball stay
  // Eigen's, whose summation order for more than two components depends on alignment.
  double* M = m_.data();
  const Eigen::Index ld = hess.outerStride();
  const double* huu = hess.data() + nx * ld + nx;
  for (int j = 0; j < nu; ++j) {
    for (int i = 0; i < nu; ++i) M[j * nu + i] = huu[j * ld + i];
  }
  double* a = a_.data();
  std::fill(a_.begin(), a_.end(), 0.0);
  std::fill(box_active_.begin(), box_active_.end(), false);
  int na = 0;
  for (const ControlSet::Block& b : ocp_.control_set().blocks()) {
    if (b.kind == ControlSet::Kind::kBox) {
      for (int i = 0; i < b.size; ++i) {
        const int j = b.offset + i;
        const double lo = b.lower[i], up = b.upper[i];
        const bool at_lower =
            std::isfinite(lo) && u[j] <= lo + kActiveTolerance * std::max(1.0, std::abs(lo));
        const bool at_upper =
            std::isfinite(up) && u[j] >= up - kActiveTolerance * std::max(1.0, std::abs(up));
        if (at_lower || at_upper) {
          a[na++ * nu + j] = 1.0;
          box_active_[j] = true;
        }
      }
    } else {
      const double* ub = u.data() + b.offset;
      const double* cb = b.center.data();
      double dd = 0.0, dg = 0.0;
      BallProducts(ub, cb, Hu.data() + b.offset, b.size, &dd, &dg);
      const double nd = std::sqrt(dd);
      if (b.radius > 0.0 && nd >= b.radius * (1.0 - kActiveTolerance)) {
        // n = d / |d|; H_u + mu (u - c) = 0 on the sphere, mu >= 0.
        const double mu = std::max(0.0, -dg / (nd * nd));
        for (int i = 0; i < b.size; ++i) {
          const int j = b.offset + i;
          M[j * nu + j] += mu;
          a[na * nu + j] = (ub[i] - cb[i]) / nd;
        }
        ++na;
      }
    }
  }
  num_active_ = na;

  // K = [M A^T; A 0] (n = nu + na), column-major, factored by a partial-pivoting LU in plain
  // loops (solvers/small_lu.h; the reduced KKT matrix is symmetric indefinite and tiny).
  const int n = nu + na;
  double* K = kkt_.data();
  for (int j = 0; j < nu; ++j) {
    for (int i = 0; i < nu; ++i) K[j * n + i] = M[j * nu + i];
    for (int r = 0; r < na; ++r) K[j * n + nu + r] = a[r * nu + j];
  }
  for (int r = 0; r < na; ++r) {
    double* column = K + (nu + r) * n;
    for (int i = 0; i < nu; ++i) column[i] = a[r * nu + i];
    for (int i = nu; i < n; ++i) column[i] = 0.0;
  }
  // (du_dx, du_dp) = -Z (H_ux, f_u^T), Z the top-left nu x nu block of K^-1 (the right-hand
  // sides vanish in the constraint rows).
  double* Z = inverse_.data();
  if (!MinimizerDerivativeInverseBlock(K, pivot_.data(), n, nu, work_.data(), Z)) return false;
  return WithSmallDims(nx, nu, [&]<int kNx, int kNu>() {
    return MinimizerDerivativeProducts<kNx, kNu>(nx,
                                                 nu,
                                                 Z,
                                                 hess.data() + nx,
                                                 static_cast<int>(hess.outerStride()),
                                                 fu.data(),
                                                 static_cast<int>(fu.outerStride()),
                                                 du_dx.data(),
                                                 static_cast<int>(du_dx.outerStride()),
                                                 du_dp.data(),
                                                 static_cast<int>(du_dp.outerStride()));
  });
}

bool MinimizerDerivative::ComputeAt(
    double t, ConstVecRef x, ConstVecRef p, VecRef u, MatRef du_dx, MatRef du_dp) {
  ocp_.MinimizeHamiltonian(t, x, p, u);
  ocp_.DynamicsJacobian(t, x, u, f_, fx_, fu_);
  double L = 0.0;
  ocp_.RunningCostGradient(t, x, u, &L, Lx_, Lu_);
  Hu_ = Lu_ + fu_.transpose() * p;
  const Vec no_mu = Vec::Zero(ocp_.num_path());
  ocp_.PointHessian(t, x, u, 1.0, p, no_mu, hess_);
  return Compute(u, Hu_, fu_, hess_, du_dx, du_dp);
}

}  // namespace ocpb
