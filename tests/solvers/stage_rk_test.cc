// Runge-Kutta schemes with one control per stage: Hager's order conditions for the tableaux, the
// transformed adjoint's gradient against finite differences, and the family's descent on them
// converging at the scheme's order (solvers/README-family.md).
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/costate_error.h"
#include "core/discrete_ocp.h"
#include "core/rk_tableau.h"
#include "core/stage_rk_ocp.h"
#include "problems/registry.h"
#include "solvers/hamiltonian_family.h"
#include "solvers/stage_descent_passes.h"
#include "solvers/stage_newton.h"

namespace ocpb {
namespace {

// ---- order conditions -----------------------------------------------------------------------

TEST(RkTableau, HagerOrderOfTheFamilysTableaux) {
  EXPECT_EQ(RkTableau::ForwardEuler().Check(), "");
  EXPECT_EQ(RkTableau::Heun().Check(), "");
  EXPECT_EQ(RkTableau::Classical4().Check(), "");
  EXPECT_EQ(HagerOrder(RkTableau::ForwardEuler()), 1);
  EXPECT_EQ(HagerOrder(RkTableau::Heun()), 2);
  EXPECT_EQ(HagerOrder(RkTableau::Classical4()), 4);
  // Classical RK4 meets all twelve conditions of order <= 4, the four with d_i / b_i included.
  for (const OrderCondition& oc : HagerOrderConditions(RkTableau::Classical4())) {
    EXPECT_NEAR(oc.value, oc.expected, 1e-15) << oc.formula;
  }
  // Heun meets orders 1 and 2 and fails order 3 (sum c_i d_i = 0, not 1/6).
  for (const OrderCondition& oc : HagerOrderConditions(RkTableau::Heun())) {
    if (oc.order <= 2) {
      EXPECT_NEAR(oc.value, oc.expected, 1e-15) << oc.formula;
    }
    if (oc.formula == "sum c_i d_i = 1/6") {
      EXPECT_EQ(oc.value, 0.0);
    }
  }
}

TEST(RkTableau, CheckRejectsAZeroWeightAndImplicitTableaux) {
  // The explicit midpoint rule has b_1 = 0: no transformed adjoint with a control at stage 1.
  const RkTableau midpoint{"midpoint", 2, {0.0, 0.0, 0.5, 0.0}, {0.0, 1.0}, {0.0, 0.5}};
  EXPECT_NE(midpoint.Check().find("b_i must be > 0"), std::string::npos);
  const RkTableau implicit{"implicit-euler", 1, {1.0}, {1.0}, {1.0}};
  EXPECT_NE(implicit.Check().find("not explicit"), std::string::npos);
  EXPECT_THROW(StageRkOcp(*MakeProblem("hager", {}, 1),
                          TimeGrid::Uniform(0.0, 1.0, 4),
                          midpoint,
                          TerminalMode::kPenalty),
               std::invalid_argument);
}

// ---- the discrete gradient -------------------------------------------------------------------

Mat RandomControls(int nu, int cols, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  Mat U(nu, cols);
  for (int j = 0; j < cols; ++j) {
    for (int r = 0; r < nu; ++r) U(r, j) = dist(rng);
  }
  return U;
}

// dJ/du_{k,i} from the transformed adjoint against central differences of J, every stage control
// of a random U (relative to the largest component), and lambda_0 = dJ/dx0 is not tested here
// (x0 is fixed) but lambda_N = grad Phi is the start of the same sweep.
void ExpectGradientMatchesDifferences(const std::string& problem_name, const RkTableau& tableau) {
  SCOPED_TRACE(problem_name + ", " + tableau.name);
  const std::unique_ptr<Ocp> ocp = MakeProblem(problem_name, {}, 1);
  const int N = 8;
  const StageRkOcp srk(
      *ocp, TimeGrid::Uniform(ocp->t0(), ocp->tf(), N), tableau, TerminalMode::kPenalty);
  Mat U = RandomControls(ocp->nu(), srk.controls(), 7);
  for (int j = 0; j < U.cols(); ++j) ocp->control_set().Project(U.col(j));
  Mat X, Lambda, Y, P, G;
  const double J = srk.Simulate(U, &X);
  ASSERT_TRUE(std::isfinite(J));
  srk.Adjoint(U, X, &Lambda, &Y, &P, &G);
  ASSERT_EQ(G.cols(), srk.controls());
  const double scale = std::max(G.cwiseAbs().maxCoeff(), 1e-12);
  double worst = 0.0;
  for (int j = 0; j < U.cols(); ++j) {
    for (int r = 0; r < U.rows(); ++r) {
      const double step = 1e-6 * std::max(1.0, std::abs(U(r, j)));
      Mat Up = U, Um = U;
      Up(r, j) += step;
      Um(r, j) -= step;
      const double fd = (srk.Simulate(Up, nullptr) - srk.Simulate(Um, nullptr)) / (2.0 * step);
      worst = std::max(worst, std::abs(fd - G(r, j)) / scale);
    }
  }
  EXPECT_LT(worst, 1e-7);
  // The gradient is h b_i H_u at the stage with the stage costate (the formula of StageRkOcp).
  Vec f(ocp->nx()), Lx(ocp->nx()), Lu(ocp->nu());
  Mat fx(ocp->nx(), ocp->nx()), fu(ocp->nx(), ocp->nu());
  double L = 0.0;
  for (int k = 0; k < N; ++k) {
    for (int i = 0; i < srk.stages(); ++i) {
      const int col = k * srk.stages() + i;
      const double t = srk.StageTime(k, i);
      ocp->DynamicsJacobian(t, Y.col(col), U.col(col), f, fx, fu);
      ocp->RunningCostGradient(t, Y.col(col), U.col(col), &L, Lx, Lu);
      const Vec Hu = fu.transpose() * P.col(col) + Lu;
      EXPECT_LT((srk.StageWeight(k, i) * Hu - G.col(col)).cwiseAbs().maxCoeff(), 1e-12 * scale);
    }
  }
  // The node costates: lambda_N = grad Phi(x_N); the stage states' first stage is x_k.
  for (int k = 0; k < N; ++k) EXPECT_EQ(Y.col(k * srk.stages()), X.col(k));
}

TEST(StageRkOcp, GradientMatchesFiniteDifferencesRk2) {
  for (const char* p : {"hager", "lqr", "vanderpol", "double-integrator"}) {
    ExpectGradientMatchesDifferences(p, RkTableau::Heun());
  }
}

TEST(StageRkOcp, GradientMatchesFiniteDifferencesRk4) {
  for (const char* p : {"hager", "lqr", "vanderpol", "double-integrator"}) {
    ExpectGradientMatchesDifferences(p, RkTableau::Classical4());
  }
}

// dJ/dh_k of StageRkOcp::Adjoint (the free final time's ingredient) against central differences
// of J on a grid with h_k moved (the later nodes shifted), and dJ/dT = sum_k (h_k / T) dJ/dh_k
// against J on the stretched grid; autonomous problems, rk2 and rk4, and Euler's H(x_k, u_k,
// lambda_{k+1}).
TEST(StageRkOcp, StepDerivativeMatchesFiniteDifferences) {
  for (const char* name : {"double-integrator-free-time", "vanderpol"}) {
    const std::unique_ptr<Ocp> ocp = MakeProblem(name, {}, 1);
    for (const RkTableau& tableau :
         {RkTableau::ForwardEuler(), RkTableau::Heun(), RkTableau::Classical4()}) {
      SCOPED_TRACE(std::string(name) + ", " + tableau.name);
      const int N = 6;
      const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), N);
      const StageRkOcp srk(*ocp, grid, tableau, TerminalMode::kPenalty);
      const Mat U = RandomControls(ocp->nu(), srk.controls(), 11);
      Mat X, Lambda, Y, P, G;
      Vec dJdh;
      srk.Simulate(U, &X);
      srk.Adjoint(U, X, &Lambda, &Y, &P, &G, &dJdh);
      ASSERT_EQ(dJdh.size(), N);
      const double d = 1e-6;
      double dJdT = 0.0;
      for (int k = 0; k < N; ++k) {
        dJdT += grid.h(k) / (grid.tf() - grid.t0()) * dJdh[k];
        auto J_with = [&](double delta) {
          std::vector<double> points = grid.points();
          for (int j = k + 1; j <= N; ++j) points[static_cast<size_t>(j)] += delta;
          return StageRkOcp(*ocp, TimeGrid::FromPoints(points), tableau, TerminalMode::kPenalty)
              .Simulate(U, nullptr);
        };
        const double fd = (J_with(d) - J_with(-d)) / (2.0 * d);
        EXPECT_NEAR(dJdh[k], fd, 1e-6 * std::max(1.0, std::abs(fd))) << "k = " << k;
      }
      auto J_at = [&](double T) {
        return StageRkOcp(*ocp, grid.StretchedTo(T), tableau, TerminalMode::kPenalty)
            .Simulate(U, nullptr);
      };
      const double fd = (J_at(grid.tf() + d) - J_at(grid.tf() - d)) / (2.0 * d);
      EXPECT_NEAR(dJdT, fd, 1e-6 * std::max(1.0, std::abs(fd)));
    }
  }
}

// A free final time on the stage controls: T moves, the result's grid ends at it, and J falls.
TEST(HamiltonianFamilyScheme, FreeFinalTimeMovesT) {
  const std::unique_ptr<Ocp> ft = MakeProblem("double-integrator-free-time", {}, 1);
  SolveRequest r;
  r.grid = TimeGrid::Uniform(ft->t0(), ft->tf(), 20);
  r.options = {{"scheme", "rk4"}, {"max_iterations", "300"}};
  const SolveResult s = HamiltonianFamily(HamiltonianFamily::Preset::kProximal).Solve(*ft, r);
  ASSERT_NE(s.status, SolveStatus::kNotApplicable) << s.message;
  ASSERT_TRUE(s.solver_stats.count("final_time"));
  const double T = s.solver_stats.at("final_time");
  EXPECT_GT(std::abs(T - ft->tf()), 1e-3);
  EXPECT_EQ(s.state_grid.tf(), T);
  EXPECT_TRUE(std::isfinite(s.solver_stats.at("dJdT")));
  ASSERT_FALSE(s.history.empty());
  EXPECT_LT(s.objective, s.history.front().J);
}

TEST(StageRkOcp, OneStageTableauIsForwardEuler) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("vanderpol", {}, 1);
  const TimeGrid grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 16);
  const StageRkOcp srk(*ocp, grid, RkTableau::ForwardEuler(), TerminalMode::kPenalty);
  const DiscreteOcp euler(*ocp, grid, Integrator::kEuler, TerminalMode::kPenalty);
  const Mat U = RandomControls(1, 16, 3);
  Mat X1, X2, L1, L2, G1, G2, Y, P;
  const double J1 = srk.Simulate(U, &X1), J2 = euler.Simulate(U, &X2);
  EXPECT_NEAR(J1, J2, 1e-14 * std::abs(J2));
  EXPECT_LT((X1 - X2).cwiseAbs().maxCoeff(), 1e-14);
  srk.Adjoint(U, X1, &L1, &Y, &P, &G1);
  euler.Adjoint(U, X2, &L2, &G2);
  EXPECT_LT((L1 - L2).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT((G1 - G2).cwiseAbs().maxCoeff(), 1e-14);
  // Euler's stage costate is lambda_{k+1}.
  EXPECT_LT((P - L1.rightCols(16)).cwiseAbs().maxCoeff(), 1e-13);
}

// The family's polish on the stage controls (StageNewton: Newton on dJ/dU = 0 by conjugate
// gradients with Hessian-vector products from central differences of the exact gradient): the
// discrete optimum to rounding (the descent stops where
// Armijo can no longer see a decrease of J, controls to ~1e-8), to separate the scheme's order
// from the descent's floor.
Mat RefineToStationary(const StageRkOcp& srk, Mat U) {
  StageNewtonOptions options;
  options.tolerance = 1e-14;
  options.max_iterations = 20;
  const StageNewtonOutcome out = StageNewton(srk, srk.ocp().control_set(), options, {}, &U);
  // 1e-14 can be below what rounding allows: Newton then ends at its limit or stall, close.
  EXPECT_TRUE(out.converged || out.residual < 1e-11) << out.why;
  return U;
}

double Slope(const std::vector<int>& Ns, const std::vector<double>& e) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = static_cast<double>(Ns.size());
  for (size_t i = 0; i < Ns.size(); ++i) {
    const double x = std::log(static_cast<double>(Ns[i])), y = std::log(e[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  return -(n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// ---- the family's descent on the schemes ------------------------------------------------------

SolveResult SolveFamily(const Ocp& ocp,
                        int N,
                        const std::string& scheme,
                        const std::string& direction = "paper",
                        int max_iterations = 5000) {
  SolveRequest r;
  r.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  r.options = {{"scheme", scheme},
               {"direction", direction},
               {"max_iterations", std::to_string(max_iterations)},
               {"relative_theta_tolerance", "0"}};
  return HamiltonianFamily(HamiltonianFamily::Preset::kProximal).Solve(ocp, r);
}

double HagerCost() { return (std::exp(3.0) - 1.0) / (2.0 + std::exp(3.0)); }

TEST(HamiltonianFamilyScheme, OptionParsesAndEulerIsTheDefault) {
  EXPECT_EQ(HamiltonianFamilyOptions().scheme, HamiltonianFamilyOptions::Scheme::kEuler);
  for (auto preset : {HamiltonianFamily::Preset::kProximal,
                      HamiltonianFamily::Preset::kAugmentedLagrangian,
                      HamiltonianFamily::Preset::kPolish}) {
    EXPECT_EQ(HamiltonianFamily::Defaults(preset).scheme, HamiltonianFamilyOptions::Scheme::kEuler);
    const auto o = HamiltonianFamily::ApplyOptions(
        preset, {{"scheme", "rk4"}}, HamiltonianFamily::Defaults(preset));
    EXPECT_EQ(o.scheme, HamiltonianFamilyOptions::Scheme::kRk4);
  }
  try {
    HamiltonianFamily::ApplyOptions(
        HamiltonianFamily::Preset::kProximal, {{"scheme", "rk3"}}, HamiltonianFamily::Proximal());
    ADD_FAILURE() << "scheme=rk3 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("scheme"), std::string::npos) << e.what();
  }
}

TEST(HamiltonianFamilyScheme, NotApplicableCasesNameTheOption) {
  const std::unique_ptr<Ocp> di = MakeProblem("double-integrator", {}, 1);
  SolveRequest r;
  r.grid = TimeGrid::Uniform(di->t0(), di->tf(), 20);
  r.options = {{"scheme", "rk2"}};
  r.integrator = Integrator::kRk4;
  SolveResult s = HamiltonianFamily(HamiltonianFamily::Preset::kProximal).Solve(*di, r);
  EXPECT_EQ(s.status, SolveStatus::kNotApplicable);
  EXPECT_NE(s.message.find("scheme=rk2"), std::string::npos) << s.message;
  // Path constraints by the outer loop (hamiltonian-al's default path option).
  const std::unique_ptr<Ocp> bd = MakeProblem("bryson-denham", {}, 0);
  r = SolveRequest();
  r.grid = TimeGrid::Uniform(bd->t0(), bd->tf(), 20);
  r.options = {{"scheme", "rk4"}};
  s = HamiltonianFamily(HamiltonianFamily::Preset::kAugmentedLagrangian).Solve(*bd, r);
  EXPECT_EQ(s.status, SolveStatus::kNotApplicable);
  EXPECT_NE(s.message.find("scheme=rk4"), std::string::npos) << s.message;
  // The polish on the stage controls keeps the horizon fixed.
  const std::unique_ptr<Ocp> free_time = MakeProblem("double-integrator-free-time", {}, 1);
  r = SolveRequest();
  r.grid = TimeGrid::Uniform(free_time->t0(), free_time->tf(), 20);
  r.options = {{"scheme", "rk4"}};
  s = HamiltonianFamily(HamiltonianFamily::Preset::kPolish).Solve(*free_time, r);
  EXPECT_EQ(s.status, SolveStatus::kNotApplicable);
  EXPECT_NE(s.message.find("free final time needs scheme=euler"), std::string::npos) << s.message;
}

// The hard terminal form by the outer loop on the stage controls: the double integrator's
// psi = x(1) = 0 to the loop's tolerance, J and the multipliers nu = p*(1) = (-12, 6) of the
// continuous optimum (u* = 6 - 12t, J* = 6): RK4's J to 1e-6, Heun's within O(h^2).
TEST(HamiltonianFamilyScheme, HardTerminalFormByTheOuterLoop) {
  const std::unique_ptr<Ocp> di = MakeProblem("double-integrator", {}, 1);
  for (const char* scheme : {"rk2", "rk4"}) {
    SCOPED_TRACE(scheme);
    SolveRequest r;
    r.grid = TimeGrid::Uniform(di->t0(), di->tf(), 20);
    r.terminal = TerminalMode::kHard;
    r.options = {{"scheme", scheme}, {"max_iterations", "20000"}};
    const SolveResult s =
        HamiltonianFamily(HamiltonianFamily::Preset::kAugmentedLagrangian).Solve(*di, r);
    ASSERT_EQ(s.status, SolveStatus::kConverged) << s.message;
    EXPECT_EQ(s.solver_status, "al_converged");
    EXPECT_LE(s.solver_stats.at("terminal_residual"), 1e-8);
    // Heun at N = 20: J = 5.9701 (0.5% low); the multipliers to the loop's accuracy.
    const bool rk4 = std::string(scheme) == "rk4";
    EXPECT_NEAR(s.objective, 6.0, rk4 ? 1e-6 : 0.05);
    const double relative = rk4 ? 1e-4 : 2e-2;
    EXPECT_NEAR(s.solver_stats.at("nu_0"), -12.0, 12.0 * relative);
    EXPECT_NEAR(s.solver_stats.at("nu_1"), 6.0, 6.0 * relative);
  }
}

// The scheme's controls at its stages from a result's control trajectory (exact for Heun, whose
// stage abscissae 0 and 1 are the interpolation's nodes; RK4's two midpoint stages get their
// mean).
Mat StageControlsOf(const SolveResult& r, const StageRkOcp& srk) {
  Mat U(r.controls.nu(), srk.controls());
  for (int k = 0; k < srk.intervals(); ++k) {
    for (int i = 0; i < srk.stages(); ++i) {
      // Heun's last stage is at t_{k+1}: the interval's own (left) limit there.
      U.col(k * srk.stages() + i) =
          r.controls(srk.StageTime(k, i),
                     i > 0 && srk.tableau().c[static_cast<size_t>(i)] == 1.0
                         ? ControlTrajectory::Side::kLeft
                         : ControlTrajectory::Side::kRight);
    }
  }
  return U;
}

// On Hager's problem (closed-form J*, p*) the error in J falls by ~2^p per doubling of N, and so
// does the node costates' (p = 2: Heun, p = 4: classical RK4), for both directions. The descent
// ends where Armijo no longer sees J decrease (controls to ~1e-8, so costates to ~1e-9): RK4's
// costate order is checked on the discrete optimum refined from the descent's controls
// (RefineToStationary), whose J the descent's matches.
TEST(HamiltonianFamilyScheme, HagerConvergesAtTheSchemesOrder) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("hager", {}, 1);
  const auto pstar = FindProblem("hager").reference_costate;
  struct Case {
    const char* scheme;
    const char* direction;
    double low, high;  // the accepted range of error(N) / error(2N)
  };
  for (const Case& c : {Case{"rk2", "paper", 3.6, 4.4},
                        Case{"rk4", "paper", 13.0, 19.0},
                        Case{"rk2", "proximal", 3.6, 4.4},
                        Case{"rk4", "proximal", 13.0, 19.0}}) {
    SCOPED_TRACE(std::string(c.scheme) + ", " + c.direction);
    const bool rk4 = std::string(c.scheme) == "rk4";
    std::vector<double> ej, ep;
    for (int N : {25, 50, 100}) {
      const SolveResult r = SolveFamily(*ocp, N, c.scheme, c.direction);
      ASSERT_TRUE(r.status == SolveStatus::kConverged || r.status == SolveStatus::kStepTooSmall)
          << r.message;
      EXPECT_EQ(r.solver_stats.at("stage_controls"), N * (rk4 ? 4 : 2));
      ej.push_back(std::abs(r.objective - HagerCost()));
      if (!rk4) {
        ep.push_back(RelativeCostateError(r.costates, r.state_grid, pstar));
        continue;
      }
      EXPECT_LT(RelativeCostateError(r.costates, r.state_grid, pstar), 1e-7);
      const StageRkOcp srk(*ocp, r.state_grid, RkTableau::Classical4(), TerminalMode::kPenalty);
      const Mat U = RefineToStationary(srk, StageControlsOf(r, srk));
      Mat X, Lambda, Y, P, G;
      EXPECT_NEAR(srk.Simulate(U, &X), r.objective, 1e-13);
      srk.Adjoint(U, X, &Lambda, &Y, &P, &G);
      ep.push_back(RelativeCostateError(Lambda, r.state_grid, pstar));
    }
    for (size_t i = 0; i + 1 < ej.size(); ++i) {
      EXPECT_GT(ej[i] / ej[i + 1], c.low) << ej[i] << " " << ej[i + 1];
      EXPECT_LT(ej[i] / ej[i + 1], c.high) << ej[i] << " " << ej[i + 1];
      EXPECT_GT(ep[i] / ep[i + 1], c.low) << ep[i] << " " << ep[i + 1];
      EXPECT_LT(ep[i] / ep[i + 1], c.high) << ep[i] << " " << ep[i + 1];
    }
  }
}

// The descent on the stage controls ends at the discrete optimum: the gradient of the scheme's J
// vanishes there (to the descent's floor) and the result's J is the scheme's discrete J.
TEST(HamiltonianFamilyScheme, DescentEndsAtTheDiscreteStationaryPoint) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("vanderpol", {}, 1);
  const SolveResult r = SolveFamily(*ocp, 20, "rk4");
  ASSERT_TRUE(r.status == SolveStatus::kConverged || r.status == SolveStatus::kStepTooSmall)
      << r.message;
  EXPECT_EQ(r.controls.interpolation(), ControlTrajectory::Interpolation::kCustom);
  EXPECT_EQ(r.states.cols(), 21);
  EXPECT_EQ(r.costates.cols(), 21);
  EXPECT_NEAR(r.objective, 1.0478069082, 1e-4);  // the continuous J*, rk4 at N = 20
}

// ---- the measured orders (solvers/README-family.md, results/notes/2026-12-06-family-rk.md)
// -------

// Prints the table of the note: N against |J - J*| and the node costates' max error, for the
// family's descent (what the method returns) and for the scheme's discrete optimum refined by
// RefineToStationary. Run: build-test/tests/solvers_test
//   --gtest_also_run_disabled_tests --gtest_filter='FamilyRkOrders.DISABLED_Table'
TEST(FamilyRkOrders, DISABLED_Table) {
  const std::vector<int> Ns{25, 50, 100, 200, 400};
  struct Reference {
    double J;
    std::function<Vec(double)> p;
  };
  for (const char* name : {"hager", "lqr", "vanderpol"}) {
    const std::unique_ptr<Ocp> ocp = MakeProblem(name, {}, 1);
    Reference ref;
    if (std::string(name) == "hager") {
      ref = {HagerCost(), FindProblem("hager").reference_costate};
    } else if (std::string(name) == "lqr") {
      // J* = 1/2 x0^T P(0) x0 = 1/2 x0^T p*(0) (p = P x), from the matrix-exponential costate.
      const auto p = FindProblem("lqr").reference_costate;
      ref = {0.5 * ocp->x0().dot(p(0.0)), p};
    } else {
      // Self-convergence: the rk4 discrete optimum at N = 3200 (its error ~ (400/3200)^4 of
      // the N = 400 one), costates at its nodes.
      const int Nref = 3200;
      const StageRkOcp srk(*ocp,
                           TimeGrid::Uniform(ocp->t0(), ocp->tf(), Nref),
                           RkTableau::Classical4(),
                           TerminalMode::kPenalty);
      const SolveResult r = SolveFamily(*ocp, 400, "rk4");
      Mat U(1, srk.controls());
      for (int k = 0; k < Nref; ++k) {
        for (int i = 0; i < 4; ++i) {
          U(0, 4 * k + i) = r.controls(srk.StageTime(k, i), ControlTrajectory::Side::kRight)(0);
        }
      }
      U = RefineToStationary(srk, U);
      Mat X, Lambda, Y, P, G;
      const double J = srk.Simulate(U, &X);
      srk.Adjoint(U, X, &Lambda, &Y, &P, &G);
      const double h = (ocp->tf() - ocp->t0()) / Nref;
      const double t0 = ocp->t0();
      ref = {J, [Lambda, h, t0](double t) -> Vec {
               return Lambda.col(static_cast<int>(std::lround((t - t0) / h)));
             }};
      std::printf("vanderpol reference: rk4, N = %d: J = %.15f (registry 1.0478069082)\n", Nref, J);
    }
    for (const char* scheme : {"euler", "rk2", "rk4"}) {
      std::vector<double> ej, ep, rj, rp;
      for (int N : Ns) {
        const SolveResult r = SolveFamily(*ocp, N, scheme, "paper", 20000);
        ej.push_back(std::abs(r.objective - ref.J));
        ep.push_back(RelativeCostateError(r.costates, r.state_grid, ref.p));
        if (std::string(scheme) == "euler") {
          rj.push_back(NAN);
          rp.push_back(NAN);
          continue;
        }
        const StageRkOcp srk(
            *ocp,
            r.state_grid,
            std::string(scheme) == "rk2" ? RkTableau::Heun() : RkTableau::Classical4(),
            TerminalMode::kPenalty);
        // From the descent's controls (StageControlsOf).
        const Mat U = RefineToStationary(srk, StageControlsOf(r, srk));
        Mat X, Lambda, Y, P, G;
        rj.push_back(std::abs(srk.Simulate(U, &X) - ref.J));
        srk.Adjoint(U, X, &Lambda, &Y, &P, &G);
        rp.push_back(RelativeCostateError(Lambda, r.state_grid, ref.p));
      }
      std::printf(
          "\n%s, %s\n| N | descent |J - J*| | descent costate err | optimum |J - J*| | "
          "optimum costate err |\n|---|---|---|---|---|\n",
          name,
          scheme);
      for (size_t i = 0; i < Ns.size(); ++i) {
        std::printf("| %d | %.3e | %.3e | %.3e | %.3e |\n", Ns[i], ej[i], ep[i], rj[i], rp[i]);
      }
      std::printf("| slope | %.2f | %.2f | %.2f | %.2f |\n",
                  Slope(Ns, ej),
                  Slope(Ns, ep),
                  Slope(Ns, rj),
                  Slope(Ns, rp));
    }
  }
}

// Heun's J error on lqr falls faster than h^2 on N = 25..400 (slope 2.7): the discrete
// optimum's |J - J*| further out, to see the asymptotic rate. Run as DISABLED_Table.
TEST(FamilyRkOrders, DISABLED_LqrHeunFurther) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("lqr", {}, 1);
  const auto p = FindProblem("lqr").reference_costate;
  const double J = 0.5 * ocp->x0().dot(p(0.0));
  std::printf("lqr J* = %.15f (registry %.10f)\n", J, 0.6739990459);
  std::printf("| N | optimum |J - J*| | optimum costate err |\n|---|---|---|\n");
  for (int N : {400, 800, 1600, 3200, 6400}) {
    const SolveResult r = SolveFamily(*ocp, N, "rk2", "paper", 20000);
    const StageRkOcp srk(*ocp, r.state_grid, RkTableau::Heun(), TerminalMode::kPenalty);
    const Mat U = RefineToStationary(srk, StageControlsOf(r, srk));
    Mat X, Lambda, Y, P, G;
    const double e = std::abs(srk.Simulate(U, &X) - J);
    srk.Adjoint(U, X, &Lambda, &Y, &P, &G);
    std::printf("| %d | %.3e | %.3e |\n", N, e, RelativeCostateError(Lambda, r.state_grid, p));
  }
}

}  // namespace
}  // namespace ocpb
