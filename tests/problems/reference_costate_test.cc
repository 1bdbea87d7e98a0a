// Known optimal costates of the reference problems (ProblemInfo::reference_costate) and the
// observed convergence order of the multiplier costate estimates of Hermite-Simpson and LGR on
// lqr and hager, measured with the records' RelativeCostateError.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/costate_error.h"
#include "problems/reference/hager.h"
#include "problems/reference/lqr.h"
#include "problems/registry.h"
#include "tests/problems/reference_test_support.h"

namespace ocpb {
namespace {

using reference_testing::Request;
using reference_testing::SolveWith;

// The closed form solves the maximum principle: x(0) = x0, p(5) = 0, and, by central
// differences, x' = A x - B B^T p, p' = -H_x = -x - A^T p; and 1/2 x0^T p(0) = J* (for an LQR,
// J*(x0) = 1/2 x0^T P(0) x0 with p(0) = P(0) x0).
TEST(ReferenceCostate, LqrClosedFormSolvesTheMaximumPrinciple) {
  const Eigen::Vector2d x0(0.0, 1.0);
  EXPECT_LT((Lqr::OptimalState(0.0) - x0).norm(), 1e-14);
  EXPECT_LT(Lqr::OptimalCostate(5.0).norm(), 1e-12);
  EXPECT_NEAR(0.5 * x0.dot(Lqr::OptimalCostate(0.0)), Lqr::kReferenceCost, 1e-10);
  const Eigen::Matrix2d A = Lqr::A();
  const Eigen::Vector2d B = Lqr::B();
  for (double t : {0.2, 1.0, 2.5, 3.7, 4.9}) {
    const double d = 1e-5;
    const Eigen::Vector2d dx = (Lqr::OptimalState(t + d) - Lqr::OptimalState(t - d)) / (2 * d);
    const Eigen::Vector2d dp = (Lqr::OptimalCostate(t + d) - Lqr::OptimalCostate(t - d)) / (2 * d);
    const Eigen::Vector2d x = Lqr::OptimalState(t), p = Lqr::OptimalCostate(t);
    EXPECT_LT((dx - (A * x - B * B.dot(p))).cwiseAbs().maxCoeff(), 1e-8) << "t = " << t;
    EXPECT_LT((dp + x + A.transpose() * p).cwiseAbs().maxCoeff(), 1e-8) << "t = " << t;
  }
}

// The registry's p* is the problems' own closed form (double-integrator: p1' = 0, p2' = -p1,
// u* = -p2 = 6 - 12t).
TEST(ReferenceCostate, RegistryEntriesGiveTheClosedForms) {
  for (double t : {0.0, 0.3, 0.5, 1.0}) {
    EXPECT_EQ(FindProblem("hager").reference_costate(t)[0], Hager::OptimalCostate(t));
    const Vec p = FindProblem("double-integrator").reference_costate(t);
    ASSERT_EQ(p.size(), 2);
    EXPECT_EQ(p[0], -12.0);
    EXPECT_NEAR(-p[1], 6.0 - 12.0 * t, 1e-15);
  }
  const Vec p = FindProblem("lqr").reference_costate(2.0);
  EXPECT_EQ((p - Lqr::OptimalCostate(2.0)).norm(), 0.0);
  // Problems whose optimal costate is not known in closed form have none.
  EXPECT_FALSE(FindProblem("double-integrator-bounded").reference_costate);
  EXPECT_FALSE(FindProblem("vanderpol").reference_costate);
}

TEST(ReferenceCostate, RelativeErrorIsMaxOverTheGridOverMaxReference) {
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, 2);
  auto reference = [](double t) { return Vec::Constant(1, 2.0 + 2.0 * t); };  // max 4 at t = 1
  Mat P(1, 3);
  P << 2.0, 3.5, 3.0;  // errors 0, 0.5, 1
  EXPECT_DOUBLE_EQ(RelativeCostateError(P, grid, reference), 0.25);
  EXPECT_TRUE(std::isnan(RelativeCostateError(Mat(), grid, reference)));      // no costates
  EXPECT_TRUE(std::isnan(RelativeCostateError(Mat(2, 3), grid, reference)));  // nx differs
  EXPECT_TRUE(std::isnan(RelativeCostateError(P, grid, [](double) { return Vec::Zero(1); })));
}

// ---- observed orders --------------------------------------------------------------------------

// The costate error of Ipopt + `transcription` on `problem` (default parameters, no terminal
// constraints) at N uniform intervals.
double CostateErrorAt(const std::string& problem,
                      const std::string& transcription,
                      int degree,
                      int N) {
  const ProblemInfo& info = FindProblem(problem);
  const auto ocp = info.make(Parameters(info.parameters), 1);
  SolveRequest r = Request(*ocp, N, TerminalMode::kHard, transcription, {{"tol", "1e-13"}});
  if (degree > 0) r.transcription_options.Set("degree", degree);
  const SolveResult s = SolveWith("ipopt", *ocp, r);
  EXPECT_EQ(s.status, SolveStatus::kConverged) << problem << " " << transcription << " N " << N;
  EXPECT_EQ(s.costate_source, "NLP multipliers (" + transcription + ")");
  return RelativeCostateError(s.costates, s.state_grid, info.reference_costate);
}

// Least-squares slope of -log(error) against log(N): the observed order.
double FittedOrder(const std::vector<int>& Ns, const std::vector<double>& errors) {
  const double n = static_cast<double>(Ns.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (size_t i = 0; i < Ns.size(); ++i) {
    const double x = std::log(Ns[i]), y = -std::log(errors[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// Orders, as measured (Debug build, Ipopt tol 1e-13; fitted over the four N of each case):
//   hermite-simpson: hager 4.00, lqr 4.01 (errors 2.6e-5 ... 6.4e-9 and 4.3e-4 ... 1.0e-7): the
//     method's order 4, for the node costates (cost-to-go gradient of the Lagrangian) and the
//     midpoint ones (from Simpson's multiplier) alike;
//   lgr, K points per interval: hager 1.91 / 2.93, lqr 1.89 / 2.92 for K = 2 / 3. The max over
//     the costate grid is set by the interior points, whose estimate -Lambda_i / w_i (Garg et
//     al.'s lambda_i = Lambda_i / w_i in Ipopt's sign convention) converges at order K; the
//     interval-start costates converge faster (2K - 1, tests/transcriptions/
//     collocation_orders_test.cc). lqr at K = 2 is still pre-asymptotic at N = 10 (1.73 over
//     N = 10-80), hence its finer grids.
struct CostateOrderCase {
  std::string problem, transcription;
  int degree;
  std::vector<int> Ns;
  double order;  // asserted within +-0.3
};

TEST(ReferenceCostate, MultiplierEstimatesConvergeAtTheirOrders) {
  const std::vector<CostateOrderCase> cases = {
      {"hager", "hermite-simpson", 0, {4, 8, 16, 32}, 4.0},
      {"lqr", "hermite-simpson", 0, {10, 20, 40, 80}, 4.0},
      {"hager", "lgr", 2, {4, 8, 16, 32}, 2.0},
      {"lqr", "lgr", 2, {20, 40, 80, 160}, 2.0},
      {"hager", "lgr", 3, {4, 8, 16, 32}, 3.0},
      {"lqr", "lgr", 3, {10, 20, 40, 80}, 3.0},
  };
  for (const CostateOrderCase& c : cases) {
    std::vector<double> errors;
    for (int N : c.Ns) errors.push_back(CostateErrorAt(c.problem, c.transcription, c.degree, N));
    const double order = FittedOrder(c.Ns, errors);
    std::printf("%-6s %-16s K=%d errors", c.problem.c_str(), c.transcription.c_str(), c.degree);
    for (double e : errors) std::printf(" %.3e", e);
    std::printf("  fitted order %.2f\n", order);
    EXPECT_NEAR(order, c.order, 0.3) << c.problem << " " << c.transcription << " K " << c.degree;
  }
}

}  // namespace
}  // namespace ocpb
