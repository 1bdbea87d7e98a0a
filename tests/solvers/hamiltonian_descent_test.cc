#include "solvers/hamiltonian_descent.h"

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>
#include <Eigen/Cholesky>

#include "core/autodiff_ocp.h"
#include "core/evaluator.h"
#include "problems/comm_path2d.h"
#include "problems/registry.h"
#include "solvers/registry.h"
#include "tests/solvers/descent_request.h"

namespace ocpb {
namespace {

using testing::DescentRequest;

std::unique_ptr<Ocp> PaperProblem(std::vector<std::string> set = {}) {
  set.insert(set.begin(), "channel=0");  // deterministic path-loss channel
  return MakeProblem("comm-path2d", set, 1);
}

// Every accepted step satisfied the Armijo test of the previous iterate's theta, J decreased,
// and the history is numbered 0..iterations.
void ExpectArmijoHistory(const SolveResult& r, double alpha = 0.1, double beta = 0.5) {
  ASSERT_EQ(static_cast<int>(r.history.size()), r.iterations + 1);
  for (size_t i = 0; i < r.history.size(); ++i) {
    const IterationRecord& h = r.history[i];
    EXPECT_EQ(h.iteration, static_cast<int>(i));
    EXPECT_LE(h.theta, 0.0);
    if (i == 0) {
      EXPECT_EQ(h.armijo_j, -1);
      continue;
    }
    const IterationRecord& prev = r.history[i - 1];
    ASSERT_GE(h.armijo_j, 0);
    EXPECT_LT(h.J, prev.J) << "iteration " << i;
    EXPECT_LE(h.J - prev.J, alpha * std::pow(beta, h.armijo_j) * prev.theta) << "iteration " << i;
    EXPECT_GE(h.cpu_seconds, prev.cpu_seconds);
  }
}

// ---- options ------------------------------------------------------------------------------------

TEST(HamiltonianDescentOptions, DefaultsAreThePapersAndValid) {
  const HamiltonianDescent::Options o;
  std::string error;
  EXPECT_TRUE(o.IsValid(&error)) << error;
  EXPECT_EQ(o.alpha, 0.1);
  EXPECT_EQ(o.beta, 0.5);
  EXPECT_EQ(o.max_iterations, 500);
  EXPECT_EQ(o.max_armijo_exponent, 50);
  EXPECT_EQ(o.theta_tolerance, 0.0);
}

TEST(HamiltonianDescentOptions, IsValidRejectsEachBadField) {
  // One function for every case (a function pointer, not a template per lambda).
  auto invalid = [](void (*mutate)(HamiltonianDescent::Options&), const char* field) {
    HamiltonianDescent::Options o;
    mutate(o);
    std::string error;
    EXPECT_FALSE(o.IsValid(&error)) << field;
    EXPECT_NE(error.find(field), std::string::npos) << error;
  };
  invalid([](auto& o) { o.alpha = 0.0; }, "alpha");
  invalid([](auto& o) { o.alpha = 1.0; }, "alpha");
  invalid([](auto& o) { o.beta = 1.5; }, "beta");
  invalid([](auto& o) { o.beta = NAN; }, "beta");
  invalid([](auto& o) { o.max_iterations = -1; }, "max_iterations");
  invalid([](auto& o) { o.max_armijo_exponent = -2; }, "max_armijo_exponent");
  invalid([](auto& o) { o.theta_tolerance = -1e-3; }, "theta_tolerance");
  invalid([](auto& o) { o.max_cpu_seconds = 0.0; }, "max_cpu_seconds");
  invalid([](auto& o) { o.path_penalty = 0.0; }, "path_penalty");
  invalid([](auto& o) { o.regularization = -1.0; }, "regularization");
  HamiltonianDescent::Options bad;
  bad.alpha = 2.0;
  EXPECT_THROW(HamiltonianDescent{bad}, std::invalid_argument);
}

TEST(HamiltonianDescentOptions, AppliesOptionsAndRejectsUnknownKeysAndBadValues) {
  const auto o = HamiltonianDescent::ApplyOptions({{"alpha", "0.2"},
                                                   {"beta", "0.25"},
                                                   {"max_iterations", "7"},
                                                   {"max_armijo_exponent", "30"},
                                                   {"theta_tolerance", "1e-8"},
                                                   {"max_cpu_seconds", "inf"}});
  EXPECT_EQ(o.alpha, 0.2);
  EXPECT_EQ(o.beta, 0.25);
  EXPECT_EQ(o.max_iterations, 7);
  EXPECT_EQ(o.max_armijo_exponent, 30);
  EXPECT_EQ(o.theta_tolerance, 1e-8);
  EXPECT_TRUE(std::isinf(o.max_cpu_seconds));
  auto message = [](const std::map<std::string, std::string>& m) {
    try {
      HamiltonianDescent::ApplyOptions(m);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message({{"max_iter", "5"}}).find("valid: alpha, beta"), std::string::npos);
  EXPECT_NE(message({{"max_iterations", "2.5"}}).find("max_iterations"), std::string::npos);
  EXPECT_NE(message({{"alpha", "abc"}}).find("alpha"), std::string::npos);
  EXPECT_NE(message({{"alpha", "1.5"}}).find("'alpha': must be a number in (0, 1)"),
            std::string::npos)
      << message({{"alpha", "1.5"}});
  EXPECT_NE(message({{"beta", "0.5x"}}).find("beta"), std::string::npos);
  EXPECT_NE(message({{"armijo_prefilter", "yes"}}).find("armijo_prefilter"), std::string::npos);
  EXPECT_FALSE(HamiltonianDescent::ApplyOptions({{"armijo_prefilter", "0"}}).armijo_prefilter);
  // Typed values are taken as they are; an integral number is an integer.
  const auto typed = HamiltonianDescent::ApplyOptions({{"max_iterations", 1e3}, {"alpha", 0.3}});
  EXPECT_EQ(typed.max_iterations, 1000);
  EXPECT_EQ(typed.alpha, 0.3);
  EXPECT_NE(message({{"max_iterations", "1e10"}}).find("max_iterations"), std::string::npos);
}

TEST(HamiltonianDescent, IsRegisteredAsHamiltonian) {
  const SolverInfo& info = FindSolver("hamiltonian");
  EXPECT_FALSE(info.uses_transcription);
  EXPECT_EQ(info.make()->name(), "hamiltonian");
}

// ---- the direction: theta bounds the discrete directional derivative ----------------------------

// On a forward-Euler grid with the exact discrete adjoint, sum_k g_k . d_k <= theta <= 0, and the
// directional derivative of the discrete J along d (central differences) is <= theta.
void ExpectThetaBoundsDirectionalDerivative(const Ocp& ocp, const Mat& U, int N) {
  const TimeGrid grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  const DiscreteOcp docp(ocp, grid, Integrator::kEuler, TerminalMode::kPenalty);
  Mat X, Lambda, G, D;
  Vec scratch;
  const double J = docp.Simulate(U, &X);
  ASSERT_TRUE(std::isfinite(J));
  docp.Adjoint(U, X, &Lambda, &G);
  const double theta = HamiltonianDescent::Direction(docp, U, X, Lambda, &D, &scratch);
  const double eps = 1e-6;
  const double fd =
      (docp.Simulate(U + eps * D, nullptr) - docp.Simulate(U - eps * D, nullptr)) / (2.0 * eps);
  const double gd = (G.array() * D.array()).sum();
  EXPECT_LT(theta, 0.0);
  EXPECT_NEAR(gd, fd, 1e-6 * std::abs(fd) + 1e-9);  // the adjoint gradient is exact
  EXPECT_GE(theta, fd - 1e-6 * std::abs(fd)) << "theta " << theta << " fd " << fd;
  EXPECT_GE(theta, gd - 1e-12 * std::abs(gd));
  // Along d the cost does decrease for a small enough step.
  EXPECT_LT(docp.Simulate(U + 1e-4 * D, nullptr), J);
}

TEST(HamiltonianDescentDirection, ThetaBoundsTheDirectionalDerivativeOnDoubleIntegrator) {
  for (const char* name : {"double-integrator", "double-integrator-bounded"}) {
    const auto ocp = MakeProblem(name, {"C=10"}, 0);
    const int N = 50;
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> dist(-3.0, 3.0);
    Mat U(1, N);
    for (int k = 0; k < N; ++k) U(0, k) = dist(rng);
    SCOPED_TRACE(name);
    ExpectThetaBoundsDirectionalDerivative(*ocp, U, N);
  }
}

TEST(HamiltonianDescentDirection, ThetaBoundsTheDirectionalDerivativeOnCommPath2d) {
  // Random feasible controls (the robot moves: speeds away from 0), with k5 = k6 = 0 and > 0.
  for (const char* k : {"k=17.75,1.16,10.46,1175,0,0", "k=17.75,1.16,10.46,1175,3,2"}) {
    const auto ocp = PaperProblem({k});
    const int N = 80;
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    Mat U(3, N);
    for (int k2 = 0; k2 < N; ++k2) {
      U.col(k2) << 0.3 * unit(rng) - 0.1, 0.3 * unit(rng) - 0.2, 3.0 + 2.5 * unit(rng);
    }
    SCOPED_TRACE(k);
    ExpectThetaBoundsDirectionalDerivative(*ocp, U, N);
  }
}

// The minimum-time problems' reformulation (controls (v, sigma), cone as a convex penalty): H is
// convex in u, so theta bounds the derivative. (With controls (w, sigma) H was bilinear and the
// Armijo search failed at the first iteration.) Random controls around the nominal one, with the
// cone penalty active at some nodes.
TEST(HamiltonianDescentDirection, ThetaBoundsTheDirectionalDerivativeOnScaledMinimumTime) {
  for (const char* name : {"brachistochrone", "zermelo", "steering"}) {
    const auto ocp = MakeProblem(name, {}, 0);
    HamiltonianReformulationOptions o;
    o.path_penalty = 50.0;
    const auto re = ocp->HamiltonianReformulation(o);
    ASSERT_NE(re, nullptr);
    const int N = 60;
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    const Vec nominal = ocp->NominalControl();
    Mat U(3, N);
    for (int k = 0; k < N; ++k) {
      const double sigma = nominal[2] * (1.0 + 0.3 * unit(rng));
      U.col(k) << nominal[0] * (1.0 + 0.4 * unit(rng)) + 0.2 * sigma * unit(rng),
          nominal[1] * (1.0 + 0.4 * unit(rng)) + 0.2 * sigma * unit(rng), sigma;
    }
    SCOPED_TRACE(name);
    ExpectThetaBoundsDirectionalDerivative(*re, U, N);
  }
}

// ---- solves -------------------------------------------------------------------------------------

// The unbounded double integrator in penalty form is a quadratic in U: its discrete minimizer
// solves a linear system. The descent (a scaled gradient step here: d = -g/h) must approach it.
TEST(HamiltonianDescent, ConvergesToTheDiscreteOptimumOfAQuadratic) {
  const auto ocp = MakeProblem("double-integrator", {"C=10"}, 0);
  const int N = 40;
  const TimeGrid grid = TimeGrid::Uniform(0.0, 1.0, N);
  const DiscreteOcp docp(*ocp, grid, Integrator::kEuler, TerminalMode::kPenalty);
  // J(U) = h/2 |U|^2 + C |A U + b|^2 with x_N = A U + b (Euler): build A by simulation.
  const double h = 1.0 / N, C = 10.0;
  Mat A(2, N);
  Vec b(2);
  b << -1.0, 0.0;  // x_N at U = 0 is x0
  for (int j = 0; j < N; ++j) {
    // Euler: x1_{k+1} = x1_k + h x2_k, x2_{k+1} = x2_k + h u_k.
    A(1, j) = h;
    A(0, j) = h * h * (N - 1 - j);
  }
  const Mat Hq = h * Mat::Identity(N, N) + 2.0 * C * A.transpose() * A;
  const Vec u_opt = Hq.ldlt().solve(-2.0 * C * A.transpose() * b);
  const double J_opt = docp.Simulate(u_opt.transpose(), nullptr);

  const HamiltonianDescent solver;
  const SolveResult r = solver.Solve(*ocp, DescentRequest(*ocp, N, {{"max_iterations", "300"}}));
  ExpectArmijoHistory(r);
  EXPECT_NEAR(r.objective, J_opt, 1e-6 * J_opt);
  EXPECT_LT((r.controls.values().row(0).transpose() - u_opt).cwiseAbs().maxCoeff(), 1e-2);
}

TEST(HamiltonianDescent, ResultDescribesTheFinalControls) {
  const auto ocp = MakeProblem("double-integrator-bounded", {"C=10", "umax=1"}, 0);
  const int N = 30;
  const SolveResult r =
      HamiltonianDescent().Solve(*ocp, DescentRequest(*ocp, N, {{"max_iterations", "20"}}));
  EXPECT_EQ(r.solver, "hamiltonian");
  EXPECT_EQ(r.status, SolveStatus::kMaxIterations);
  EXPECT_EQ(r.solver_status, "max_iterations");
  EXPECT_EQ(r.iterations, 20);
  ExpectArmijoHistory(r);
  ASSERT_EQ(r.controls.interpolation(), ControlTrajectory::Interpolation::kPiecewiseConstant);
  ASSERT_EQ(r.controls.values().cols(), N);
  EXPECT_EQ(r.states.cols(), N + 1);
  EXPECT_EQ(r.costates.cols(), N + 1);
  EXPECT_EQ(r.state_grid.intervals(), N);
  EXPECT_EQ(r.history.back().J, r.objective);
  EXPECT_EQ(r.solver_stats.at("final_theta"), r.history.back().theta);
  EXPECT_GE(r.cpu_seconds, 0.0);
  // The common evaluator (Euler on the same grid) sees exactly the solver's discrete J and X.
  const Evaluation ev = Evaluate(*ocp, r.controls, r.state_grid, Integrator::kEuler);
  EXPECT_NEAR(ev.J, r.objective, 1e-12 * r.objective);
  EXPECT_LT((ev.X - r.states).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LE(ev.control_violation, 0.0);
  // The costates are the exact discrete adjoint of the final controls.
  const DiscreteOcp docp(*ocp, r.state_grid, Integrator::kEuler, TerminalMode::kPenalty);
  Mat Lambda, G;
  docp.Adjoint(r.controls.values(), r.states, &Lambda, &G);
  EXPECT_LT((Lambda - r.costates).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(HamiltonianDescent, WarmStartContinuesTheSameSequence) {
  const auto ocp = PaperProblem();
  const HamiltonianDescent solver;
  const SolveResult ten = solver.Solve(*ocp, DescentRequest(*ocp, 100, {{"max_iterations", "10"}}));
  const SolveResult five = solver.Solve(*ocp, DescentRequest(*ocp, 100, {{"max_iterations", "5"}}));
  SolveRequest more = DescentRequest(*ocp, 100, {{"max_iterations", "5"}});
  more.initial_guess = five.controls;
  const SolveResult next = solver.Solve(*ocp, more);
  EXPECT_EQ(next.history.front().J, five.objective);
  EXPECT_NEAR(next.objective, ten.objective, 1e-10 * ten.objective);
}

TEST(HamiltonianDescent, InitialGuessIsSampledAndProjectedOntoU) {
  const auto ocp = MakeProblem("double-integrator-bounded", {"umax=1"}, 0);
  SolveRequest req = DescentRequest(*ocp, 20, {{"max_iterations", "0"}});
  const TimeGrid coarse = TimeGrid::Uniform(0.0, 1.0, 4);
  Mat values(1, 4);
  values << 5.0, -0.5, 0.25, -7.0;
  req.initial_guess = ControlTrajectory::PiecewiseConstant(coarse, values);
  const SolveResult r = HamiltonianDescent().Solve(*ocp, req);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.status, SolveStatus::kMaxIterations);
  const Mat& u = r.controls.values();
  EXPECT_EQ(u(0, 0), 1.0);
  EXPECT_EQ(u(0, 5), -0.5);
  EXPECT_EQ(u(0, 10), 0.25);
  EXPECT_EQ(u(0, 19), -1.0);
}

// The paper's scenario on the deterministic path-loss channel: the starting cost is the paper's
// 2.3872e5, and the descent makes most of its progress in the first 20 iterations.
TEST(HamiltonianDescent, PaperScenarioStartsAt238720AndDescends) {
  const auto ocp = PaperProblem();
  const SolveResult r =
      HamiltonianDescent().Solve(*ocp, DescentRequest(*ocp, 400, {{"max_iterations", "60"}}));
  ExpectArmijoHistory(r);
  ASSERT_GE(r.history.size(), 21u);
  EXPECT_NEAR(r.history[0].J, 238720.0, 1.0);
  EXPECT_LT(r.history[20].J, 2000.0);
  EXPECT_LT(r.objective, 1000.0);
  const Evaluation ev = Evaluate(*ocp, r.controls, r.state_grid, Integrator::kEuler);
  EXPECT_NEAR(ev.J, r.objective, 1e-9 * r.objective);
  EXPECT_LE(ev.control_violation, 1e-12);
  EXPECT_GT(ev.Jbar, 470.0);  // gamma k4 tf alone is 470
}

TEST(HamiltonianDescent, Rk4IntegratorIsGuardedByArmijo) {
  const auto ocp = PaperProblem();
  SolveRequest req = DescentRequest(*ocp, 100, {{"max_iterations", "15"}});
  req.integrator = Integrator::kRk4;
  const SolveResult r = HamiltonianDescent().Solve(*ocp, req);
  ExpectArmijoHistory(r);
  EXPECT_GT(r.iterations, 0);
  EXPECT_LT(r.objective, 0.05 * r.history[0].J);
  const Evaluation ev = Evaluate(*ocp, r.controls, r.state_grid, Integrator::kRk4);
  EXPECT_NEAR(ev.J, r.objective, 1e-9 * r.objective);
}

// The states-only bound only skips trials that would fail: the iterates, accepted exponents and
// costs are identical with and without it, and it does skip trials on the paper's problem.
TEST(HamiltonianDescent, ArmijoPrefilterChangesNothingButTheWork) {
  const auto ocp = PaperProblem();
  ASSERT_TRUE(ocp->RunningCostLowerBound().has_value());
  const SolveResult with =
      HamiltonianDescent().Solve(*ocp, DescentRequest(*ocp, 200, {{"max_iterations", "40"}}));
  const SolveResult without = HamiltonianDescent().Solve(
      *ocp, DescentRequest(*ocp, 200, {{"max_iterations", "40"}, {"armijo_prefilter", "0"}}));
  ASSERT_EQ(with.history.size(), without.history.size());
  for (size_t i = 0; i < with.history.size(); ++i) {
    EXPECT_EQ(with.history[i].J, without.history[i].J) << i;
    EXPECT_EQ(with.history[i].armijo_j, without.history[i].armijo_j) << i;
    EXPECT_EQ(with.history[i].theta, without.history[i].theta) << i;
  }
  EXPECT_EQ(with.controls.values(), without.controls.values());
  EXPECT_GT(with.solver_stats.at("prefilter_rejections"), 0.0);
  EXPECT_EQ(without.solver_stats.at("prefilter_rejections"), 0.0);
  EXPECT_EQ(with.solver_stats.at("simulations") + with.solver_stats.at("prefilter_rejections"),
            without.solver_stats.at("simulations"));
}

// The same on comm-fixed-path, which does not declare affine dynamics: the prefilter's general
// path (a states-only simulation per trial) instead of the affine one above.
TEST(HamiltonianDescent, ArmijoPrefilterWithoutTheAffineShortcut) {
  const auto ocp = MakeProblem("comm-fixed-path", {"channel=0"}, 1);
  ASSERT_TRUE(ocp->RunningCostLowerBound().has_value());
  ASSERT_FALSE(ocp->HasAffineDynamics());
  const SolveResult with =
      HamiltonianDescent().Solve(*ocp, DescentRequest(*ocp, 100, {{"max_iterations", "30"}}));
  const SolveResult without = HamiltonianDescent().Solve(
      *ocp, DescentRequest(*ocp, 100, {{"max_iterations", "30"}, {"armijo_prefilter", "0"}}));
  ASSERT_EQ(with.history.size(), without.history.size());
  for (size_t i = 0; i < with.history.size(); ++i) {
    EXPECT_EQ(with.history[i].J, without.history[i].J) << i;
    EXPECT_EQ(with.history[i].armijo_j, without.history[i].armijo_j) << i;
  }
  EXPECT_GT(with.solver_stats.at("prefilter_rejections"), 0.0);
}

// ---- every stopping reason ----------------------------------------------------------------------

TEST(HamiltonianDescentStops, ThetaBelowTolerance) {
  const auto ocp = MakeProblem("double-integrator", {"C=10"}, 0);
  const SolveResult r =
      HamiltonianDescent().Solve(*ocp, DescentRequest(*ocp, 20, {{"theta_tolerance", "1e6"}}));
  EXPECT_EQ(r.status, SolveStatus::kConverged);
  EXPECT_EQ(r.solver_status, "theta_below_tolerance");
  EXPECT_EQ(r.iterations, 0);
  // A tolerance reached after some iterations.
  const SolveResult r2 =
      HamiltonianDescent().Solve(*ocp, DescentRequest(*ocp, 20, {{"theta_tolerance", "1e-6"}}));
  EXPECT_EQ(r2.solver_status, "theta_below_tolerance");
  EXPECT_GT(r2.iterations, 0);
  EXPECT_LE(std::abs(r2.history.back().theta), 1e-6);
  EXPECT_GT(std::abs(r2.history[r2.history.size() - 2].theta), 1e-6);
}

TEST(HamiltonianDescentStops, ArmijoExponentExceeded) {
  // With C = 1000 the full step to u* = -p2 overshoots by far; allowing only j = 0 must fail.
  const auto ocp = MakeProblem("double-integrator", {"C=1000"}, 0);
  const SolveResult r =
      HamiltonianDescent().Solve(*ocp, DescentRequest(*ocp, 20, {{"max_armijo_exponent", "0"}}));
  EXPECT_EQ(r.status, SolveStatus::kStepTooSmall);
  EXPECT_EQ(r.solver_status, "armijo_exponent_exceeded");
  EXPECT_EQ(r.iterations, 0);
  EXPECT_EQ(r.history.size(), 1u);
  EXPECT_EQ(r.controls.values().cols(), 20);  // the last iterate is still returned
}

TEST(HamiltonianDescentStops, MaxCpuSeconds) {
  const auto ocp = PaperProblem();
  const SolveResult r =
      HamiltonianDescent().Solve(*ocp, DescentRequest(*ocp, 400, {{"max_cpu_seconds", "1e-9"}}));
  EXPECT_EQ(r.status, SolveStatus::kMaxTime);
  EXPECT_EQ(r.solver_status, "max_cpu_seconds");
  EXPECT_EQ(r.iterations, 0);
}

// Small problems that exercise the failure paths.
template <bool kWrongMinimizer, bool kNanCost, int NC>
class ScalarOcp final : public AutoDiffOcp<ScalarOcp<kWrongMinimizer, kNanCost, NC>, 1, 1, 1, NC> {
 public:
  ScalarOcp() {
    this->SetDimensions(1, 1, 1, NC);
    this->SetHorizon(0.0, 1.0);
    this->SetInitialState(Vec::Constant(1, kNanCost ? -1.0 : 1.0));
  }
  std::string name() const override { return "scalar"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>& x, const VecT<T, 1>& u) const {
    if constexpr (kNanCost) return sqrt(x[0]) + u[0] * u[0];
    return u[0] * u[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 1>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[0];
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 1>& x, const VecT<T, 1>&, VecT<T, NC>* c) const {
    (*c)[0] = x[0] - 10.0;
  }
  bool HasHamiltonianMinimizer() const override { return true; }
  void MinimizeHamiltonian(double, ConstVecRef, ConstVecRef p, VecRef u) const override {
    u[0] = kWrongMinimizer ? p[0] : -0.5 * p[0];  // argmin p u + u^2 is -p/2
  }
};

TEST(HamiltonianDescentStops, NonfiniteCost) {
  const ScalarOcp<false, true, 0> ocp;
  const SolveResult r = HamiltonianDescent().Solve(ocp, DescentRequest(ocp, 10));
  EXPECT_EQ(r.status, SolveStatus::kNumericalFailure);
  EXPECT_EQ(r.solver_status, "nonfinite_cost");
}

TEST(HamiltonianDescentStops, ThetaPositiveWhenTheMinimizerIsWrong) {
  const ScalarOcp<true, false, 0> ocp;
  const SolveResult r = HamiltonianDescent().Solve(ocp, DescentRequest(ocp, 10));
  EXPECT_EQ(r.status, SolveStatus::kError);
  EXPECT_EQ(r.solver_status, "theta_positive");
  // The correct minimizer on the same problem converges (theta -> 0 on a quadratic).
  const ScalarOcp<false, false, 0> good;
  const SolveResult ok =
      HamiltonianDescent().Solve(good, DescentRequest(good, 10, {{"theta_tolerance", "1e-12"}}));
  EXPECT_EQ(ok.status, SolveStatus::kConverged);
}

// At a stationary point theta is a sum of terms that are zero up to rounding, and it can come out
// as +1e-17. With the default theta_tolerance = 0 that must read as convergence, not as a wrong
// minimizer (it did on lqr and hager before the rounding test existed).
TEST(HamiltonianDescentStops, ThetaAtRoundoffIsConvergenceNotAnError) {
  for (const char* name : {"lqr", "hager"}) {
    const std::unique_ptr<Ocp> ocp = MakeProblem(name, {}, 1);
    const SolveResult r =
        HamiltonianDescent().Solve(*ocp, DescentRequest(*ocp, 100, {{"max_iterations", "20000"}}));
    // Both reach a stationary point well within the iteration limit (39 and 16 iterations when
    // this test was written); theta then ends at rounding level, whatever its sign.
    EXPECT_EQ(r.status, SolveStatus::kConverged) << name << ": " << r.message;
    EXPECT_LT(r.iterations, 20000) << name;
    EXPECT_LE(std::abs(r.solver_stats.at("final_theta")), 1e-12) << name;
  }
}

// ---- not applicable / invalid requests ----------------------------------------------------------

TEST(HamiltonianDescentNotApplicable, HardTerminalConstraints) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  SolveRequest req = DescentRequest(*ocp, 10);
  req.terminal = TerminalMode::kHard;
  const SolveResult r = HamiltonianDescent().Solve(*ocp, req);
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_NE(r.message.find("penalty"), std::string::npos);
  EXPECT_EQ(r.controls.nu(), 0);
}

TEST(HamiltonianDescentNotApplicable, PathConstraints) {
  const ScalarOcp<false, false, 1> ocp;
  const SolveResult r = HamiltonianDescent().Solve(ocp, DescentRequest(ocp, 10));
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_NE(r.message.find("path constraints"), std::string::npos);
}

// A problem with a path constraint whose Hamiltonian reformulation drops it (a stand-in for a
// penalty reformulation); it records the options the solver passed.
class ReformulatingOcp final : public AutoDiffOcp<ReformulatingOcp, 1, 1, 1, 1> {
 public:
  explicit ReformulatingOcp(HamiltonianReformulationOptions* seen) : seen_(seen) {
    SetDimensions(1, 1, 1, 1);
    SetInitialState(Vec::Constant(1, 1.0));
  }
  std::string name() const override { return "reformulating"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
  template <class T>
  void EvalTerminalConstraints(const VecT<T, 1>& x, VecT<T, 1>* psi) const {
    (*psi)[0] = x[0];
  }
  template <class T>
  void EvalPathConstraints(double, const VecT<T, 1>& x, const VecT<T, 1>&, VecT<T, 1>* c) const {
    (*c)[0] = x[0] - 10.0;
  }
  std::unique_ptr<Ocp> HamiltonianReformulation(
      const HamiltonianReformulationOptions& options) const override {
    *seen_ = options;
    return std::make_unique<ScalarOcp<false, false, 0>>();
  }

 private:
  HamiltonianReformulationOptions* seen_;
};

TEST(HamiltonianDescent, SolvesTheProblemsReformulationWhenItOffersOne) {
  HamiltonianReformulationOptions seen;
  const ReformulatingOcp ocp(&seen);
  const SolveResult r = HamiltonianDescent().Solve(
      ocp, DescentRequest(ocp, 10, {{"path_penalty", "250"}, {"theta_tolerance", "1e-12"}}));
  EXPECT_EQ(r.status, SolveStatus::kConverged) << r.message;
  EXPECT_NE(r.message.find("reformulation 'scalar'"), std::string::npos) << r.message;
  EXPECT_EQ(r.solver_stats.at("reformulated"), 1.0);
  ASSERT_TRUE(seen.path_penalty.has_value());
  EXPECT_EQ(*seen.path_penalty, 250.0);
  EXPECT_FALSE(seen.regularization.has_value());
  EXPECT_THROW(HamiltonianDescent().Solve(ocp, DescentRequest(ocp, 10, {{"path_penalty", "-1"}})),
               std::invalid_argument);
}

class NoMinimizerOcp final : public AutoDiffOcp<NoMinimizerOcp, 1, 1> {
 public:
  NoMinimizerOcp() { SetDimensions(1, 1, 0, 0); }
  std::string name() const override { return "no-minimizer"; }
  template <class T>
  void EvalDynamics(double, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = u[0];
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
};

TEST(HamiltonianDescentNotApplicable, NoHamiltonianMinimizer) {
  const NoMinimizerOcp ocp;
  const SolveResult r = HamiltonianDescent().Solve(ocp, DescentRequest(ocp, 10));
  EXPECT_EQ(r.status, SolveStatus::kNotApplicable);
  EXPECT_NE(r.message.find("Hamiltonian minimizer"), std::string::npos);
}

TEST(HamiltonianDescentInvalid, RequestsThatThrow) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  SolveRequest req = DescentRequest(*ocp, 10);
  req.grid = TimeGrid::Uniform(0.0, 2.0, 10);
  EXPECT_THROW(HamiltonianDescent().Solve(*ocp, req), std::invalid_argument);
  req = DescentRequest(*ocp, 10);
  req.initial_guess = ControlTrajectory::Constant(req.grid, Vec::Zero(2));
  EXPECT_THROW(HamiltonianDescent().Solve(*ocp, req), std::invalid_argument);
  req = DescentRequest(*ocp, 10, {{"gamma", "1"}});
  EXPECT_THROW(HamiltonianDescent().Solve(*ocp, req), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
