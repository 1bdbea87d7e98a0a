// MultiPhaseOcp: every derivative of the stacked problem against central differences (the
// chain rule through the durations, the links, events and each phase's own boundary rows and
// initial cost), the layout, SplitPhases, and the constructor's one-line refusals.
#include "core/multi_phase_ocp.h"

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/autodiff_ocp.h"
#include "core/derivative_check.h"

namespace ocpb {
namespace {

// Phase A: 2 states, 1 control, a nonlinear f, L, phi, one path row and one terminal row (an
// event when A is not the last phase).
class PhaseA final : public AutoDiffOcp<PhaseA, 2, 1, 1, 1> {
 public:
  PhaseA() {
    SetHorizon(0.0, 2.0);
    SetInitialState(Eigen::Vector2d(0.3, -0.2));
    SetControlSet(ControlSet::Box(Vec::Constant(1, -2.0), Vec::Constant(1, 2.0)));
  }
  std::string name() const override { return "phase-a"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 2>* f) const {
    (*f)[0] = x[1] * cos(x[0]);
    (*f)[1] = u[0] * x[0] - sin(x[1]) * u[0] * u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 2>& x, const VecT<T, 1>& u) const {
    return x[0] * x[0] * u[0] + exp(0.3 * x[1]) + u[0] * u[0];
  }
  template <class T>
  T EvalTerminalCost(const VecT<T, 2>& x) const {
    return x[0] * x[1] * x[1];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 2>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[0] * x[0] + sin(x[1]) - 0.5;
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 2>& x, const VecT<T, 1>& u, VecT<T, 1>* c) const {
    (*c)[0] = x[0] * u[0] - x[1];
  }
};

// Phase B: 3 states, 2 controls, a ball control set, an initial cost, its own boundary row and
// two terminal rows.
class PhaseB final : public AutoDiffOcp<PhaseB, 3, 2, 2, 0> {
 public:
  PhaseB() {
    SetHorizon(0.0, 1.5);
    SetInitialState(Eigen::Vector3d(0.1, 0.2, 1.0));
    SetControlSet(ControlSet().AddBall(2, 1.5));
    SetBoundaryConstraints(Vec::Constant(1, -1.0), Vec::Constant(1, 1.0));
  }
  std::string name() const override { return "phase-b"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 3>& x, const VecT<T, 2>& u, VecT<T, 3>* f) const {
    (*f)[0] = x[1] + u[0] * x[2];
    (*f)[1] = -x[0] * u[1] + x[2] * x[2];
    (*f)[2] = -0.1 * (u[0] * u[0] + u[1] * u[1]) * x[2];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 3>& x, const VecT<T, 2>& u) const {
    return x[0] * x[1] + u[0] * u[1] * x[2] + u[1] * u[1];
  }
  template <class T>
  T EvalInitialCost(const VecT<T, 3>& x0) const {
    return x0[0] * x0[0] * x0[2] + x0[1];
  }
  template <class T>
  void EvalBoundaryConstraints(const VecT<T, 3>& x0,
                               const VecT<T, 3>& xf,
                               VecT<T, Eigen::Dynamic>* b) const {
    (*b)[0] = xf[2] * x0[0] - x0[1] * x0[1] + xf[0] * xf[1];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 3>& x, VecT<T, 2>* psi) const {
    (*psi)[0] = x[0] * x[2];
    (*psi)[1] = x[1] - x[0] * x[0];
  }
};

// A phase with a free final time of its own (refused: the duration is the phases' decision).
class FreeTimePhase final : public AutoDiffOcp<FreeTimePhase, 1, 1, 0, 0> {
 public:
  FreeTimePhase() {
    SetHorizon(0.0, 1.0);
    SetFreeFinalTime(0.5, 2.0);
  }
  std::string name() const override { return "free-time-phase"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = u[0];
  }
};

// One state in [0, 2], starting at 0.5.
class BoundedPhase final : public AutoDiffOcp<BoundedPhase, 1, 1, 0, 0> {
 public:
  BoundedPhase() {
    SetHorizon(0.0, 1.0);
    SetInitialState(Vec::Constant(1, 0.5));
    SetStateBounds(Vec::Constant(1, 0.0), Vec::Constant(1, 2.0));
  }
  std::string name() const override { return "bounded-phase"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = u[0];
  }
};
std::unique_ptr<MultiPhaseOcp> MakeAb() {
  std::vector<PhaseSpec> phases = {{std::make_shared<PhaseA>(), 0.5, 4.0},
                                   {std::make_shared<PhaseB>(), 0.2, 3.0}};
  // B's first two states continue A's (the second with a jump), B's third starts free.
  return std::make_unique<MultiPhaseOcp>(
      "ab", std::move(phases), std::vector<std::vector<PhaseLink>>{{{0, 0, 0.0}, {1, 1, -0.25}}});
}

Vec Random(int n, double scale, unsigned seed) {
  Vec v(n);
  for (int i = 0; i < n; ++i) v[i] = scale * std::sin(1.7 * (i + 1) + 0.37 * seed);
  return v;
}

TEST(MultiPhaseOcp, LayoutAndBounds) {
  const auto ocp = MakeAb();
  EXPECT_EQ(ocp->nx(), 2 + 3 + 2);  // states of both phases, then the two durations
  EXPECT_EQ(ocp->nu(), 1 + 2);
  EXPECT_EQ(ocp->num_path(), 1);
  EXPECT_EQ(ocp->num_terminal(), 2);          // B's psi
  EXPECT_EQ(ocp->num_boundary(), 2 + 1 + 1);  // two links, A's event, B's own row
  EXPECT_EQ(ocp->num_static_parameters(), 2);
  EXPECT_EQ(ocp->duration_index(1), 6);
  EXPECT_TRUE(ocp->HasFreeInitialState());
  EXPECT_TRUE(ocp->HasInitialCost());
  const VectorBounds b0 = ocp->InitialNodeBounds();
  // Phase A's start is fixed, B's free, durations in their bounds (guess = nominal 2, 1.5).
  EXPECT_EQ(b0.lower[0], 0.3);
  EXPECT_EQ(b0.upper[1], -0.2);
  EXPECT_EQ(b0.lower[3], -std::numeric_limits<double>::infinity());
  EXPECT_EQ(b0.lower[5], 0.5);
  EXPECT_EQ(b0.upper[6], 3.0);
  EXPECT_EQ(ocp->x0()[5], 2.0);
  EXPECT_EQ(ocp->x0()[6], 1.5);
  EXPECT_EQ(ocp->control_set().blocks().size(), 2u);
  EXPECT_EQ(ocp->control_set().blocks()[1].kind, ControlSet::Kind::kBall);
  EXPECT_EQ(ocp->control_set().blocks()[1].offset, 1);
  EXPECT_NO_THROW(ocp->CheckStaticParameterDynamics());
}

// A later phase's start is a decision: its state bounds hold there (the initial node takes the
// initial-state bounds alone).
TEST(MultiPhaseOcp, LaterPhasesStartInsideTheirStateBounds) {
  const auto p = std::make_shared<BoundedPhase>();
  const MultiPhaseOcp ocp("p", {{p, 1, 2}, {p, 1, 2}}, {MultiPhaseOcp::Continuity(1)});
  const VectorBounds b0 = ocp.InitialNodeBounds();
  EXPECT_EQ(b0.lower[0], 0.5);  // phase 1: its fixed x0
  EXPECT_EQ(b0.lower[1], 0.0);  // phase 2: its state bounds
  EXPECT_EQ(b0.upper[1], 2.0);
  ASSERT_TRUE(ocp.state_bounds().has_value());
  EXPECT_EQ(ocp.state_bounds()->upper[1], 2.0);
}

TEST(MultiPhaseOcp, DerivativesMatchFiniteDifferences) {
  const auto ocp = MakeAb();
  const int n = ocp->nx(), nb = ocp->num_boundary();
  for (unsigned seed = 1; seed <= 3; ++seed) {
    Vec x = Random(n, 0.8, seed);
    x[5] = 1.3 + 0.1 * seed;  // durations away from 0
    x[6] = 0.7;
    const Vec u = Random(ocp->nu(), 0.9, seed + 10);
    const Vec lambda = Random(n, 1.1, seed + 20);
    const Vec mu = Random(ocp->num_path(), 0.7, seed + 30);
    const Vec nu = Random(ocp->num_terminal(), 0.6, seed + 40);
    const DerivativeCheck point = CheckOcpDerivatives(*ocp, 0.4, x, u, lambda, mu, nu);
    EXPECT_LT(point.max_error, 1e-7) << point.log;

    // Boundary rows (links, A's event, B's own row) in (x(0), x(1)), and their Hessian.
    Vec x0 = Random(n, 0.6, seed + 50), xf = Random(n, 0.7, seed + 60);
    Vec ends(2 * n);
    ends << x0, xf;
    const auto b_of = [&](const Vec& z) {
      Vec b(nb);
      ocp->BoundaryConstraints(z.head(n), z.tail(n), b);
      return b;
    };
    Vec b(nb);
    Mat b0(nb, n), bf(nb, n);
    ocp->BoundaryConstraintsJacobian(x0, xf, b, b0, bf);
    Mat jac(nb, 2 * n);
    jac << b0, bf;
    EXPECT_LT((jac - CentralJacobian(b_of, ends)).cwiseAbs().maxCoeff(), 1e-7);
    EXPECT_LT((b - b_of(ends)).cwiseAbs().maxCoeff(), 1e-15);
    const Vec mu_b = Random(nb, 0.9, seed + 70);
    const auto grad_of = [&](const Vec& z) {
      Vec bb(nb);
      Mat j0(nb, n), jf(nb, n);
      ocp->BoundaryConstraintsJacobian(z.head(n), z.tail(n), bb, j0, jf);
      Vec g(2 * n);
      g << j0.transpose() * mu_b, jf.transpose() * mu_b;
      return g;
    };
    Mat hess(2 * n, 2 * n);
    ocp->BoundaryHessian(x0, xf, mu_b, hess);
    EXPECT_LT((hess - CentralJacobian(grad_of, ends)).cwiseAbs().maxCoeff(), 1e-6);

    // Initial cost (B's: its start is a decision) and its derivatives.
    const auto phi0_of = [&](const Vec& z) { return Vec::Constant(1, ocp->InitialCost(z)); };
    double phi0 = 0.0;
    Vec g0(n);
    ocp->InitialCostGradient(x0, &phi0, g0);
    EXPECT_NEAR(phi0, ocp->InitialCost(x0), 1e-15);
    EXPECT_LT((g0.transpose() - CentralJacobian(phi0_of, x0)).cwiseAbs().maxCoeff(), 1e-7);
    const auto g0_of = [&](const Vec& z) {
      double v = 0.0;
      Vec g(n);
      ocp->InitialCostGradient(z, &v, g);
      return Vec(1.7 * g);
    };
    Mat h0(n, n);
    ocp->InitialCostHessian(x0, 1.7, h0);
    EXPECT_LT((h0 - CentralJacobian(g0_of, x0)).cwiseAbs().maxCoeff(), 1e-6);
  }
}

// The stacked values are the phases' own: T_i f_i, T_i L_i, the links with their jumps.
TEST(MultiPhaseOcp, ValuesAreThePhasesScaledByTheirDurations) {
  const auto ocp = MakeAb();
  Vec x = Random(ocp->nx(), 0.8, 4);
  x[5] = 1.25;
  x[6] = 0.5;
  const Vec u = Random(ocp->nu(), 0.9, 5);
  Vec f(ocp->nx());
  ocp->Dynamics(0.3, x, u, f);
  Vec fa(2), fb(3);
  ocp->phase(0).Dynamics(0.3 * 2.0, x.head(2), u.head(1), fa);
  ocp->phase(1).Dynamics(0.3 * 1.5, x.segment(2, 3), u.tail(2), fb);
  EXPECT_LT((f.head(2) - 1.25 * fa).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((f.segment(2, 3) - 0.5 * fb).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_EQ(f[5], 0.0);
  EXPECT_EQ(f[6], 0.0);
  const double L = ocp->RunningCost(0.3, x, u);
  EXPECT_NEAR(L,
              1.25 * ocp->phase(0).RunningCost(0.6, x.head(2), u.head(1)) +
                  0.5 * ocp->phase(1).RunningCost(0.45, x.segment(2, 3), u.tail(2)),
              1e-14);
  Vec x0 = x, xf = x;
  x0[3] = xf[1] - 0.25 + 0.125;  // B's second state starts 0.125 above A's end + jump
  Vec b(ocp->num_boundary());
  ocp->BoundaryConstraints(x0, xf, b);
  EXPECT_NEAR(b[1], 0.125, 1e-15);
}

TEST(MultiPhaseOcp, SplitPhasesGivesPhysicalTimes) {
  const auto ocp = MakeAb();
  const std::vector<double> tau = {0.0, 0.5, 1.0};
  Mat X = Mat::Zero(ocp->nx(), 3);
  X.row(5).setConstant(2.0);  // T_A
  X.row(6).setConstant(1.0);  // T_B
  X.row(2) << 7.0, 8.0, 9.0;  // B's first state
  const auto phases = ocp->SplitPhases(tau, X);
  ASSERT_EQ(phases.size(), 2u);
  EXPECT_EQ(phases[0].t, (std::vector<double>{0.0, 1.0, 2.0}));
  EXPECT_EQ(phases[1].t, (std::vector<double>{2.0, 2.5, 3.0}));
  EXPECT_EQ(phases[1].x.rows(), 3);
  EXPECT_EQ(phases[1].x(0, 2), 9.0);
  EXPECT_THROW(ocp->SplitPhases({0.0, 1.0}, X), std::invalid_argument);
}

// Refusals: one line naming the problem, the phase and the rule.
TEST(MultiPhaseOcp, RefusesInconsistentDefinitions) {
  const auto expect_error = [](const std::function<void()>& make, const std::string& part) {
    try {
      make();
      ADD_FAILURE() << "no error; expected one containing: " << part;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  const auto a = std::make_shared<PhaseA>();
  const auto b = std::make_shared<PhaseB>();
  expect_error([] { MultiPhaseOcp("p", {}, {}); }, "multi-phase problem 'p': no phase");
  expect_error(
      [&] {
        MultiPhaseOcp("p", {{a, 1, 2}, {b, 1, 2}}, {});
      },
      "0 link lists for 2 phases");
  expect_error(
      [&] {
        MultiPhaseOcp("p", {{a, 1, 2}, {b, 1, 2}}, {{{2, 0, 0.0}}});
      },
      "link from phase 1 state 2 to phase 2 state 0: index outside");
  expect_error(
      [&] {
        MultiPhaseOcp("p", {{a, 0, 2}}, {});
      },
      "phase 1: duration bounds [0, 2] must be finite with 0 < min <= max");
  expect_error([&] { MultiPhaseOcp("p", {{a, 3, 2}}, {}); }, "0 < min <= max");
  expect_error([&] { MultiPhaseOcp("p", {{a, -1e-7, 2}}, {}); }, "bounds [-1e-07, 2]");
  expect_error(
      [&] {
        MultiPhaseOcp("p", {{a, 1, 2}, {b, 1, 2}}, {{{0, 0, 0.0}, {1, 0, 0.0}}});
      },
      "phase 2 state 0 is linked twice");
  expect_error(
      [] {
        MultiPhaseOcp("p", {{std::make_shared<FreeTimePhase>(), 1, 2}}, {});
      },
      "phase 1: has a free final time of its own");
  expect_error([&] { MultiPhaseOcp("p", {{nullptr, 1, 2}}, {}); }, "phase 1: no problem");
  expect_error([] { MultiPhaseOcp::Continuity(2, Vec::Ones(3)); }, "jump has 3 entries");
}

}  // namespace
}  // namespace ocpb
