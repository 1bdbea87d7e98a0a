#include "core/discrete_ocp.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace ocpb {

const char* ToString(Integrator integrator) {
  return integrator == Integrator::kEuler ? "euler" : "rk4";
}

Integrator ParseIntegrator(const std::string& name) {
  if (name == "euler") return Integrator::kEuler;
  if (name == "rk4") return Integrator::kRk4;
  throw std::invalid_argument("unknown integrator '" + name + "' (valid: euler, rk4)");
}

DiscreteOcp::DiscreteOcp(const Ocp& ocp,
                         const TimeGrid& grid,
                         Integrator integrator,
                         TerminalMode mode)
    : ocp_(ocp), grid_(grid), integrator_(integrator), mode_(mode), x0_(ocp.x0()) {}

void DiscreteOcp::SetInitialState(ConstVecRef x0) {
  if (x0.size() != ocp_.nx()) {
    throw std::invalid_argument(
        "DiscreteOcp::SetInitialState: x0 must have nx = " + std::to_string(ocp_.nx()) +
        " entries, has " + std::to_string(x0.size()));
  }
  x0_ = x0;
}

double DiscreteOcp::InitialObjective(ConstVecRef x0) const {
  return ocp_.HasFreeInitialState() && ocp_.HasInitialCost() ? ocp_.InitialCost(x0) : 0.0;
}

void DiscreteOcp::Rk4Step(int k, const Vec& x, const Vec& u, Vec* x_next, double* ell) const {
  const int nx = ocp_.nx();
  const double t = grid_.t(k), h = grid_.h(k);
  Vec k1(nx), k2(nx), k3(nx), k4(nx);
  ocp_.Dynamics(t, x, u, k1);
  const double l1 = ocp_.RunningCost(t, x, u);
  const Vec z2 = x + 0.5 * h * k1;
  ocp_.Dynamics(t + 0.5 * h, z2, u, k2);
  const double l2 = ocp_.RunningCost(t + 0.5 * h, z2, u);
  const Vec z3 = x + 0.5 * h * k2;
  ocp_.Dynamics(t + 0.5 * h, z3, u, k3);
  const double l3 = ocp_.RunningCost(t + 0.5 * h, z3, u);
  const Vec z4 = x + h * k3;
  ocp_.Dynamics(t + h, z4, u, k4);
  const double l4 = ocp_.RunningCost(t + h, z4, u);
  *x_next = x + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  *ell = (h / 6.0) * (l1 + 2.0 * l2 + 2.0 * l3 + l4);
}

void DiscreteOcp::Rk4StepAdjoint(
    int k, const Vec& x, const Vec& u, const Vec& bar_next, Vec* bar_x, Vec* bar_u) const {
  const int nx = ocp_.nx(), nu = ocp_.nu();
  const double t = grid_.t(k), h = grid_.h(k);
  const double ts[4] = {t, t + 0.5 * h, t + 0.5 * h, t + h};
  const double w[4] = {1.0, 2.0, 2.0, 1.0};
  // Forward: stage points z_i and their Jacobians.
  Vec z[4], kk[4];
  Mat fx[4], fu[4];
  Vec Lx[4], Lu[4];
  for (int i = 0; i < 4; ++i) {
    kk[i].resize(nx);
    fx[i].resize(nx, nx);
    fu[i].resize(nx, nu);
    Lx[i].resize(nx);
    Lu[i].resize(nu);
  }
  double L;
  z[0] = x;
  for (int i = 0; i < 4; ++i) {
    if (i > 0) z[i] = x + (i == 3 ? h : 0.5 * h) * kk[i - 1];
    ocp_.DynamicsJacobian(ts[i], z[i], u, kk[i], fx[i], fu[i]);
    ocp_.RunningCostGradient(ts[i], z[i], u, &L, Lx[i], Lu[i]);
  }
  // Reverse: x_next = x + h/6 sum w_i k_i, ell = h/6 sum w_i l_i, z_{i} = x + c_i k_{i-1}.
  *bar_x = bar_next;
  *bar_u = Vec::Zero(nu);
  Vec bar_k[4];
  for (int i = 0; i < 4; ++i) bar_k[i] = (h / 6.0) * w[i] * bar_next;
  for (int i = 3; i >= 0; --i) {
    const double bar_l = (h / 6.0) * w[i];
    const Vec bar_z = fx[i].transpose() * bar_k[i] + bar_l * Lx[i];
    *bar_u += fu[i].transpose() * bar_k[i] + bar_l * Lu[i];
    *bar_x += bar_z;
    if (i > 0) bar_k[i - 1] += (i == 3 ? h : 0.5 * h) * bar_z;
  }
}

double DiscreteOcp::Simulate(const Mat& U, Mat* X, double* running) const {
  const int nx = ocp_.nx(), N = grid_.intervals();
  if (U.rows() != ocp_.nu() || U.cols() != N) {
    throw std::invalid_argument("DiscreteOcp::Simulate: U must be nu x N");
  }
  Vec x = x0_, xn(nx), f(nx);
  if (X) {
    X->resize(nx, N + 1);
    X->col(0) = x;
  }
  double sum = 0.0;
  for (int k = 0; k < N; ++k) {
    const double h = grid_.h(k);
    if (integrator_ == Integrator::kEuler) {
      ocp_.Dynamics(grid_.t(k), x, U.col(k), f);
      sum += h * ocp_.RunningCost(grid_.t(k), x, U.col(k));
      x += h * f;
    } else {
      double ell;
      Rk4Step(k, x, U.col(k), &xn, &ell);
      sum += ell;
      x = xn;
    }
    if (X) X->col(k + 1) = x;
  }
  if (running) *running = sum;
  const double J = InitialObjective(x0_) + sum + ocp_.TerminalObjective(x, mode_);
  return std::isfinite(J) && x.allFinite() ? J : std::numeric_limits<double>::quiet_NaN();
}

void DiscreteOcp::SimulateStates(const Mat& U, Mat* X) const { SimulateStatesFrom(x0_, U, X); }

void DiscreteOcp::SimulateStatesFrom(ConstVecRef x0, const Mat& U, Mat* X) const {
  if (integrator_ != Integrator::kEuler) {
    DiscreteOcp from(*this);
    from.SetInitialState(x0);
    from.Simulate(U, X);
    return;
  }
  const int nx = ocp_.nx(), N = grid_.intervals();
  if (U.rows() != ocp_.nu() || U.cols() != N) {
    throw std::invalid_argument("DiscreteOcp::SimulateStates: U must be nu x N");
  }
  Vec f(nx);
  X->resize(nx, N + 1);
  X->col(0) = x0;
  for (int k = 0; k < N; ++k) {
    ocp_.Dynamics(grid_.t(k), X->col(k), U.col(k), f);
    X->col(k + 1).noalias() = X->col(k) + grid_.h(k) * f;  // Simulate's x += h f
  }
}

void DiscreteOcp::Adjoint(const Mat& U, const Mat& X, Mat* Lambda, Mat* G) const {
  const int nx = ocp_.nx(), nu = ocp_.nu(), N = grid_.intervals();
  Lambda->resize(nx, N + 1);
  G->resize(nu, N);
  double phi;
  Vec lam(nx);
  ocp_.TerminalObjectiveGradient(X.col(N), mode_, &phi, lam);
  Lambda->col(N) = lam;
  Vec f(nx), Lx(nx), Lu(nu), bar_x(nx), bar_u(nu), tmp_x(nx), tmp_u(nu);
  Mat fx(nx, nx), fu(nx, nu);
  double L;
  for (int k = N - 1; k >= 0; --k) {
    const double t = grid_.t(k), h = grid_.h(k);
    if (integrator_ == Integrator::kEuler) {
      ocp_.DynamicsJacobian(t, X.col(k), U.col(k), f, fx, fu);
      ocp_.RunningCostGradient(t, X.col(k), U.col(k), &L, Lx, Lu);
      // Coefficient-wise products into preallocated vectors: no heap allocation per step (the
      // blocked matrix-vector kernel and its temporaries dominate for these small sizes).
      tmp_u.noalias() = fu.transpose().lazyProduct(lam);
      G->col(k) = h * (tmp_u + Lu);
      tmp_x.noalias() = fx.transpose().lazyProduct(lam);
      lam += h * (tmp_x + Lx);
    } else {
      Rk4StepAdjoint(k, X.col(k), U.col(k), lam, &bar_x, &bar_u);
      G->col(k) = bar_u;
      lam = bar_x;
    }
    Lambda->col(k) = lam;
  }
}

}  // namespace ocpb
