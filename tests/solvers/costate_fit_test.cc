// The costate fit in one place (solvers/costate_fit.h): FitEulerCostates and
// IndirectNewton::CostatesFromControls against verbatim copies of the two fits they replaced
// (solvers/euler_costate_fit.cc and solvers/indirect_newton.cc at 691cadc), bitwise, on
// problems with free, clipped and disc-bounded controls in both terminal forms.
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>

#include "core/autodiff_ocp.h"
#include "core/control_set.h"
#include "core/discrete_ocp.h"
#include "problems/registry.h"
#include "solvers/costate_fit.h"
#include "solvers/euler_costate_fit.h"
#include "solvers/hamiltonian_descent.h"
#include "solvers/hamiltonian_family.h"
#include "solvers/indirect_newton.h"
#include "solvers/registry.h"
#include "tests/solvers/indirect_test_support.h"

namespace ocpb {
namespace legacy {

// ---- solvers/euler_costate_fit.cc at 691cadc, verbatim but for the names ----
// The components of u strictly inside U (see FitEulerCostates).
std::vector<int> EulerFreeComponents(const ControlSet& set, ConstVecRef u) {
  std::vector<int> free;
  if (set.blocks().empty()) {
    for (int i = 0; i < u.size(); ++i) free.push_back(i);
    return free;
  }
  constexpr double kMargin = 1e-6;
  for (const ControlSet::Block& b : set.blocks()) {
    if (b.kind == ControlSet::Kind::kBox) {
      for (int i = 0; i < b.size; ++i) {
        const double lo = b.lower[i], hi = b.upper[i], v = u[b.offset + i];
        const double margin = kMargin * (std::isfinite(hi - lo) ? hi - lo : 1.0);
        if (v > lo + margin && v < hi - margin) free.push_back(b.offset + i);
      }
    } else {
      const auto ub = u.segment(b.offset, b.size);
      const double r = b.center.size() > 0 ? (ub - b.center).norm() : ub.norm();
      if (r < (1.0 - kMargin) * b.radius) {
        for (int i = 0; i < b.size; ++i) free.push_back(b.offset + i);
      }
    }
  }
  return free;
}

Mat EulerFit(const Ocp& ocp, const TimeGrid& grid, TerminalMode mode, const Mat& U, const Mat& X) {
  const int nx = ocp.nx(), nu = ocp.nu(), N = grid.intervals();
  if (U.rows() != nu || U.cols() != N || X.rows() != nx || X.cols() != N + 1) {
    throw std::invalid_argument("FitEulerCostates: U must be nu x N and X nx x (N+1)");
  }
  // p_k = M_k q + c_k: M_N = I, c_N = 0; M_k = (I + h fx^T) M_{k+1}, c_k = (I + h fx^T) c_{k+1}
  // + h L_x at (t_k, x_k, u_k).
  std::vector<Mat> M(N + 1);
  std::vector<Vec> c(N + 1);
  M[N] = Mat::Identity(nx, nx);
  c[N] = Vec::Zero(nx);
  Vec f(nx), Lx(nx), Lu(nu);
  Mat fx(nx, nx), fu(nx, nu), hess(nx + nu, nx + nu);
  double L = 0.0;
  for (int k = N - 1; k >= 0; --k) {
    const double t = grid.t(k), h = grid.h(k);
    ocp.DynamicsJacobian(t, X.col(k), U.col(k), f, fx, fu);
    ocp.RunningCostGradient(t, X.col(k), U.col(k), &L, Lx, Lu);
    M[k] = M[k + 1] + h * fx.transpose() * M[k + 1];
    c[k] = c[k + 1] + h * (fx.transpose() * c[k + 1] + Lx);
  }
  Vec q0(nx);
  double phi = 0.0;
  ocp.TerminalObjectiveGradient(X.col(N), mode, &phi, q0);

  // Rows sqrt(h_k) (H_uu)_F^-1 [G_k q + g_k] of the free components, H_u = G q + g.
  std::vector<double> rows;  // [A | b] row-major
  const Vec no_mu = Vec::Zero(ocp.num_path());
  for (int k = 0; k < N; ++k) {
    const double t = grid.t(k), h = grid.h(k);
    const std::vector<int> free = EulerFreeComponents(ocp.control_set(), U.col(k));
    if (free.empty()) continue;
    ocp.DynamicsJacobian(t, X.col(k), U.col(k), f, fx, fu);
    ocp.RunningCostGradient(t, X.col(k), U.col(k), &L, Lx, Lu);
    const Vec p0 = M[k + 1] * q0 + c[k + 1];
    ocp.PointHessian(t, X.col(k), U.col(k), 1.0, p0, no_mu, hess);
    const int m = static_cast<int>(free.size());
    Mat Huu(m, m), G(m, nx);
    Vec g(m);
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) Huu(a, b) = hess(nx + free[a], nx + free[b]);
      G.row(a) = fu.col(free[a]).transpose() * M[k + 1];
      g[a] = Lu[free[a]] + fu.col(free[a]).dot(c[k + 1]);
    }
    const Eigen::LLT<Mat> llt(Huu);
    if (llt.info() == Eigen::Success && Huu.allFinite()) {
      G = llt.solve(G);
      g = llt.solve(g);
    }
    const double w = std::sqrt(h);
    for (int a = 0; a < m; ++a) {
      for (int j = 0; j < nx; ++j) rows.push_back(w * G(a, j));
      rows.push_back(-w * g[a]);
    }
  }
  Vec q = q0;
  const int count = static_cast<int>(rows.size()) / (nx + 1);
  if (count > 0) {
    Mat A(count + nx, nx);
    Vec b(count + nx);
    for (int i = 0; i < count; ++i) {
      for (int j = 0; j < nx; ++j) A(i, j) = rows[static_cast<size_t>(i) * (nx + 1) + j];
      b[i] = rows[static_cast<size_t>(i) * (nx + 1) + nx];
    }
    const double delta = 1e-8 * A.topRows(count).colwise().norm().maxCoeff();
    A.bottomRows(nx) = delta * Mat::Identity(nx, nx);
    b.tail(nx) = delta * q0;
    if (A.allFinite() && b.allFinite() && delta > 0.0) {
      const Vec fitted = A.householderQr().solve(b);
      if (fitted.allFinite()) q = fitted;
    }
  }
  Mat P(nx, N + 1);
  for (int k = 0; k <= N; ++k) P.col(k) = M[k] * q + c[k];
  return P;
}

// ---- solvers/indirect_newton.cc at 691cadc, verbatim but for the names ----
// The components of u strictly inside U (see IndirectNewton::CostatesFromControls).
void TrapezoidFreeComponents(const ControlSet& set, ConstVecRef u, std::vector<int>* free) {
  free->clear();
  if (set.blocks().empty()) {
    for (int i = 0; i < u.size(); ++i) free->push_back(i);
    return;
  }
  constexpr double kMargin = 1e-6;
  for (const ControlSet::Block& b : set.blocks()) {
    if (b.kind == ControlSet::Kind::kBox) {
      for (int i = 0; i < b.size; ++i) {
        const double lo = b.lower[i], hi = b.upper[i], v = u[b.offset + i];
        const double margin = kMargin * (std::isfinite(hi - lo) ? hi - lo : 1.0);
        if (v > lo + margin && v < hi - margin) free->push_back(b.offset + i);
      }
    } else {
      const auto ub = u.segment(b.offset, b.size);
      const double r = b.center.size() > 0 ? (ub - b.center).norm() : ub.norm();
      if (r < (1.0 - kMargin) * b.radius) {
        for (int i = 0; i < b.size; ++i) free->push_back(b.offset + i);
      }
    }
  }
}

// The kFit terminal costate of IndirectNewton::CostatesFromControls, given p_k = M_k q + c_k
// and the adjoint's q0: least squares on the stacked rows sqrt(w_k) (H_uu)_F^-1 (H_u)_F(q) of
// every node, plus the ridge rows delta (q - q0).
Vec TrapezoidTerminalCostate(const Ocp& ocp,
                             const TimeGrid& grid,
                             const ControlTrajectory& controls,
                             const Mat& X,
                             const std::vector<Mat>& M,
                             const std::vector<Vec>& c,
                             const Vec& q0) {
  const int nx = ocp.nx(), nu = ocp.nu(), N = grid.intervals();
  std::vector<double> values;  // rows of [A | b], row-major
  Vec f(nx), Lx(nx), Lu(nu), u(nu), p0(nx);
  Mat fx(nx, nx), fu(nx, nu), hess(nx + nu, nx + nu);
  double L = 0.0;
  std::vector<int> free;
  for (int k = 0; k <= N; ++k) {
    const double t = grid.t(k);
    controls.Evaluate(
        t, k < N ? ControlTrajectory::Side::kRight : ControlTrajectory::Side::kLeft, u);
    TrapezoidFreeComponents(ocp.control_set(), u, &free);
    if (free.empty()) continue;
    ocp.DynamicsJacobian(t, X.col(k), u, f, fx, fu);
    ocp.RunningCostGradient(t, X.col(k), u, &L, Lx, Lu);
    p0 = M[k] * q0 + c[k];
    ocp.PointHessian(t, X.col(k), u, 1.0, p0, Vec(), hess);
    const int m = static_cast<int>(free.size());
    Mat Huu(m, m), G(m, nx);
    Vec g(m);
    for (int a = 0; a < m; ++a) {
      for (int b = 0; b < m; ++b) Huu(a, b) = hess(nx + free[a], nx + free[b]);
      // H_u,a(q) = Lu_a + fu_a^T (M_k q + c_k) = G_a q + g_a.
      G.row(a) = fu.col(free[a]).transpose() * M[k];
      g[a] = Lu[free[a]] + fu.col(free[a]).dot(c[k]);
    }
    const Eigen::LLT<Mat> llt(Huu);
    if (llt.info() == Eigen::Success && Huu.allFinite()) {
      G = llt.solve(G);
      g = llt.solve(g);
    }
    const double hw = 0.5 * ((k > 0 ? grid.h(k - 1) : 0.0) + (k < N ? grid.h(k) : 0.0));
    const double w = std::sqrt(hw);
    for (int a = 0; a < m; ++a) {
      for (int j = 0; j < nx; ++j) values.push_back(w * G(a, j));
      values.push_back(-w * g[a]);
    }
  }
  const int rows = static_cast<int>(values.size()) / (nx + 1);
  if (rows == 0) return q0;
  Mat A(rows + nx, nx);
  Vec b(rows + nx);
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < nx; ++j) A(i, j) = values[static_cast<size_t>(i) * (nx + 1) + j];
    b[i] = values[static_cast<size_t>(i) * (nx + 1) + nx];
  }
  const double delta = 1e-8 * A.topRows(rows).colwise().norm().maxCoeff();
  A.bottomRows(nx) = delta * Mat::Identity(nx, nx);
  b.tail(nx) = delta * q0;
  if (!A.allFinite() || !b.allFinite() || !(delta > 0.0)) return q0;
  const Vec q = A.householderQr().solve(b);
  return q.allFinite() ? q : q0;
}

void TrapezoidFit(const Ocp& ocp,
                  const TimeGrid& grid,
                  TerminalMode mode,
                  const ControlTrajectory& controls,
                  const Mat& X,
                  Mat* P) {
  const int nx = ocp.nx(), nu = ocp.nu(), N = grid.intervals();
  if (X.rows() != nx || X.cols() != N + 1 || controls.nu() != nu) {
    throw std::invalid_argument(
        std::string("legacy") +
        ": the start's states must be nx x (N+1) and its controls nu-valued");
  }
  // Backward sweep of p_{k+1} - p_k + h/2 (H_x,k + H_x,k+1) = 0, H_x = L_x + f_x^T p, as
  // p_k = M_k q + c_k: (I - h/2 fx_k^T) p_k = (I + h/2 fx_k+1^T) p_{k+1} + h/2 (Lx_k + Lx_k+1).
  std::vector<Mat> M(N + 1);
  std::vector<Vec> c(N + 1);
  M[N] = Mat::Identity(nx, nx);
  c[N] = Vec::Zero(nx);
  Vec f(nx), Lx(nx), Lu(nu), ua(nu), ub(nu), rhs(nx);
  Mat fx(nx, nx), fu(nx, nu), B(nx, nx);
  double L = 0.0;
  for (int k = N - 1; k >= 0; --k) {
    const double hh = 0.5 * grid.h(k);
    controls.Evaluate(grid.t(k + 1), ControlTrajectory::Side::kLeft, ub);
    controls.Evaluate(grid.t(k), ControlTrajectory::Side::kRight, ua);
    ocp.DynamicsJacobian(grid.t(k + 1), X.col(k + 1), ub, f, fx, fu);
    ocp.RunningCostGradient(grid.t(k + 1), X.col(k + 1), ub, &L, Lx, Lu);
    B = Mat::Identity(nx, nx) + hh * fx.transpose();
    rhs = hh * Lx;
    ocp.DynamicsJacobian(grid.t(k), X.col(k), ua, f, fx, fu);
    ocp.RunningCostGradient(grid.t(k), X.col(k), ua, &L, Lx, Lu);
    rhs += hh * Lx;
    const Eigen::PartialPivLU<Mat> A((Mat::Identity(nx, nx) - hh * fx.transpose()).eval());
    M[k] = A.solve(B * M[k + 1]);
    c[k] = A.solve(B * c[k + 1] + rhs);
  }
  Vec q(nx);
  double value = 0.0;
  ocp.TerminalObjectiveGradient(X.col(N), mode, &value, q);
  q = TrapezoidTerminalCostate(ocp, grid, controls, X, M, c, q);
  P->resize(nx, N + 1);
  for (int k = 0; k <= N; ++k) P->col(k) = M[k] * q + c[k];
}

}  // namespace legacy

namespace {

// Controls that are free at some nodes and on the boundary of U at others: a smooth profile
// past U's bounds, projected onto U. nu x cols.
Mat MixedControls(const Ocp& ocp, int cols) {
  const Vec nominal = ocp.NominalControl();
  Mat U(ocp.nu(), cols);
  for (int k = 0; k < cols; ++k) {
    for (int i = 0; i < ocp.nu(); ++i) {
      const double scale = std::max(1.0, std::abs(nominal[i]));
      U(i, k) = nominal[i] + 1.3 * scale * std::sin(0.37 * k + 1.1 * i);
    }
    ocp.control_set().Project(U.col(k));
  }
  return U;
}

struct FitCase {
  const char* problem;
  std::vector<std::string> params;
  bool mayer = false;  // L = 0: the adjoint sweep replaces the degenerate fit
};

std::vector<FitCase> Cases() {
  return {{"comm-path2d", {"channel=0", "gamma=1e-3"}},
          {"vanderpol", {}},
          {"lqr", {}},
          {"bryson-denham", {}},
          {"catmix", {"eps=1e-4"}},
          {"catmix", {}, true},  // COPS' problem, eps = 0: Mayer
          {"double-integrator", {}},
          {"brachistochrone-free-time", {}},  // L = 1: a constant L keeps its fit
          {"brachistochrone", {}}};
}

void ExpectBitwiseEqual(const Mat& now, const Mat& before) {
  ASSERT_EQ(now.rows(), before.rows());
  ASSERT_EQ(now.cols(), before.cols());
  ASSERT_TRUE(before.allFinite());
  EXPECT_TRUE((now.array() == before.array()).all())
      << "max |now - before| = " << (now - before).lpNorm<Eigen::Infinity>();
}

// Free components over the columns of U: the fit has rows to solve, and (where U is bounded)
// some controls on the boundary, so neither branch of the fit goes untested.
void ExpectMixed(const Ocp& ocp, const Mat& U, int* free_total, int* bound_total) {
  std::vector<int> free;
  for (int k = 0; k < U.cols(); ++k) {
    FreeControlComponents(ocp.control_set(), U.col(k), &free);
    *free_total += static_cast<int>(free.size());
    *bound_total += ocp.nu() - static_cast<int>(free.size());
  }
}

TEST(CostateFit, EulerFitIsBitwiseTheFitItReplaced) {
  int free_total = 0, bound_total = 0;
  for (const FitCase& c : Cases()) {
    const auto ocp = MakeProblem(c.problem, c.params, 1);
    const int N = 40;
    const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
    const Mat U = MixedControls(*ocp, N);
    ExpectMixed(*ocp, U, &free_total, &bound_total);
    for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
      if (mode == TerminalMode::kHard && ocp->num_terminal() == 0) continue;
      SCOPED_TRACE(std::string(c.problem) + " " + ToString(mode));
      Mat X;
      DiscreteOcp(*ocp, grid, Integrator::kEuler, mode).Simulate(U, &X);
      bool fallback = !c.mayer;
      const Mat P = FitEulerCostates(*ocp, grid, mode, U, X, &fallback);
      EXPECT_EQ(fallback, c.mayer);
      if (!c.mayer) ExpectBitwiseEqual(P, legacy::EulerFit(*ocp, grid, mode, U, X));
    }
  }
  EXPECT_GT(free_total, 100);
  EXPECT_GT(bound_total, 100);
}

TEST(CostateFit, TrapezoidFitIsBitwiseTheFitItReplaced) {
  int free_total = 0, bound_total = 0;
  for (const FitCase& c : Cases()) {
    const auto ocp = MakeProblem(c.problem, c.params, 1);
    const int N = 40;
    const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
    const Mat nodes = MixedControls(*ocp, N + 1);
    ExpectMixed(*ocp, nodes, &free_total, &bound_total);
    for (const bool linear : {true, false}) {
      const ControlTrajectory controls =
          linear ? ControlTrajectory::PiecewiseLinear(grid, nodes)
                 : ControlTrajectory::PiecewiseConstant(grid, nodes.leftCols(N));
      for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
        if (mode == TerminalMode::kHard && ocp->num_terminal() == 0) continue;
        SCOPED_TRACE(std::string(c.problem) + " " + ToString(mode) +
                     (linear ? " piecewise linear" : " piecewise constant"));
        Mat X;
        DiscreteOcp(*ocp, grid, Integrator::kEuler, mode).Simulate(nodes.leftCols(N), &X);
        Mat now, before;
        bool fallback = !c.mayer;
        IndirectNewton::CostatesFromControls(*ocp,
                                             grid,
                                             mode,
                                             controls,
                                             X,
                                             IndirectNewton::Options::Costates::kFit,
                                             &now,
                                             &fallback);
        EXPECT_EQ(fallback, c.mayer);
        legacy::TrapezoidFit(*ocp, grid, mode, controls, X, &before);
        if (!c.mayer) ExpectBitwiseEqual(now, before);
      }
    }
  }
  EXPECT_GT(free_total, 100);
  EXPECT_GT(bound_total, 100);
}

// The shared solve itself: on a linear-quadratic problem the fitted q reproduces stationary
// controls exactly (the rows' least-squares residual is zero at the true q), and the checks of
// its arguments throw.
TEST(CostateFit, RecoversTheTerminalCostateOfStationaryControls) {
  const auto ocp = MakeProblem("lqr", {}, 0);
  const int N = 30;
  const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
  const SolveResult descent = HamiltonianDescent().Solve(
      *ocp, Request(*ocp, N, TerminalMode::kPenalty, {{"max_iterations", "5000"}}));
  ASSERT_LE(std::abs(descent.solver_stats.at("final_theta")), 1e-12) << descent.message;
  const Mat P = FitEulerCostates(
      *ocp, grid, TerminalMode::kPenalty, descent.controls.values(), descent.states);
  EXPECT_LE((P - descent.costates).lpNorm<Eigen::Infinity>(),
            1e-6 * (1.0 + descent.costates.lpNorm<Eigen::Infinity>()));

  CostateFitNodes nodes;
  const Mat X = descent.states, U = descent.controls.values();
  nodes.t = {0.0};
  nodes.weight = {1.0, 2.0};  // one weight too many
  nodes.X = &X;
  nodes.U = &U;
  const std::vector<Mat> M(N + 1, Mat::Identity(ocp->nx(), ocp->nx()));
  const std::vector<Vec> c(N + 1, Vec::Zero(ocp->nx()));
  EXPECT_THROW(FitTerminalCostate(*ocp, nodes, M, c, Vec::Zero(ocp->nx())), std::invalid_argument);
  nodes.weight = {1.0};
  nodes.costate_offset = N + 1;  // past the costates
  EXPECT_THROW(FitTerminalCostate(*ocp, nodes, M, c, Vec::Zero(ocp->nx())), std::invalid_argument);
  nodes.costate_offset = 0;
  const CostateFit fit = FitTerminalCostate(*ocp, nodes, M, c, Vec::Ones(ocp->nx()));
  EXPECT_EQ(fit.rows, ocp->nu());
  EXPECT_TRUE(fit.q.allFinite());
}

// The minimum-energy double integrator in Mayer form: the energy is a state,
//   minimize e(1),  x1' = x2,  x2' = u,  e' = u^2 / 2,  x(0) = 0,  psi = (x1(1) - 1, x2(1)) = 0,
//   |u| <= 10.
// H = p1 x2 + p2 u + p3 u^2 / 2 with p3 = 1 (e enters nothing): u* = clip(-p2 / p3) for p3 > 0.
// Optimum: u = 6 - 12 t, J = 6, p = (-12, 12 t - 6, 1), nu = (-12, 6). L = 0, so the costate
// fit's rows are homogeneous (H_u = f_u^T p): its least-squares q is ~0.
class MayerDoubleIntegrator final : public AutoDiffOcp<MayerDoubleIntegrator, 3, 1, 2, 0> {
 public:
  static constexpr double kUmax = 10.0;
  explicit MayerDoubleIntegrator(double weight = 100.0) {
    SetHorizon(0.0, 1.0);
    SetInitialState(Vec::Zero(3));
    SetTerminalWeights(Vec::Constant(2, weight));
    SetControlSet(ControlSet::Box(Vec::Constant(1, -kUmax), Vec::Constant(1, kUmax)));
  }
  std::string name() const override { return "mayer-double-integrator"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 1>& u, VecT<T, 3>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0];
    (*f)[2] = 0.5 * u[0] * u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 3>&, const VecT<T, 1>&) const {
    return T(0.0);
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 3>& x) const {
    return x[2];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] - 1.0;
    (*psi)[1] = x[1];
  }
  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const override {
    if (p[2] > 0.0) {
      u[0] = std::clamp(-p[1] / p[2], -kUmax, kUmax);
    } else {
      u[0] = p[1] > 0.0 ? -kUmax : kUmax;  // H concave or linear in u: an end of U
    }
  }
};

// The start's costates of a Mayer problem: the old fit's are near zero and Newton fails from
// them; the adjoint sweep's start converges to the discrete optimum (Ipopt on the same
// discrete problem), which approaches J* = 6.
SolveResult EulerIpopt(const Ocp& ocp, int N, TerminalMode mode, const char* transcription) {
  SolveRequest request = Request(ocp, N, mode);
  request.transcription = transcription;
  return FindSolver("ipopt").make()->Solve(ocp, request);
}

TEST(MayerStart, EulerNewtonConvergesFromTheAdjointSweep) {
  const MayerDoubleIntegrator ocp;
  const int N = 50;
  const SolveResult descent = HamiltonianDescent().Solve(
      ocp, Request(ocp, N, TerminalMode::kPenalty, {{"max_iterations", "200"}}));
  ASSERT_TRUE(descent.states.allFinite()) << descent.message;
  const Mat& U = descent.controls.values();
  const TimeGrid& grid = descent.state_grid;
  IndirectNewtonOptions no;
  no.scheme = IndirectNewtonOptions::Scheme::kEuler;
  for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
    SCOPED_TRACE(ToString(mode));
    const SolveResult ipopt = EulerIpopt(ocp, N, mode, "euler");
    ASSERT_EQ(ipopt.status, SolveStatus::kConverged) << ipopt.message;
    // The old start: costates ~0 (the ridge's shrinkage of q0). (Newton happens to converge
    // from them here: u* = -p2 / p3 does not see the scale of p; see the next test.)
    const Mat old_start = legacy::EulerFit(ocp, grid, mode, U, descent.states);
    EXPECT_LE(old_start.lpNorm<Eigen::Infinity>(), 1e-6);
    // The new start: the adjoint sweep of the descent's controls, the descent's own costates.
    bool fallback = false;
    const Mat P = FitEulerCostates(ocp, grid, mode, U, descent.states, &fallback);
    EXPECT_TRUE(fallback);
    EXPECT_LE((P - descent.costates).lpNorm<Eigen::Infinity>(),
              1e-10 * descent.costates.lpNorm<Eigen::Infinity>());
    const SolveResult newton =
        IndirectNewton(no).SolveFrom(ocp, Request(ocp, N, mode), descent.states, P);
    ExpectConverged(newton);
    EXPECT_NEAR(newton.objective, ipopt.objective, 1e-6 * std::abs(ipopt.objective));
    if (mode == TerminalMode::kHard) {
      EXPECT_NEAR(newton.objective, 6.0, 0.5);
    }
  }
}

TEST(MayerStart, HamiltonianPolishConvergesAndRecordsItsStart) {
  const MayerDoubleIntegrator ocp;
  const int N = 50;
  const SolveResult ipopt = EulerIpopt(ocp, N, TerminalMode::kHard, "euler");
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged) << ipopt.message;
  const SolveResult r = HamiltonianFamily(HamiltonianFamily::Preset::kPolish)
                            .Solve(ocp, Request(ocp, N, TerminalMode::kHard));
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
  EXPECT_EQ(r.solver_stats.at("newton_attempts"), 1.0);
  EXPECT_EQ(r.solver_stats.at("start_adjoint_fallback"), 1.0);
  EXPECT_NE(r.message.find("adjoint costates (Mayer cost"), std::string::npos) << r.message;
  EXPECT_NEAR(r.objective, ipopt.objective, 1e-6 * std::abs(ipopt.objective));
  // A problem with a running cost keeps the fitted start (and its records: stat 0).
  const auto vdp = MakeProblem("vanderpol", {}, 0);
  const SolveResult v = HamiltonianFamily(HamiltonianFamily::Preset::kPolish)
                            .Solve(*vdp, Request(*vdp, 40, TerminalMode::kPenalty));
  EXPECT_EQ(v.solver_stats.at("start_adjoint_fallback"), 0.0);
}

TEST(MayerStart, IndirectNewtonConvergesFromTheAdjointSweep) {
  const MayerDoubleIntegrator ocp(1.0);
  const int N = 50;
  SolveRequest request = Request(ocp, N, TerminalMode::kHard);
  // A start from u = 3, far from the optimum u = 6 - 12 t.
  request.initial_guess = ControlTrajectory::Constant(request.grid, Vec::Constant(1, 3.0));
  const SolveResult r = IndirectNewton().Solve(ocp, request);
  ExpectConverged(r);
  EXPECT_EQ(r.solver_stats.at("start_adjoint_fallback"), 1.0);
  // The trapezoid is second order: J within O(h^2) of J* = 6.
  EXPECT_NEAR(r.objective, 6.0, 1e-2);
}

}  // namespace
}  // namespace ocpb
