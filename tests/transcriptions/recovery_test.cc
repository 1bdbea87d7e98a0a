// What the transcriptions hand back: controls with each scheme's interpolation rule, states on
// state_grid(), the starting point, bounds, scaling invariance and request validation.
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "core/evaluator.h"
#include "problems/registry.h"
#include "tests/core/test_problems.h"
#include "tests/transcriptions/nlp_test_util.h"
#include "tests/transcriptions/test_ocps.h"
#include "transcriptions/collocation_nlp.h"
#include "transcriptions/radau_nodes.h"

namespace ocpb {
namespace {

using Side = ControlTrajectory::Side;

const CollocationNlp& AsCollocation(const std::unique_ptr<TranscribedNlp>& nlp) {
  return dynamic_cast<const CollocationNlp&>(*nlp);
}

// z with the given control function at every control block (states zero).
Vec WithControls(const CollocationNlp& nlp, const std::function<double(double)>& u) {
  Vec z = Vec::Zero(nlp.num_variables());
  for (const auto& c : nlp.layout().controls) z[c.offset] = u(c.t);
  return z;
}

TEST(Recovery, TrapezoidControlsArePiecewiseLinearThroughTheNodes) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  TranscriptionOptions o;
  o.grid = TimeGrid::FromPoints({0.0, 0.3, 0.5, 1.0});
  const auto nlp = testing::MakeScheme("trapezoid")->Transcribe(*ocp, o);
  const Vec z = WithControls(AsCollocation(nlp), [](double t) { return t * t; });
  const ControlTrajectory u = nlp->Controls(z);
  EXPECT_EQ(u.interpolation(), ControlTrajectory::Interpolation::kPiecewiseLinear);
  EXPECT_NEAR(u(0.4)[0], 0.5 * (0.09 + 0.25), 1e-15);
  EXPECT_NEAR(u(1.0, Side::kLeft)[0], 1.0, 1e-15);
  EXPECT_EQ(nlp->state_grid().size(), 4);
}

TEST(Recovery, HermiteSimpsonControlsAreQuadraticPerIntervalAndProjected) {
  const auto ocp = MakeProblem("double-integrator-bounded", {}, 0);  // |u| <= 5
  TranscriptionOptions o;
  o.grid = TimeGrid::FromPoints({0.0, 0.4, 1.0});
  const auto nlp = testing::MakeScheme("hermite-simpson")->Transcribe(*ocp, o);
  EXPECT_EQ(nlp->state_grid().size(), 5);
  EXPECT_DOUBLE_EQ(nlp->state_grid().t(1), 0.2);
  // A quadratic inside the bounds is reproduced exactly on each interval.
  const auto q = [](double t) { return 1.0 - 3.0 * t + 4.0 * t * t; };
  const ControlTrajectory u = nlp->Controls(WithControls(AsCollocation(nlp), q));
  for (double t : {0.05, 0.33, 0.4, 0.71, 0.99}) EXPECT_NEAR(u(t)[0], q(t), 1e-14) << t;
  // An overshoot between the points is projected onto [-5, 5]: values 5, 5, 0 on [0, 0.4] give
  // 5.625 at s = 1/4 before projection.
  Vec z = Vec::Zero(nlp->num_variables());
  const auto& c = AsCollocation(nlp).layout().controls;
  z[c[0].offset] = 5.0;
  z[c[1].offset] = 5.0;
  const ControlTrajectory v = nlp->Controls(z);
  EXPECT_DOUBLE_EQ(v(0.1)[0], 5.0);
  EXPECT_NEAR(v(0.3)[0], 3.125, 1e-14);  // s = 3/4: -5/8 + 15/4, inside the box
}

TEST(Recovery, LgrControlsArePolynomialsPerIntervalWithOneSidedLimits) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  TranscriptionOptions o;
  o.grid = TimeGrid::FromPoints({0.0, 0.45, 1.0});
  o.degree = 4;
  const auto nlp = testing::MakeScheme("lgr")->Transcribe(*ocp, o);
  EXPECT_EQ(nlp->state_grid().size(), 2 * 4 + 1);
  // A cubic (degree K - 1) is reproduced on each interval, including the extrapolated end.
  const auto cubic = [](double t) { return 0.2 + t - 2.0 * t * t * t; };
  const ControlTrajectory u = nlp->Controls(WithControls(AsCollocation(nlp), cubic));
  for (double t : {0.0, 0.2, 0.449, 0.6, 0.99}) EXPECT_NEAR(u(t)[0], cubic(t), 1e-13) << t;
  EXPECT_NEAR(u(0.45, Side::kLeft)[0], cubic(0.45), 1e-13);
  EXPECT_NEAR(u(1.0, Side::kLeft)[0], cubic(1.0), 1e-13);
  // Different constants on the two intervals: the breakpoint's left limit uses interval 0.
  const ControlTrajectory w = nlp->Controls(
      WithControls(AsCollocation(nlp), [](double t) { return t < 0.45 ? 1.0 : 2.0; }));
  EXPECT_NEAR(w(0.45, Side::kLeft)[0], 1.0, 1e-14);
  EXPECT_NEAR(w(0.45, Side::kRight)[0], 2.0, 1e-14);
  // The interior LGR times are t_k + h (tau_i + 1)/2.
  const RadauNodes r = ComputeRadauNodes(4);
  EXPECT_NEAR(nlp->state_grid().t(2), 0.45 * (r.points[2] + 1.0) / 2.0, 1e-15);
}

// At the analytic double-integrator optimum, re-simulating each scheme's controls with fine RK4
// reproduces the scheme's states: exactly for the schemes whose control rule contains the linear
// u* (trapezoid, Hermite-Simpson, LGR), up to 6h for Euler's piecewise constant.
TEST(Recovery, ResimulationOfTheAnalyticOptimum) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  for (const std::string scheme : {"euler", "trapezoid", "hermite-simpson", "lgr"}) {
    TranscriptionOptions o;
    o.grid = TimeGrid::Uniform(0.0, 1.0, 8);
    o.terminal = TerminalMode::kHard;
    const auto nlp = testing::MakeScheme(scheme)->Transcribe(*ocp, o);
    Vec z(nlp->num_variables());
    for (const auto& s : AsCollocation(nlp).layout().states) {
      z[s.offset] = -1.0 + 3.0 * s.t * s.t - 2.0 * s.t * s.t * s.t;
      z[s.offset + 1] = 6.0 * s.t - 6.0 * s.t * s.t;
    }
    for (const auto& c : AsCollocation(nlp).layout().controls) z[c.offset] = 6.0 - 12.0 * c.t;
    const double defect =
        ResimulationDefect(*ocp, nlp->Controls(z), nlp->state_grid(), nlp->States(z), 4);
    if (scheme == "euler") {
      // x2(1) re-simulated = sum h (6 - 12 t_k) = 6h instead of 0.
      EXPECT_NEAR(defect, 6.0 / 8.0, 1e-12);
    } else {
      EXPECT_LT(defect, 1e-13) << scheme;
    }
  }
}

// Collocation schemes start from the RK4 simulation, on state_grid(), of the projected guess.
TEST(Recovery, StartingPointSimulatesTheGuessWithRk4) {
  const testing::BallTestOcp ocp;
  for (const std::string scheme : {"trapezoid", "hermite-simpson", "lgr"}) {
    TranscriptionOptions o;
    o.grid = TimeGrid::Uniform(0.0, 2.0, 5);
    Vec u(3);
    u << 0.5, 0.4, 3.0;  // outside the box [-0.5, 2] in u3; inside the ball in (u1, u2)
    o.initial_guess = ControlTrajectory::Constant(o.grid, u);
    const auto nlp = testing::MakeScheme(scheme)->Transcribe(ocp, o);
    const Vec z = nlp->StartingPoint();
    const ControlTrajectory controls = nlp->Controls(z);
    EXPECT_NEAR(controls(0.7)[2], 2.0, 1e-14) << scheme;
    const Evaluation ev = Evaluate(ocp, controls, nlp->state_grid(), Integrator::kRk4);
    EXPECT_TRUE(nlp->States(z).isApprox(ev.X, 1e-14)) << scheme;
  }
}

// Box blocks become variable bounds, ball blocks one constraint |u_b - c|^2 <= r^2 per control
// block, path constraints c <= 0, and the hard terminal constraints psi = 0.
TEST(Recovery, BoundsOfMixedControlSetPathAndTerminalRows) {
  const testing::BallTestOcp ocp;
  TranscriptionOptions o;
  o.grid = TimeGrid::Uniform(0.0, 2.0, 3);
  o.terminal = TerminalMode::kHard;
  const auto nlp_ptr = testing::MakeScheme("trapezoid")->Transcribe(ocp, o);
  const CollocationNlp& nlp = AsCollocation(nlp_ptr);
  EXPECT_EQ(nlp.num_constraints(), 3 * 2 + 4 * 2 + 4 + 1);
  Vec zl, zu, gl, gu;
  nlp.Bounds(&zl, &zu, &gl, &gu);
  const auto& c = nlp.layout().controls[1];
  EXPECT_TRUE(std::isinf(zl[c.offset]) && std::isinf(zu[c.offset + 1]));
  EXPECT_EQ(zl[c.offset + 2], -0.5);
  EXPECT_EQ(zu[c.offset + 2], 2.0);
  for (int r = nlp.path_row_begin(); r < nlp.ball_row_begin(); ++r) {
    EXPECT_TRUE(std::isinf(gl[r]) && gl[r] < 0 && gu[r] == 0.0);
  }
  for (int r = nlp.ball_row_begin(); r < nlp.terminal_row_begin(); ++r) {
    EXPECT_TRUE(std::isinf(gl[r]) && gu[r] == 1.0);
  }
  EXPECT_EQ(gl[nlp.terminal_row_begin()], 0.0);
  EXPECT_EQ(gu[nlp.terminal_row_begin()], 0.0);
  Vec z = nlp.StartingPoint();
  z.segment(c.offset, 3) << 0.2 + 0.6, -0.1 - 0.8, 1.0;
  Vec g(nlp.num_constraints());
  ASSERT_TRUE(nlp.Constraints(z, g));
  EXPECT_NEAR(g[nlp.ball_row_begin() + 1], 1.0, 1e-15);
}

// Scaling changes what the solver sees, not the answer: the exact optimum of the scaled NLP maps
// back to the same controls, states and costates, and its objective is the scaled one.
TEST(Recovery, ScalingLeavesTheSolutionUnchanged) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  for (const std::string scheme : {"euler", "hermite-simpson", "lgr"}) {
    for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
      TranscriptionOptions o;
      o.grid = TimeGrid::Uniform(0.0, 1.0, 6);
      o.terminal = mode;
      const auto plain = testing::MakeScheme(scheme)->Transcribe(*ocp, o);
      o.scaling.objective = 1e-3;
      o.scaling.state = Vec::Constant(2, 4.0);
      o.scaling.state[1] = 0.1;
      o.scaling.control = Vec::Constant(1, 20.0);
      const auto scaled = testing::MakeScheme(scheme)->Transcribe(*ocp, o);
      const testing::KktSolution a = testing::SolveEqualityKkt(*plain, plain->StartingPoint());
      const testing::KktSolution b = testing::SolveEqualityKkt(*scaled, scaled->StartingPoint());
      ASSERT_TRUE(a.converged && b.converged);
      const CollocationNlp& s = dynamic_cast<const CollocationNlp&>(*scaled);
      EXPECT_TRUE(s.Unscale(b.z).isApprox(a.z, 1e-10)) << scheme;
      EXPECT_TRUE(scaled->States(b.z).isApprox(plain->States(a.z), 1e-10));
      EXPECT_TRUE(scaled->Costates(b.z, b.lambda).isApprox(plain->Costates(a.z, a.lambda), 1e-8))
          << scheme << "\n"
          << scaled->Costates(b.z, b.lambda) << "\n"
          << plain->Costates(a.z, a.lambda);
      EXPECT_NEAR(scaled->Controls(b.z)(0.3)[0], plain->Controls(a.z)(0.3)[0], 1e-9);
      double fa, fb;
      ASSERT_TRUE(plain->Objective(a.z, &fa) && scaled->Objective(b.z, &fb));
      EXPECT_NEAR(fb, 1e-3 * fa, 1e-12);
      EXPECT_TRUE(s.Unscale(scaled->StartingPoint()).isApprox(plain->StartingPoint(), 1e-15));
    }
  }
}

TEST(Recovery, InvalidRequestsThrow) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  for (const std::string scheme : {"euler", "trapezoid", "hermite-simpson", "lgr"}) {
    const auto t = testing::MakeScheme(scheme);
    EXPECT_EQ(t->name(), scheme);
    TranscriptionOptions o;
    o.grid = TimeGrid::Uniform(0.0, 0.9, 4);
    EXPECT_THROW(t->Transcribe(*ocp, o), std::invalid_argument) << scheme;
    o.grid = TimeGrid::Uniform(0.0, 1.0, 4);
    o.initial_guess = ControlTrajectory::Constant(o.grid, Vec::Zero(2));
    EXPECT_THROW(t->Transcribe(*ocp, o), std::invalid_argument) << scheme;
    o.initial_guess.reset();
    o.scaling.state = Vec::Ones(3);
    EXPECT_THROW(t->Transcribe(*ocp, o), std::invalid_argument) << scheme;
    o.scaling.state = Vec::Ones(2);
    EXPECT_NO_THROW(t->Transcribe(*ocp, o)) << scheme;
  }
  TranscriptionOptions o;
  o.grid = TimeGrid::Uniform(0.0, 1.0, 4);
  o.degree = 0;
  EXPECT_THROW(testing::MakeScheme("lgr")->Transcribe(*ocp, o), std::invalid_argument);
}

// LGR with one point per interval is forward Euler: same variables, defects halved, same
// objective.
TEST(Recovery, LgrWithOnePointIsEuler) {
  const testing::ScalarLqOcp ocp;
  TranscriptionOptions o;
  o.grid = TimeGrid::FromPoints({0.0, 0.2, 0.7, 1.0});
  o.degree = 1;
  const auto lgr = testing::MakeScheme("lgr")->Transcribe(ocp, o);
  const auto euler = testing::MakeScheme("euler")->Transcribe(ocp, o);
  ASSERT_EQ(lgr->num_variables(), euler->num_variables());
  ASSERT_EQ(lgr->num_constraints(), euler->num_constraints());
  Vec z = Vec::LinSpaced(lgr->num_variables(), -0.4, 0.9);
  double fl, fe;
  ASSERT_TRUE(lgr->Objective(z, &fl) && euler->Objective(z, &fe));
  EXPECT_NEAR(fl, fe, 1e-15);
  Vec gl(lgr->num_constraints()), ge(euler->num_constraints());
  ASSERT_TRUE(lgr->Constraints(z, gl) && euler->Constraints(z, ge));
  EXPECT_TRUE(gl.isApprox(0.5 * ge, 1e-14));
}

}  // namespace
}  // namespace ocpb
