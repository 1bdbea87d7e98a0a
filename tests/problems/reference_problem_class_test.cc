// The widened problem class (Ocp's class comment): state bounds declared as bounds and a partly
// free initial state with an initial cost. Checked on their reference problems
// ("bryson-denham-bounds", "free-start") against the analytic optima, through the registry as a
// user solves them; the validation of the new setters; the evaluator and the judge from the
// chosen x(t0); and a clear not_applicable from every method that does not take them.
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/autodiff_ocp.h"
#include "core/derivative_check.h"
#include "core/evaluator.h"
#include "problems/reference/bryson_denham.h"
#include "problems/reference/coupled_ends.h"
#include "problems/reference/free_start.h"
#include "problems/reference/free_time_double_integrator.h"
#include "problems/registry.h"
#include "solvers/forwarding_ocp.h"
#include "solvers/judge.h"
#include "tests/problems/reference_test_support.h"

namespace ocpb {
namespace {

using reference_testing::RelativeError;
using reference_testing::Request;
using reference_testing::SolveWith;

constexpr double kInf = std::numeric_limits<double>::infinity();

// A two-state problem with nonlinear boundary constraints coupling both ends (fixed x0), for
// the AD's boundary derivatives and the refusal of methods that do not take them.
class Coupled final : public AutoDiffOcp<Coupled, 2, 1> {
 public:
  Coupled() {
    SetHorizon(0.0, 1.0);
    SetInitialState(Eigen::Vector2d(0.3, -0.2));
    SetBoundaryConstraints(Eigen::Vector2d(0.0, -kInf), Eigen::Vector2d(0.0, 1.0));
  }
  std::string name() const override { return "coupled"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
  template <class T>
  void EvalBoundaryConstraints(const VecT<T, 2>& x0,
                               const VecT<T, 2>& xf,
                               VecT<T, Eigen::Dynamic>* b) const {
    (*b)[0] = x0[0] * xf[1] - 0.1;
    (*b)[1] = sin(x0[1]) + xf[0] * xf[0] * xf[1];
  }
  void Declare(const Vec& lo, const Vec& hi) { SetBoundaryConstraints(lo, hi); }
};

// A two-state problem for the setters' checks.
class Tiny final : public AutoDiffOcp<Tiny, 2, 1> {
 public:
  std::string name() const override { return "tiny"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1];
    (*f)[1] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
  void Bounds(const Vec& lo, const Vec& hi) { SetStateBounds(lo, hi); }
  void Start(const Vec& x0) { SetInitialState(x0); }
  void StartBounds(const Vec& lo, const Vec& hi) { SetInitialStateBounds(lo, hi); }
  void Params(const Vec& lo, const Vec& hi, const Vec& guess) {
    SetStaticParameters(lo, hi, guess);
  }
};

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(ProblemClass, SettersRejectInconsistentBoundsWithOneLineNamingTheRule) {
  Tiny p;
  EXPECT_NE(ErrorOf([&] { p.Bounds(Vec::Zero(3), Vec::Ones(3)); }).find("size nx = 2"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              p.Bounds(Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 1));
            }).find("component 0 needs lower <= upper"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              p.Bounds(Eigen::Vector2d(NAN, 0), Eigen::Vector2d(1, 1));
            }).find("component 0 is NaN"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              p.Bounds(Eigen::Vector2d(kInf, 0), Eigen::Vector2d(kInf, 1));
            }).find("lower < +inf"),
            std::string::npos);
  EXPECT_FALSE(p.state_bounds().has_value());  // nothing half-set
  // x0 must lie within the initial-state bounds, whichever is set first.
  EXPECT_NE(
      ErrorOf([&] { p.StartBounds(Eigen::Vector2d(1, 0), Eigen::Vector2d(2, 0)); }).find("x0"),
      std::string::npos);
  EXPECT_FALSE(p.HasFreeInitialState());
  p.StartBounds(Eigen::Vector2d(-1, 0), Eigen::Vector2d(1, 0));
  EXPECT_TRUE(p.HasFreeInitialState());
  EXPECT_NE(ErrorOf([&] { p.Start(Eigen::Vector2d(3, 0)); }).find("initial-state bounds"),
            std::string::npos);
  EXPECT_EQ(p.x0(), Vec::Zero(2));
  EXPECT_EQ(p.InitialNodeBounds().lower, Eigen::Vector2d(-1, 0));
  // Bounds that fix every component leave x(t0) fixed.
  Tiny fixed;
  fixed.StartBounds(Vec::Zero(2), Vec::Zero(2));
  EXPECT_FALSE(fixed.HasFreeInitialState());
  // Static parameters: sizes, ranges, and the order of the setters.
  Tiny q;
  EXPECT_NE(ErrorOf([&] { q.Params(Vec::Zero(3), Vec::Ones(3), Vec::Zero(3)); }).find("np <= nx"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              q.Params(Vec::Zero(1), Vec::Ones(1), Vec::Constant(1, 2.0));
            }).find("lower <= guess <= upper"),
            std::string::npos);
  EXPECT_EQ(q.num_static_parameters(), 0);
  q.Params(Vec::Zero(1), Vec::Ones(1), Vec::Constant(1, 0.5));
  EXPECT_EQ(q.num_static_parameters(), 1);
  EXPECT_TRUE(q.HasFreeInitialState());
  EXPECT_EQ(q.x0()[1], 0.5);
  EXPECT_NE(ErrorOf([&] { q.Params(Vec::Zero(1), Vec::Ones(1), Vec::Zero(1)); }).find("twice"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { q.Start(Vec::Zero(2)); }).find("before SetStaticParameters"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              q.StartBounds(-Vec::Ones(2), Vec::Ones(2));
            }).find("before SetStaticParameters"),
            std::string::npos);
  EXPECT_EQ(q.x0()[1], 0.5);
}

TEST(ProblemClass, VectorBoundsViolationIsTheDistanceOutside) {
  const VectorBounds b{Eigen::Vector2d(-1, -kInf), Eigen::Vector2d(1, 2)};
  EXPECT_EQ(b.Violation(Eigen::Vector2d(0, -1e300)), 0.0);
  EXPECT_EQ(b.Violation(Eigen::Vector2d(-1.5, 0)), 0.5);
  EXPECT_EQ(b.Violation(Eigen::Vector2d(0, 2.25)), 0.25);
}

// phi0 by forward-mode AD against central differences of InitialCost.
TEST(ProblemClass, InitialCostDerivativesMatchFiniteDifferences) {
  const auto ocp = MakeProblem("free-start", {"w=1.7", "a=0.3"}, 0);
  ASSERT_TRUE(ocp->HasInitialCost());
  const Vec x0 = Eigen::Vector2d(0.4, -0.2);
  double phi0 = 0.0;
  Vec grad(2);
  ocp->InitialCostGradient(x0, &phi0, grad);
  EXPECT_DOUBLE_EQ(phi0, ocp->InitialCost(x0));
  const Mat fd =
      CentralJacobian([&](const Vec& x) { return Vec::Constant(1, ocp->InitialCost(x)); }, x0);
  EXPECT_LT((grad.transpose() - fd).cwiseAbs().maxCoeff(), 1e-8);
  Mat hess(2, 2);
  ocp->InitialCostHessian(x0, 0.5, hess);
  const Mat fd_hess = CentralJacobian(
      [&](const Vec& x) {
        double v = 0.0;
        Vec g(2);
        ocp->InitialCostGradient(x, &v, g);
        return Vec(0.5 * g);
      },
      x0);
  EXPECT_LT((hess - fd_hess).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_NEAR(hess(0, 0), 0.5 * 1.7, 1e-14);
  // A problem without one: 0, and HasInitialCost false.
  const auto plain = MakeProblem("double-integrator", {}, 0);
  EXPECT_FALSE(plain->HasInitialCost());
  EXPECT_EQ(plain->InitialCost(Eigen::Vector2d(1, 2)), 0.0);
}

TEST(ProblemClass, BoundaryConstraintDerivativesMatchFiniteDifferences) {
  Coupled p;
  ASSERT_EQ(p.num_boundary(), 2);
  const Vec x0 = Eigen::Vector2d(0.4, -0.7), xf = Eigen::Vector2d(1.3, 0.6);
  Vec b(2);
  Mat b0(2, 2), bf(2, 2);
  p.BoundaryConstraintsJacobian(x0, xf, b, b0, bf);
  Vec direct(2);
  p.BoundaryConstraints(x0, xf, direct);
  EXPECT_EQ(b, direct);
  const Vec ends = (Vec(4) << x0, xf).finished();
  const auto value = [&](const Vec& e) {
    Vec out(2);
    p.BoundaryConstraints(e.head(2), e.tail(2), out);
    return out;
  };
  const Mat fd = CentralJacobian(value, ends);
  Mat jac(2, 4);
  jac << b0, bf;
  EXPECT_LT((jac - fd).cwiseAbs().maxCoeff(), 1e-8);
  const Vec mu = Eigen::Vector2d(0.7, -1.3);
  Mat hess(4, 4);
  p.BoundaryHessian(x0, xf, mu, hess);
  const Mat fd_hess = CentralJacobian(
      [&](const Vec& e) {
        Vec bb(2);
        Mat j0(2, 2), jf(2, 2);
        p.BoundaryConstraintsJacobian(e.head(2), e.tail(2), bb, j0, jf);
        Mat j(2, 4);
        j << j0, jf;
        return Vec(j.transpose() * mu);
      },
      ends);
  EXPECT_LT((hess - fd_hess).cwiseAbs().maxCoeff(), 1e-7);
  EXPECT_LT((hess - hess.transpose()).cwiseAbs().maxCoeff(), 1e-15);
  // Declaration errors: one line naming the row and the rule.
  EXPECT_NE(ErrorOf([&] { p.Declare(Vec::Zero(2), Vec::Zero(3)); }).find("same size"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              p.Declare(Eigen::Vector2d(0, 2), Eigen::Vector2d(1, 1));
            }).find("row 1 needs lower <= upper"),
            std::string::npos);
  EXPECT_EQ(p.num_boundary(), 2);
}

// coupled-ends: every collocation scheme reaches the analytic optimum with the boundary
// constraint active, x(0) chosen, and the costate p = -u (its end closed by the constraint's
// multiplier); the judge measures the boundary residual.
TEST(ProblemClass, CoupledEndsReachesTheAnalyticOptimumWithEveryCollocationScheme) {
  const auto ocp = MakeProblem("coupled-ends", {}, 0);
  const auto& problem = dynamic_cast<const CoupledEnds&>(*ocp);
  ASSERT_NEAR(problem.OptimalCost(), 1.53, 1e-14);
  for (const std::string scheme : {"euler", "trapezoid", "hermite-simpson", "lgr"}) {
    for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
      SCOPED_TRACE(scheme + " " + ToString(mode));
      const SolveRequest request = Request(*ocp, 20, mode, scheme);
      const SolveResult r = SolveWith("ipopt", *ocp, request);
      ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
      ASSERT_EQ(r.initial_state.size(), 1);
      EXPECT_NEAR(r.initial_state[0], 1.1, 1e-7);
      EXPECT_LT(RelativeError(r.objective, 1.53), 1e-8);
      const Judgement j = JudgeResult(*ocp, request, r);
      EXPECT_LT(RelativeError(j.fine.J, 1.53), 1e-8);
      ASSERT_EQ(j.fine.boundary_residual.size(), 1);
      EXPECT_NEAR(j.fine.boundary_residual[0], 0.8, 1e-7);
      EXPECT_LT(j.fine.boundary_violation, 1e-7);
      EXPECT_FALSE(j.HasWarning("infeasible"));
      for (int k = 0; k < r.costates.cols(); ++k) EXPECT_NEAR(r.costates(0, k), -0.8, 1e-6);
    }
  }
  // NLopt (SLSQP) takes the same NLP rows.
  const SolveRequest request = Request(*ocp, 10, TerminalMode::kHard, "hermite-simpson");
  const SolveResult n = SolveWith("nlopt", *ocp, request);
  ASSERT_EQ(n.status, SolveStatus::kConverged) << n.message;
  EXPECT_LT(RelativeError(n.objective, 1.53), 1e-6);
}

// A problem whose "parameter" drifts (nonzero dynamics), and bad declarations.
class DriftingParameter final : public AutoDiffOcp<DriftingParameter, 2, 1> {
 public:
  DriftingParameter() {
    SetHorizon(0.0, 1.0);
    SetStaticParameters(Vec::Constant(1, -1.0), Vec::Constant(1, 1.0), Vec::Constant(1, 0.5));
  }
  std::string name() const override { return "drifting"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1] * u[0];
    (*f)[1] = 0.25 * u[0];  // wrong: a static parameter must not move
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
};

// double-integrator-time-parameter: T as a static parameter reaches the free-time optimum
// (T* = 18^(1/4), J* = 4 T*/3) with Hermite-Simpson and LGR (exact for this u*), and the record's
// x(t0) carries T; a parameter with dynamics is refused before solving, with the component.
TEST(ProblemClass, StaticParameterReachesTheFreeTimeOptimum) {
  const auto ocp = MakeProblem("double-integrator-time-parameter", {}, 0);
  EXPECT_EQ(ocp->num_static_parameters(), 1);
  EXPECT_EQ(ocp->x0()[2], 1.0);  // the guess
  const double T = FreeTimeDoubleIntegrator::OptimalTime(),
               J = FreeTimeDoubleIntegrator::OptimalCost();
  for (const std::string scheme : {"hermite-simpson", "lgr"}) {
    SCOPED_TRACE(scheme);
    const SolveRequest request = Request(*ocp, 20, TerminalMode::kHard, scheme);
    const SolveResult r = SolveWith("ipopt", *ocp, request);
    ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
    ASSERT_EQ(r.initial_state.size(), 3);
    EXPECT_NEAR(r.initial_state[2], T, 1e-7);
    EXPECT_EQ(r.initial_state[0], -1.0);
    // Constant along the solution: the defects carry it.
    EXPECT_LT((r.states.row(2).array() - r.initial_state[2]).abs().maxCoeff(), 1e-9);
    EXPECT_LT(RelativeError(r.objective, J), 1e-9);
    const Judgement j = JudgeResult(*ocp, request, r);
    EXPECT_LT(RelativeError(j.fine.Jbar, J), 1e-8);
    EXPECT_LT(j.fine.terminal_violation, 1e-8);
  }
  const SolveResult t =
      SolveWith("ipopt", *ocp, Request(*ocp, 100, TerminalMode::kHard, "trapezoid"));
  ASSERT_EQ(t.status, SolveStatus::kConverged);
  EXPECT_NEAR(t.initial_state[2], T, 1e-3);  // second order in h

  const DriftingParameter drifting;
  try {
    SolveWith("ipopt", drifting, Request(drifting, 10, TerminalMode::kPenalty, "trapezoid"));
    ADD_FAILURE() << "a parameter with dynamics was solved";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("static parameter 0 (state component 1)"),
              std::string::npos)
        << e.what();
  }
  const SolveResult refused =
      SolveWith("hamiltonian", *ocp, Request(*ocp, 10, TerminalMode::kPenalty));
  EXPECT_EQ(refused.status, SolveStatus::kNotApplicable);
  EXPECT_NE(refused.message.find("static parameters"), std::string::npos) << refused.message;
}

// A wrapper keeps every feature of the problem it wraps.
TEST(ProblemClass, ForwardingOcpKeepsTheFeatures) {
  for (const std::string name :
       {"double-integrator-time-parameter", "coupled-ends", "bryson-denham-bounds", "free-start"}) {
    SCOPED_TRACE(name);
    const auto inner = MakeProblem(name, {}, 0);
    const ForwardingOcp outer(*inner);
    EXPECT_EQ(outer.num_static_parameters(), inner->num_static_parameters());
    EXPECT_EQ(outer.HasFreeInitialState(), inner->HasFreeInitialState());
    EXPECT_EQ(outer.state_bounds().has_value(), inner->state_bounds().has_value());
    EXPECT_EQ(outer.num_boundary(), inner->num_boundary());
    EXPECT_EQ(outer.HasInitialCost(), inner->HasInitialCost());
    EXPECT_EQ(outer.x0(), inner->x0());
    EXPECT_EQ(outer.InitialNodeBounds().lower, inner->InitialNodeBounds().lower);
    EXPECT_EQ(outer.InitialNodeBounds().upper, inner->InitialNodeBounds().upper);
  }
}

// The evaluator from a chosen x(t0): phi0 in J, and x(t0) judged against its bounds.
TEST(ProblemClass, EvaluatorStartsFromTheGivenInitialStateAndAddsTheInitialCost) {
  const auto ocp = MakeProblem("free-start", {}, 0);
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, 10);
  const auto u = ControlTrajectory::Constant(grid, Vec::Constant(1, 0.5));
  const Evaluation at_bound = Evaluate(*ocp, u, grid, Integrator::kRk4, Eigen::Vector2d(0.5, 0));
  EXPECT_DOUBLE_EQ(at_bound.initial_cost, 0.5 * 0.25);
  EXPECT_DOUBLE_EQ(at_bound.X(0, 10), 1.0);
  // x1(1) = 1, energy 1/8, terminal 2 (1 - 2)^2 = 2.
  EXPECT_NEAR(at_bound.Jbar, 0.125 + 0.125 + 2.0, 1e-12);
  EXPECT_EQ(at_bound.state_bound_violation, 0.0);
  const Evaluation outside = Evaluate(*ocp, u, grid, Integrator::kRk4, Eigen::Vector2d(0.75, 0));
  EXPECT_DOUBLE_EQ(outside.state_bound_violation, 0.25);
  EXPECT_THROW(Evaluate(*ocp, u, grid, Integrator::kRk4, Vec::Zero(3)), std::invalid_argument);
}

// free-start: every collocation scheme with Ipopt reaches the analytic optimum (u is constant,
// which every scheme integrates exactly) with x1(0) at its active bound 0.5, the result carries
// the chosen x(t0), and the judge starts from it.
TEST(ProblemClass, FreeStartReachesTheAnalyticOptimumWithEveryCollocationScheme) {
  const auto ocp = MakeProblem("free-start", {}, 0);
  const FreeStart::Optimum o = dynamic_cast<const FreeStart&>(*ocp).AnalyticOptimum();
  ASSERT_DOUBLE_EQ(o.x1_start, 0.5);
  ASSERT_NEAR(o.J, 1.025, 1e-15);
  for (const std::string scheme : {"euler", "trapezoid", "hermite-simpson", "lgr"}) {
    SCOPED_TRACE(scheme);
    const SolveRequest request = Request(*ocp, 20, TerminalMode::kPenalty, scheme);
    const SolveResult r = SolveWith("ipopt", *ocp, request);
    ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
    ASSERT_EQ(r.initial_state.size(), 2);
    EXPECT_NEAR(r.initial_state[0], 0.5, 1e-7);
    EXPECT_EQ(r.initial_state[1], 0.0);  // the fixed component stays fixed
    EXPECT_LT(RelativeError(r.objective, o.J), 1e-8);
    const Judgement j = JudgeResult(*ocp, request, r);
    ASSERT_TRUE(j.judged);
    EXPECT_LT(RelativeError(j.fine.J, o.J), 1e-8);
    EXPECT_NEAR(j.fine.X(0, 0), 0.5, 1e-7);
    EXPECT_LT(j.fine.state_bound_violation, 1e-7);
    EXPECT_FALSE(j.HasWarning("infeasible"));
    // Costates p1 = q (x1(T)* - b), p2 = 1 from the NLP multipliers (at t0 the cost-to-go
    // gradient, which the bound multiplier closes).
    ASSERT_EQ(r.costates.rows(), 2);
    const Vec p = dynamic_cast<const FreeStart&>(*ocp).OptimalCostate();
    for (int k = 0; k < r.costates.cols(); ++k) {
      EXPECT_NEAR(r.costates(0, k), p[0], 1e-6) << "node " << k;
      EXPECT_NEAR(r.costates(1, k), p[1], 1e-6) << "node " << k;
    }
  }
  // With wide bounds the unconstrained start 8/9 is chosen.
  const auto wide = MakeProblem("free-start", {"hi=2"}, 0);
  const SolveResult r =
      SolveWith("ipopt", *wide, Request(*wide, 20, TerminalMode::kPenalty, "trapezoid"));
  ASSERT_EQ(r.status, SolveStatus::kConverged);
  EXPECT_NEAR(r.initial_state[0], 8.0 / 9.0, 1e-7);
  EXPECT_LT(RelativeError(r.objective, dynamic_cast<const FreeStart&>(*wide).AnalyticOptimum().J),
            1e-8);
}

// bryson-denham-bounds: the bound is a variable bound (no constraint row), the states stay
// within it, and Hermite-Simpson and LGR reach J* = 4 as the path-row form does.
TEST(ProblemClass, StateBoundsAreVariableBoundsAndReachTheBrysonDenhamOptimum) {
  const auto bounds = MakeProblem("bryson-denham-bounds", {}, 0);
  const auto rows = MakeProblem("bryson-denham", {}, 0);
  EXPECT_EQ(bounds->num_path(), 0);
  ASSERT_TRUE(bounds->state_bounds().has_value());
  for (const std::string scheme : {"trapezoid", "hermite-simpson"}) {
    SCOPED_TRACE(scheme);
    const SolveRequest request = Request(*bounds, 150, TerminalMode::kHard, scheme);
    const SolveResult b = SolveWith("ipopt", *bounds, request);
    const SolveResult r = SolveWith("ipopt", *rows, request);
    ASSERT_EQ(b.status, SolveStatus::kConverged) << b.message;
    ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
    // Fewer constraint rows: N + 1 path rows gone (Hermite-Simpson also evaluates c at its
    // midpoints: more).
    EXPECT_LT(b.solver_stats.at("nlp_constraints"), r.solver_stats.at("nlp_constraints"));
    EXPECT_EQ(b.solver_stats.at("nlp_variables"), r.solver_stats.at("nlp_variables"));
    EXPECT_LT(b.states.row(0).maxCoeff(), BrysonDenham::kDefaultBound + 1e-8);
    EXPECT_LT(RelativeError(b.objective, BrysonDenham::OptimalCost()), 1e-3);
    const Judgement j = JudgeResult(*bounds, request, b);
    EXPECT_LT(RelativeError(j.fine.Jbar, BrysonDenham::OptimalCost()), 2e-3);
    EXPECT_GE(j.fine.state_bound_violation, 0.0);
    EXPECT_LT(j.fine.state_bound_violation, 1e-3);
    EXPECT_FALSE(j.HasWarning("infeasible"));
  }
  const SolveRequest request = Request(*bounds, 40, TerminalMode::kHard, "lgr");
  const SolveResult l = SolveWith("ipopt", *bounds, request);
  ASSERT_EQ(l.status, SolveStatus::kConverged) << l.message;
  EXPECT_LT(RelativeError(l.objective, BrysonDenham::OptimalCost()), 1e-3);
}

// The judge warns when a result leaves the state bounds: controls that drive x1 over l.
TEST(ProblemClass, JudgeWarnsWhenTheStateBoundsAreViolated) {
  const auto ocp = MakeProblem("bryson-denham-bounds", {}, 0);
  SolveRequest request = Request(*ocp, 50, TerminalMode::kHard, "trapezoid");
  SolveResult r;
  r.status = SolveStatus::kConverged;
  r.controls = ControlTrajectory::Constant(request.grid, Vec::Constant(1, 0.0));  // x1 = t
  const Judgement j = JudgeResult(*ocp, request, r);
  EXPECT_NEAR(j.fine.state_bound_violation, 1.0 - BrysonDenham::kDefaultBound, 1e-12);
  EXPECT_TRUE(j.HasWarning("infeasible"));
}

// Every method that does not take a feature says so, naming the feature and who takes it.
TEST(ProblemClass, MethodsThatDoNotTakeAFeatureAreNotApplicableWithTheReason) {
  struct Refusal {
    std::string solver, transcription, feature;
  };
  for (const std::string problem : {"free-start", "bryson-denham-bounds"}) {
    const auto ocp = MakeProblem(problem, {}, 0);
    const std::string feature = problem == "free-start" ? "a free initial state" : "state bounds";
    for (const Refusal& c : {Refusal{"hamiltonian", "", feature},
                             Refusal{"hamiltonian-proximal", "", feature},
                             Refusal{"hamiltonian-polish", "", feature},
                             Refusal{"indirect-newton", "", feature},
                             Refusal{"riccati-ip", "euler", feature},
                             Refusal{"ipopt", "single-shooting", feature},
                             Refusal{"nlopt", "single-shooting", feature}}) {
      // riccati-ip takes state bounds (as bounds of x_1..x_N) and a free initial state (stage-0
      // variables; its optima are checked by solvers_test's RiccatiIpSolver.StateBoundsReach-
      // and FreeInitialStatesAndStaticParametersReachIpoptsOptimum): through the registry it
      // must solve, not refuse.
      // indirect-newton takes a free initial state (transversality rows; checked against the
      // analytic optimum by solvers_test's IndirectNewtonFreeStart tests), not state bounds, and
      // so does the Hamiltonian family on forward Euler (FamilyFreeStart tests); the paper's
      // hamiltonian keeps x0 fixed.
      SCOPED_TRACE(problem + " / " + c.solver + " " + c.transcription);
      const bool takes_free_start = c.solver == "indirect-newton" ||
                                    c.solver == "hamiltonian-proximal" ||
                                    c.solver == "hamiltonian-polish";
      if (c.solver == "riccati-ip" || (takes_free_start && feature == "a free initial state")) {
        const SolveResult r =
            SolveWith(c.solver, *ocp, Request(*ocp, 10, TerminalMode::kPenalty, c.transcription));
        EXPECT_EQ(r.status, SolveStatus::kConverged) << r.message;
        continue;
      }
      const SolveResult r =
          SolveWith(c.solver, *ocp, Request(*ocp, 10, TerminalMode::kPenalty, c.transcription));
      EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
      EXPECT_EQ(r.solver_status, "not_applicable");
      EXPECT_NE(r.message.find(c.feature), std::string::npos) << r.message;
      // ...while it is for these (a free initial state, state bounds), which it takes.
      EXPECT_NE(r.message.find("riccati-ip on euler"), std::string::npos) << r.message;
      EXPECT_EQ(r.iterations, 0);
    }
  }
  const Coupled coupled;  // boundary constraints alone (x0 fixed), one of them an inequality
  for (const std::string solver : {"hamiltonian", "indirect-newton"}) {
    const SolveResult r = SolveWith(solver, coupled, Request(coupled, 10, TerminalMode::kHard));
    EXPECT_EQ(r.status, SolveStatus::kNotApplicable) << solver;
    // Who solves it: riccati-ip, which takes boundary inequalities too.
    EXPECT_NE(r.message.find("riccati-ip on euler"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("boundary constraints"), std::string::npos) << r.message;
  }
  const SolveResult riccati =
      SolveWith("riccati-ip", coupled, Request(coupled, 10, TerminalMode::kHard, "euler"));
  EXPECT_EQ(riccati.status, SolveStatus::kConverged) << riccati.message;
  const SolveResult ipopt =  // the same Euler NLP (the second row one-sided: upper 1, lower -inf)
      SolveWith("ipopt", coupled, Request(coupled, 10, TerminalMode::kHard, "euler"));
  ASSERT_EQ(ipopt.status, SolveStatus::kConverged) << ipopt.message;
  EXPECT_NEAR(riccati.objective, ipopt.objective, 1e-8 * std::max(1.0, std::abs(ipopt.objective)));
  const SolveResult shooting =
      SolveWith("ipopt", coupled, Request(coupled, 10, TerminalMode::kHard, "single-shooting"));
  EXPECT_EQ(shooting.status, SolveStatus::kNotApplicable);
  EXPECT_NE(shooting.message.find("boundary constraints"), std::string::npos);
}

}  // namespace
}  // namespace ocpb
