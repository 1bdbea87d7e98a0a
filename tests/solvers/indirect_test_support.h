// Helpers shared by the indirect method's test files (tests/solvers/indirect_*_test.cc).
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "core/derivative_check.h"
#include "core/ocp.h"
#include "solvers/pmp_residual.h"
#include "solvers/solver.h"

namespace ocpb {

/// A request on the uniform N-interval grid of the problem's (nominal) horizon.
inline SolveRequest Request(const Ocp& ocp,
                            int N,
                            TerminalMode mode = TerminalMode::kPenalty,
                            std::map<std::string, std::string> options = {}) {
  SolveRequest r;
  r.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  r.terminal = mode;
  r.options = std::move(options);
  return r;
}

// Quadratic convergence at the end of a solve: over the last kTailSteps Newton steps, every step
// from |F_k| <= 1e-2 to |F_{k+1}| above the roundoff floor must satisfy
// |F_{k+1}| <= bound |F_k|^2. Returns the number of steps tested: the callers assert it is at
// least the number they observed, so the check cannot pass vacuously.
inline constexpr int kTailSteps = 3;
inline int ExpectQuadraticTail(const SolveResult& r, double bound, double floor = 1e-12) {
  int checked = 0;
  const size_t first = r.history.size() > kTailSteps ? r.history.size() - kTailSteps : 1;
  for (size_t k = std::max<size_t>(first, 1); k < r.history.size(); ++k) {
    const double a = r.history[k - 1].primal_inf, b = r.history[k].primal_inf;
    if (a > 1e-2 || b <= floor) continue;  // only near the solution, above roundoff
    EXPECT_LE(b / (a * a), bound) << "iterate " << k << ": |F| " << a << " -> " << b;
    ++checked;
  }
  return checked;
}

inline void ExpectConverged(const SolveResult& r) {
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.solver_status << ": " << r.message;
  EXPECT_EQ(r.solver_status, "converged");
  EXPECT_LE(r.history.back().primal_inf, 1e-10);
  EXPECT_EQ(static_cast<int>(r.history.size()), r.iterations + 1);
}

/// The residual's sparse Jacobian (of `scheme`) on a 5-interval grid against central finite
/// differences at z0, and every finite-difference nonzero inside the declared structure.
inline void ExpectJacobianMatchesFiniteDifferences(
    const Ocp& ocp,
    TerminalMode mode,
    const Vec& z0,
    PmpResidual::Scheme scheme = PmpResidual::Scheme::kTrapezoid) {
  PmpResidual pmp(ocp, TimeGrid::Uniform(ocp.t0(), ocp.tf(), 5), mode, scheme);
  ASSERT_EQ(z0.size(), pmp.size());
  Vec F(pmp.size());
  ASSERT_TRUE(pmp.Evaluate(z0, F, nullptr, true)) << pmp.FailureMessage();
  const Mat analytic = Mat(pmp.jacobian());
  auto residual = [&](const Vec& z) {
    Vec out(pmp.size());
    EXPECT_TRUE(pmp.Evaluate(z, out, nullptr, false));
    return out;
  };
  const Mat fd = CentralJacobian(residual, z0);
  const double err = (analytic - fd).lpNorm<Eigen::Infinity>();
  EXPECT_LE(err, 1e-6 * std::max(1.0, fd.lpNorm<Eigen::Infinity>())) << "max |J - J_fd| = " << err;
  // Every finite-difference nonzero lies in the declared structure (the dense copy of the sparse
  // matrix has an explicit entry wherever the structure has one).
  Eigen::SparseMatrix<double> pattern = pmp.jacobian();
  for (int k = 0; k < pattern.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(pattern, k); it; ++it) it.valueRef() = 1.0;
  }
  const Mat structure = Mat(pattern);
  for (int i = 0; i < fd.rows(); ++i) {
    for (int j = 0; j < fd.cols(); ++j) {
      if (std::abs(fd(i, j)) > 1e-8) {
        EXPECT_EQ(structure(i, j), 1.0) << i << ", " << j;
      }
    }
  }
}

inline Vec SomePoint(int size, double scale, double shift) {
  Vec z(size);
  for (int i = 0; i < size; ++i) z[i] = scale * std::sin(1.3 * i + shift);
  return z;
}

}  // namespace ocpb
