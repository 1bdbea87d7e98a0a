// Accuracy of the transcriptions without an NLP solver: the analytic optimum of the double
// integrator in each NLP, and the exact discrete optima (Newton-KKT on the equality-constrained
// QPs) of the double integrator and of a scalar LQ problem with a non-polynomial solution,
// against the known optima: objective, states and costates converge at each scheme's order.
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "problems/registry.h"
#include "tests/transcriptions/nlp_test_util.h"
#include "tests/transcriptions/test_ocps.h"
#include "transcriptions/collocation_nlp.h"

namespace ocpb {
namespace {

struct Scheme {
  std::string name;
  int degree = 3;
  std::string Label() const { return name == "lgr" ? "lgr" + std::to_string(degree) : name; }
};

std::unique_ptr<TranscribedNlp> Make(const Scheme& s, const Ocp& ocp, int N, TerminalMode mode) {
  TranscriptionOptions options;
  options.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  options.terminal = mode;
  options.degree = s.degree;
  return testing::MakeScheme(s.name)->Transcribe(ocp, options);
}

double Order(double coarse, double fine) { return std::log2(coarse / fine); }

// x1* = -1 + 3t^2 - 2t^3, x2* = 6t - 6t^2, u* = 6 - 12t, p* = (-12, 12t - 6) (H = p^T f + L:
// p2 = -u*, p1 = -p2'); every state and control block of the NLP set from them.
Vec DoubleIntegratorOptimum(const CollocationNlp& nlp) {
  Vec z(nlp.num_variables());
  for (const auto& s : nlp.layout().states) {
    z[s.offset] = -1.0 + 3.0 * s.t * s.t - 2.0 * s.t * s.t * s.t;
    z[s.offset + 1] = 6.0 * s.t - 6.0 * s.t * s.t;
  }
  for (const auto& c : nlp.layout().controls) z[c.offset] = 6.0 - 12.0 * c.t;
  return z;
}

struct AnalyticPointErrors {
  double objective;  // |J_nlp(z*) - 6|
  double defect;     // max |g(z*)| (hard mode: defects and psi)
};

AnalyticPointErrors AtAnalyticOptimum(const Scheme& s, int N) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  const auto nlp = Make(s, *ocp, N, TerminalMode::kHard);
  const Vec z = DoubleIntegratorOptimum(dynamic_cast<const CollocationNlp&>(*nlp));
  double f;
  EXPECT_TRUE(nlp->Objective(z, &f));
  Vec g(nlp->num_constraints());
  EXPECT_TRUE(nlp->Constraints(z, g));
  return {std::abs(f - 6.0), g.cwiseAbs().maxCoeff()};
}

// Euler: the rectangle rule on u*^2/2 = (6 - 12t)^2/2 loses its first-order term
// (h/2 (g(0) - g(1)) = 0, the integrand is symmetric), so the objective error is O(h^2); the local
// defect x_{k+1} - x_k - h f is O(h^2). Trapezoid: O(h^2) objective, O(h^3) local defect.
TEST(AnalyticOptimum, EulerAndTrapezoidConvergeAtTheirOrders) {
  const struct {
    Scheme scheme;
    double objective_order, defect_order;
  } expectations[] = {{{"euler"}, 2.0, 2.0}, {{"trapezoid"}, 2.0, 3.0}};
  for (const auto& e : expectations) {
    const AnalyticPointErrors c = AtAnalyticOptimum(e.scheme, 16),
                              f = AtAnalyticOptimum(e.scheme, 32);
    EXPECT_NEAR(Order(c.objective, f.objective), e.objective_order, 0.05) << e.scheme.Label();
    EXPECT_NEAR(Order(c.defect, f.defect), e.defect_order, 0.05) << e.scheme.Label();
  }
}

// Hermite-Simpson and LGR with K >= 3 contain the cubic state and linear control exactly:
// the analytic optimum satisfies their defects and their quadrature gives J = 6 to roundoff
// (consistent with order >= 4; the order itself shows on the LQ problem below). LGR with K = 2
// integrates u^2 exactly but its quadratic state polynomial leaves an O(h^3) defect.
TEST(AnalyticOptimum, HermiteSimpsonAndLgrAreExactOnThePolynomialSolution) {
  for (const Scheme& s : {Scheme{"hermite-simpson"}, Scheme{"lgr", 3}, Scheme{"lgr", 5}}) {
    for (int N : {3, 10}) {
      const AnalyticPointErrors e = AtAnalyticOptimum(s, N);
      EXPECT_LT(e.objective, 1e-13) << s.Label() << " N " << N;
      EXPECT_LT(e.defect, 1e-13) << s.Label() << " N " << N;
    }
  }
  const AnalyticPointErrors c = AtAnalyticOptimum({"lgr", 2}, 16),
                            f = AtAnalyticOptimum({"lgr", 2}, 32);
  EXPECT_LT(c.objective, 1e-13);
  EXPECT_NEAR(Order(c.defect, f.defect), 3.0, 0.05);
}

struct DiscreteOptimum {
  double J;
  Mat X, P;
  TimeGrid grid;
};

DiscreteOptimum SolveExactly(const Scheme& s, const Ocp& ocp, int N, TerminalMode mode) {
  const auto nlp = Make(s, ocp, N, mode);
  const testing::KktSolution sol = testing::SolveEqualityKkt(*nlp, nlp->StartingPoint());
  EXPECT_TRUE(sol.converged) << s.Label() << " N " << N;
  EXPECT_LT(sol.constraint_norm, 1e-10);
  DiscreteOptimum out;
  EXPECT_TRUE(nlp->Objective(sol.z, &out.J));
  out.X = nlp->States(sol.z);
  out.P = nlp->Costates(sol.z, sol.lambda);
  out.grid = nlp->state_grid();
  return out;
}

// Max errors of the LQ discrete optimum against x*(t), p*(t): over the interval-start blocks
// (grid nodes) and over the interior blocks.
struct LqErrors {
  double J, x_nodes, p_nodes, p_interior;
};

LqErrors LqErrorsAt(const Scheme& s, int N) {
  const testing::ScalarLqOcp lq;
  const DiscreteOptimum d = SolveExactly(s, lq, N, TerminalMode::kPenalty);
  LqErrors e{std::abs(d.J - testing::ScalarLqOcp::OptimalCost()), 0.0, 0.0, 0.0};
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, N);
  for (int j = 0; j < d.grid.size(); ++j) {
    const double t = d.grid.t(j);
    const bool node = std::abs(t - grid.t(grid.Locate(t))) < 1e-14 || j == d.grid.size() - 1;
    const double ex = std::abs(d.X(0, j) - testing::ScalarLqOcp::State(t));
    const double ep = std::abs(d.P(0, j) - testing::ScalarLqOcp::Costate(t));
    if (node) {
      e.x_nodes = std::max(e.x_nodes, ex);
      e.p_nodes = std::max(e.p_nodes, ep);
    } else {
      e.p_interior = std::max(e.p_interior, ep);
    }
  }
  return e;
}

// The discrete optima of the scalar LQ problem (J* = tanh(1)/2) converge at each scheme's order:
// Euler 1, trapezoid 2, Hermite-Simpson 4 (costates at nodes and midpoints too), LGR 2K - 1 in J,
// nodal states and nodal costates, K at the interior LGR points (the -lambda/w estimate).
TEST(DiscreteOptimum, ScalarLqConvergesAtEachSchemesOrder) {
  const struct {
    Scheme scheme;
    int N;
    double order_J, order_x, order_p, order_p_interior;  // < 0: no interior blocks
  } expectations[] = {
      {{"euler"}, 16, 1.0, 1.0, 1.0, -1.0},
      {{"trapezoid"}, 16, 2.0, 2.0, 2.0, -1.0},
      {{"hermite-simpson"}, 8, 4.0, 4.0, 4.0, 4.0},
      {{"lgr", 2}, 8, 3.0, 3.0, 3.0, 2.0},
      {{"lgr", 3}, 4, 5.0, 5.0, 5.0, 3.0},
      {{"lgr", 4}, 4, 7.0, 7.0, 7.0, 4.0},
  };
  for (const auto& e : expectations) {
    const LqErrors c = LqErrorsAt(e.scheme, e.N), f = LqErrorsAt(e.scheme, 2 * e.N);
    const std::string label = e.scheme.Label() + " N " + std::to_string(e.N);
    std::printf(
        "%-16s N=%3d  |J-J*| %.2e -> %.2e  x %.2e -> %.2e  p %.2e -> %.2e  p_int %.2e -> %.2e\n",
        e.scheme.Label().c_str(),
        e.N,
        c.J,
        f.J,
        c.x_nodes,
        f.x_nodes,
        c.p_nodes,
        f.p_nodes,
        c.p_interior,
        f.p_interior);
    EXPECT_NEAR(Order(c.J, f.J), e.order_J, 0.25) << label;
    EXPECT_NEAR(Order(c.x_nodes, f.x_nodes), e.order_x, 0.25) << label;
    EXPECT_NEAR(Order(c.p_nodes, f.p_nodes), e.order_p, 0.25) << label;
    if (e.order_p_interior > 0) {
      EXPECT_NEAR(Order(c.p_interior, f.p_interior), e.order_p_interior, 0.25) << label;
    }
  }
}

// The exact discrete optimum of the hard-constrained double integrator: Euler and trapezoid
// converge to J* = 6 at order 2 (see above for Euler's symmetric integrand), Hermite-Simpson and
// LGR (K >= 2) hit it to roundoff; costates against p*(t) = (-12, 12t - 6).
TEST(DiscreteOptimum, DoubleIntegratorObjectiveAndCostates) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  auto costate_error = [](const DiscreteOptimum& d) {
    double worst = 0.0;
    for (int j = 0; j < d.grid.size(); ++j) {
      const double t = d.grid.t(j);
      worst = std::max({worst, std::abs(d.P(0, j) + 12.0), std::abs(d.P(1, j) - (12.0 * t - 6.0))});
    }
    return worst;
  };
  for (const Scheme& s : {Scheme{"euler"}, Scheme{"trapezoid"}}) {
    const DiscreteOptimum c = SolveExactly(s, *ocp, 16, TerminalMode::kHard);
    const DiscreteOptimum f = SolveExactly(s, *ocp, 32, TerminalMode::kHard);
    EXPECT_NEAR(Order(std::abs(c.J - 6.0), std::abs(f.J - 6.0)), 2.0, 0.1) << s.Label();
    EXPECT_LT(costate_error(f), costate_error(c)) << s.Label();
    EXPECT_LT(costate_error(f), 1.0) << s.Label();
  }
  for (const Scheme& s : {Scheme{"hermite-simpson"}, Scheme{"lgr", 2}, Scheme{"lgr", 3}}) {
    const DiscreteOptimum d = SolveExactly(s, *ocp, 7, TerminalMode::kHard);
    EXPECT_NEAR(d.J, 6.0, 1e-12) << s.Label();
    EXPECT_LT(costate_error(d), 1e-9) << s.Label() << "\n" << d.P;
  }
}

}  // namespace
}  // namespace ocpb
