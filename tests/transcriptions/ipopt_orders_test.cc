// The acceptance test of the direct transcriptions: Ipopt (through the solver registry) on each
// scheme, on the double integrator (J* = 6) and on a nonlinear problem with a known optimum
// (BilinearTestOcp), hard terminal constraints. The error of the NLP optimum against the known
// optimum shrinks at each scheme's order as N doubles, and the multiplier costates converge.
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "problems/registry.h"
#include "solvers/registry.h"
#include "tests/transcriptions/test_ocps.h"

namespace ocpb {
namespace {

struct IpoptRun {
  double error;          // |objective - J*|
  double costate_error;  // max over state_grid of |p_component - p*|
};

IpoptRun SolveWithIpopt(const Ocp& ocp,
                        const std::string& transcription,
                        int degree,
                        int N,
                        double J_star,
                        const std::function<double(double)>& p_star,
                        int component = 0) {
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  request.terminal = TerminalMode::kHard;
  request.transcription = transcription;
  if (transcription == std::string("lgr")) request.transcription_options.Set("degree", degree);
  request.options = {{"tol", "1e-12"}};
  const SolveResult result = FindSolver("ipopt").make()->Solve(ocp, request);
  EXPECT_EQ(result.status, SolveStatus::kConverged)
      << transcription << " N " << N << ": " << result.solver_status << " " << result.message;
  IpoptRun run{std::abs(result.objective - J_star), 0.0};
  EXPECT_EQ(result.costates.cols(), result.state_grid.size()) << transcription;
  for (int j = 0; j < result.costates.cols(); ++j) {
    run.costate_error =
        std::max(run.costate_error,
                 std::abs(result.costates(component, j) - p_star(result.state_grid.t(j))));
  }
  return run;
}

double ObservedOrder(double coarse, double fine) { return std::log2(coarse / fine); }

struct Expectation {
  std::string transcription;
  int degree;
  int N;         // orders from N to 2N
  double order;  // of the objective error
};

// BilinearTestOcp: x' = x u/2, L = u^2/2 + x^2, x(1) fixed; J* = 4(cot d - cot(1 + d)) - 2.
TEST(IpoptOrders, NonlinearProblemConvergesAtEachSchemesOrder) {
  const testing::BilinearTestOcp ocp;
  const double J_star = testing::BilinearTestOcp::OptimalCost();
  const Expectation expectations[] = {
      {"euler", 3, 32, 1.0},
      {"trapezoid", 3, 16, 2.0},
      {"hermite-simpson", 3, 8, 4.0},
      {"lgr", 2, 8, 3.0},
      {"lgr", 3, 2, 5.0},
  };
  for (const Expectation& e : expectations) {
    const IpoptRun c = SolveWithIpopt(
        ocp, e.transcription, e.degree, e.N, J_star, testing::BilinearTestOcp::Costate);
    const IpoptRun f = SolveWithIpopt(
        ocp, e.transcription, e.degree, 2 * e.N, J_star, testing::BilinearTestOcp::Costate);
    std::printf("%-16s K=%d N=%2d->%2d |J-J*| %.3e -> %.3e (order %.2f)  |p-p*| %.2e -> %.2e\n",
                e.transcription.c_str(),
                e.degree,
                e.N,
                2 * e.N,
                c.error,
                f.error,
                ObservedOrder(c.error, f.error),
                c.costate_error,
                f.costate_error);
    EXPECT_GT(ObservedOrder(c.error, f.error), e.order - 0.3)
        << e.transcription << " K " << e.degree;
    EXPECT_LT(ObservedOrder(c.error, f.error), e.order + 0.7)
        << e.transcription << " K " << e.degree;
    EXPECT_LT(f.costate_error, c.costate_error) << e.transcription << " K " << e.degree;
  }
}

// Double integrator, J* = 6, p* = (-12, 12t - 6). Euler and trapezoid converge at order 2 (the
// rectangle rule's first-order term vanishes on the symmetric u*^2); Hermite-Simpson and LGR
// contain the polynomial optimum and hit it to Ipopt's accuracy.
TEST(IpoptOrders, DoubleIntegrator) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const auto p2 = [](double t) { return 12.0 * t - 6.0; };
  for (const std::string t : {"euler", "trapezoid"}) {
    const IpoptRun c = SolveWithIpopt(*ocp, t, 3, 16, 6.0, p2, 1);
    const IpoptRun f = SolveWithIpopt(*ocp, t, 3, 32, 6.0, p2, 1);
    std::printf("%-16s N=16->32 |J-6| %.3e -> %.3e (order %.2f)\n",
                t.c_str(),
                c.error,
                f.error,
                ObservedOrder(c.error, f.error));
    EXPECT_NEAR(ObservedOrder(c.error, f.error), 2.0, 0.15) << t;
    EXPECT_LT(f.costate_error, c.costate_error) << t;
  }
  for (const std::string t : {"hermite-simpson", "lgr"}) {
    const IpoptRun r = SolveWithIpopt(*ocp, t, 3, 5, 6.0, p2, 1);
    EXPECT_LT(r.error, 1e-8) << t;
    EXPECT_LT(r.costate_error, 1e-6) << t;
  }
}

// Every registered direct transcription is found by name and builds the scheme it names.
TEST(IpoptOrders, TranscriptionsAreRegistered) {
  for (const std::string name : {"euler", "trapezoid", "hermite-simpson", "lgr"}) {
    EXPECT_EQ(FindTranscription(name).make()->name(), name);
  }
}

}  // namespace
}  // namespace ocpb
