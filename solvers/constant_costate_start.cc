#include "solvers/constant_costate_start.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>

namespace ocpb {
namespace {

// The components i with column i of f_x and L_x exactly zero at every node of (U, X): the
// derivatives are exact (AD or tested), so a structural zero is a zero here.
std::vector<int> IntegratorComponents(const Ocp& ocp,
                                      const TimeGrid& grid,
                                      const Mat& U,
                                      const Mat& X) {
  const int nx = ocp.nx(), nu = ocp.nu();
  std::vector<bool> zero(static_cast<size_t>(nx), true);
  Vec f(nx), Lx(nx), Lu(nu);
  Mat fx(nx, nx), fu(nx, nu);
  double L = 0.0;
  for (int k = 0; k < grid.intervals(); ++k) {
    ocp.DynamicsJacobian(grid.t(k), X.col(k), U.col(k), f, fx, fu);
    ocp.RunningCostGradient(grid.t(k), X.col(k), U.col(k), &L, Lx, Lu);
    for (int i = 0; i < nx; ++i) {
      // Written so that a NaN entry counts as nonzero.
      if (!(Lx[i] == 0.0) || (fx.col(i).array() != 0.0).any()) zero[i] = false;
    }
  }
  std::vector<int> components;
  for (int i = 0; i < nx; ++i) {
    if (zero[i]) components.push_back(i);
  }
  return components;
}

// The row r of psi that is x_i's terminal condition: the only row with a nonzero entry in column
// i, depending on x_i alone (so psi_r(x_N) = 0 is a condition on x_i(N) only); none otherwise.
std::optional<int> TerminalRowOf(const Ocp& ocp, ConstVecRef xN, int i) {
  const int npsi = ocp.num_terminal();
  Vec psi(npsi);
  Mat psix(npsi, ocp.nx());
  ocp.TerminalConstraintsJacobian(xN, psi, psix);
  std::optional<int> row;
  for (int r = 0; r < npsi; ++r) {
    if (psix(r, i) == 0.0) continue;
    if (row) return std::nullopt;  // two rows constrain x_i
    row = r;
  }
  if (!row) return std::nullopt;
  for (int j = 0; j < ocp.nx(); ++j) {
    if (j != i && psix(*row, j) != 0.0) return std::nullopt;  // the row couples x_i to others
  }
  return row;
}

// g(c) of one component (see ConstantCostateStart), with x_i(k; c) written to xi.
class TerminalEquation {
 public:
  TerminalEquation(const Ocp& ocp,
                   const TimeGrid& grid,
                   TerminalMode mode,
                   const Mat& X,
                   const Mat& P,
                   int i,
                   std::optional<int> row)
      : ocp_(ocp), grid_(grid), mode_(mode), X_(X), P_(P), i_(i), row_(row) {}

  double operator()(double c, Vec* xi) {
    ++evaluations_;
    const int nx = ocp_.nx(), N = grid_.intervals();
    Vec p(nx), u(ocp_.nu()), f(nx);
    xi->resize(N + 1);
    (*xi)[0] = X_(i_, 0);
    for (int k = 0; k < N; ++k) {
      p = P_.col(k + 1);
      p[i_] = c;
      ocp_.MinimizeHamiltonian(grid_.t(k), X_.col(k), p, u);
      ocp_.Dynamics(grid_.t(k), X_.col(k), u, f);
      (*xi)[k + 1] = (*xi)[k] + grid_.h(k) * f[i_];
    }
    Vec xN = X_.col(N);
    xN[i_] = (*xi)[N];
    if (mode_ == TerminalMode::kHard) {
      Vec psi(ocp_.num_terminal());
      ocp_.TerminalConstraints(xN, psi);
      return psi[*row_];
    }
    Vec grad(nx);
    double value = 0.0;
    ocp_.TerminalObjectiveGradient(xN, TerminalMode::kPenalty, &value, grad);
    return c - grad[i_];
  }
  int evaluations() const { return evaluations_; }

 private:
  const Ocp& ocp_;
  const TimeGrid& grid_;
  TerminalMode mode_;
  const Mat& X_;
  const Mat& P_;
  int i_;
  std::optional<int> row_;
  int evaluations_ = 0;
};

struct Root {
  double c = NAN;
  Vec xi;
  double residual = INFINITY;  ///< |g(c)|
};

// A bracket [a, b] with g(a) g(b) <= 0, searched outwards from c0 in both directions by steps
// |c0| 4^j / 4 (the scale of the costate is unknown; the fitted one can be off by orders of
// magnitude and of the wrong sign); the nearer end of each bracket is the last point tried on
// that side, so the bracket is as tight as the search allows.
bool Bracket(
    TerminalEquation& g, double c0, double g0, double* a, double* ga, double* b, double* gb) {
  constexpr int kExpansions = 31;
  const double scale = c0 != 0.0 ? std::abs(c0) : 1.0;
  Vec xi;
  double inner[2] = {c0, c0}, g_inner[2] = {g0, g0};
  for (int j = 0; j < kExpansions; ++j) {
    const double step = 0.25 * scale * std::pow(4.0, j);
    for (int side = 0; side < 2; ++side) {
      const double c = side == 0 ? c0 - step : c0 + step;
      const double gc = g(c, &xi);
      if (!std::isfinite(gc)) continue;
      if ((gc <= 0.0) != (g0 <= 0.0) || gc == 0.0) {
        *a = inner[side], *ga = g_inner[side], *b = c, *gb = gc;
        return true;
      }
      inner[side] = c, g_inner[side] = gc;
    }
  }
  return false;
}

// The root of g in a bracket by the Illinois method (regula falsi with the stale end's value
// halved), ended at |g| <= tolerance or a bracket of relative width 1e-15.
Root Refine(TerminalEquation& g, double a, double ga, double b, double gb, double tolerance) {
  constexpr int kMaxSteps = 100;
  Root best;
  double g_best = INFINITY;
  Vec xi;
  int stale = 0;  // -1: a kept twice in a row, +1: b kept twice
  for (int step = 0; step < kMaxSteps; ++step) {
    double c = (a * gb - b * ga) / (gb - ga);
    if (!std::isfinite(c) || c <= std::min(a, b) || c >= std::max(a, b)) c = 0.5 * (a + b);
    const double gc = g(c, &xi);
    if (!std::isfinite(gc)) return best;
    if (std::abs(gc) < g_best) g_best = std::abs(gc), best = {c, xi, g_best};
    if (std::abs(gc) <= tolerance) break;
    if ((gc <= 0.0) == (ga <= 0.0)) {
      a = c, ga = gc;
      if (stale == 1) gb *= 0.5;
      stale = 1;
    } else {
      b = c, gb = gc;
      if (stale == -1) ga *= 0.5;
      stale = -1;
    }
    if (std::abs(b - a) <= 1e-15 * std::max(std::abs(a), std::abs(b))) break;
  }
  return best;
}

}  // namespace

ConstantCostateStartOutcome ConstantCostateStart(
    const Ocp& ocp, const TimeGrid& grid, TerminalMode mode, const Mat& U, Mat* X, Mat* P) {
  const int nx = ocp.nx(), N = grid.intervals();
  if (U.rows() != ocp.nu() || U.cols() != N || X->rows() != nx || X->cols() != N + 1 ||
      P->rows() != nx || P->cols() != N + 1) {
    throw std::invalid_argument(
        "ConstantCostateStart: U must be nu x N and X, P nx x (N+1) on the grid");
  }
  ConstantCostateStartOutcome outcome;
  for (const int i : IntegratorComponents(ocp, grid, U, *X)) {
    ++outcome.candidates;
    std::optional<int> row;
    if (mode == TerminalMode::kHard) {
      row = TerminalRowOf(ocp, X->col(N), i);
      if (!row) continue;  // x_i(N) is free or coupled: no scalar equation
    }
    TerminalEquation g(ocp, grid, mode, *X, *P, i, row);
    Vec xi;
    const double c0 = (*P)(i, N);
    const double g0 = g(c0, &xi);
    // The equation's scale: x_i's (hard form) or the costate's (penalty form).
    const double scale = mode == TerminalMode::kHard
                             ? std::max({1.0, std::abs((*X)(i, 0)), std::abs(xi[N])})
                             : std::max(1.0, std::abs(c0));
    const double tolerance = 1e-13 * scale;
    Root root;
    if (std::isfinite(g0) && std::abs(g0) <= tolerance) {
      root = {c0, xi, std::abs(g0)};
    } else if (double a, ga, b, gb; std::isfinite(g0) && Bracket(g, c0, g0, &a, &ga, &b, &gb)) {
      root = gb == 0.0 ? Root{b, Vec(), 0.0} : Refine(g, a, ga, b, gb, tolerance);
      if (gb == 0.0) g(b, &root.xi);
    }
    outcome.evaluations += g.evaluations();
    // Applied only where the equation holds: a bracket can also close on a jump of g (a
    // clipped or bang-bang control in f_i), whose best point solves nothing. 1e-9 of the scale
    // leaves room for the last digits regula falsi cannot resolve.
    if (!std::isfinite(root.c) || !(root.residual <= 1e-9 * scale)) continue;
    P->row(i).setConstant(root.c);
    X->row(i) = root.xi.transpose();
    ++outcome.solved;
  }
  return outcome;
}

}  // namespace ocpb
