// ConvexPointMinimizer (the generic proximal and AL Hamiltonian minimizer) against brute force
// and against closed forms.
#include "solvers/convex_point_minimizer.h"

#include <cmath>
#include <limits>
#include <random>

#include <gtest/gtest.h>

#include "core/proximal_hamiltonian.h"
#include "problems/registry.h"

namespace ocpb {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// phi at w no worse than at any point of a grid over U's bounding box (projected) and random
// points near w.
void ExpectBeatsBruteForce(const Ocp& ocp,
                           ConvexPointMinimizer& m,
                           double t,
                           const Vec& x,
                           const Vec& p,
                           const Vec& center,
                           double eps,
                           const Vec& w) {
  Vec lo, hi;
  ocp.control_set().BoundingBox(&lo, &hi);
  const int nu = ocp.nu();
  for (int i = 0; i < nu; ++i) {
    if (!std::isfinite(lo[i])) lo[i] = w[i] - 5.0;
    if (!std::isfinite(hi[i])) hi[i] = w[i] + 5.0;
  }
  const double best_w = m.Objective(t, x, p, center, eps, w);
  const int per = nu == 1 ? 4001 : (nu == 2 ? 201 : 41);
  Vec v(nu);
  std::vector<int> idx(nu, 0);
  double best = kInf;
  for (;;) {
    for (int i = 0; i < nu; ++i) v[i] = lo[i] + (hi[i] - lo[i]) * idx[i] / (per - 1.0);
    ocp.control_set().Project(v);
    best = std::min(best, m.Objective(t, x, p, center, eps, v));
    int i = 0;
    while (i < nu && ++idx[i] == per) idx[i++] = 0;
    if (i == nu) break;
  }
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int s = 0; s < 3000; ++s) {
    for (int i = 0; i < nu; ++i) v[i] = w[i] + unit(rng) * std::pow(10.0, -1.0 - (s % 5));
    ocp.control_set().Project(v);
    best = std::min(best, m.Objective(t, x, p, center, eps, v));
  }
  EXPECT_LE(best_w, best + 1e-10 * (1.0 + std::abs(best)));
}

// A quadratic-in-u Hamiltonian with a box (the bounded double integrator): the first step is the
// exact minimizer, with and without the proximal term, and it matches the problem's u*.
TEST(ConvexPointMinimizer, QuadraticHamiltonianInOneStep) {
  const auto ocp = MakeProblem("double-integrator-bounded", {"umax=1"}, 0);
  ConvexPointMinimizer m(*ocp);
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> unit(-3.0, 3.0);
  for (int trial = 0; trial < 20; ++trial) {
    Vec x(2), p(2), c(1), w(1), u_star(1);
    x << unit(rng), unit(rng);
    p << unit(rng), unit(rng);
    c << 0.3 * unit(rng);
    const int steps = m.Minimize(0.2, x, p, c, kInf, c, w);
    EXPECT_GE(steps, 1);
    EXPECT_LE(steps, 2);
    ocp->MinimizeHamiltonian(0.2, x, p, u_star);
    EXPECT_NEAR(w[0], u_star[0], 1e-14);
    for (double eps : {0.01, 0.5, 10.0}) {
      const int s = m.Minimize(0.2, x, p, c, eps, c, w);
      EXPECT_GE(s, 1);
      EXPECT_LE(s, 2);
      ExpectBeatsBruteForce(*ocp, m, 0.2, x, p, c, eps, w);
    }
  }
}

// A non-quadratic H on a ball times a box (comm-path2d with k5, k6 > 0: the smoothed norms and
// 2^R): the generic minimizer agrees with the problem's closed-form proximal minimizer and beats
// brute force.
TEST(ConvexPointMinimizer, AgreesWithCommPath2dsClosedForm) {
  const auto ocp = MakeProblem("comm-path2d", {"channel=0", "k=17.75,1.16,10.46,1175,2,1"}, 1);
  const auto* closed = dynamic_cast<const ProximalHamiltonianMinimizer*>(ocp.get());
  ASSERT_NE(closed, nullptr);
  ConvexPointMinimizer m(*ocp);
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < 12; ++trial) {
    Vec x(5), p(5), c(3), w(3), w_ref(3);
    x << 20.0 + 10.0 * unit(rng), 20.0 + 10.0 * unit(rng), unit(rng), unit(rng), 10.0;
    for (int i = 0; i < 4; ++i) p[i] = 0.2 * unit(rng);
    p[4] = -1e-3 * (1.0 + unit(rng)) * std::pow(10.0, -2.0 * std::abs(unit(rng)));
    c << 0.3 * unit(rng), 0.3 * unit(rng), 3.0 + 3.0 * unit(rng);
    for (double eps : {0.1, 3.0, 100.0}) {
      const int steps = m.Minimize(0.0, x, p, c, eps, c, w);
      EXPECT_GE(steps, 1) << "did not converge";
      closed->MinimizeProximalHamiltonian(0.0, x, p, c, eps, w_ref);
      EXPECT_LE((w - w_ref).lpNorm<Eigen::Infinity>(), 1e-7) << "eps " << eps;
      EXPECT_LE(m.Objective(0.0, x, p, c, eps, w_ref), m.Objective(0.0, x, p, c, eps, w) + 1e-12);
    }
  }
}

TEST(ConvexPointMinimizer, InvalidOptionsThrow) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  ConvexPointMinimizerOptions o;
  o.max_iterations = 0;
  EXPECT_THROW(ConvexPointMinimizer(*ocp, o), std::invalid_argument);
  o = ConvexPointMinimizerOptions();
  o.sufficient_decrease = 0.7;
  EXPECT_THROW(ConvexPointMinimizer(*ocp, o), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
