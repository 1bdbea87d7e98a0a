// CPU limits that hold inside the Hamiltonian family and the indirect method: every loop (the
// Armijo search, Newton's line search and steps, the outer loop, the polish, grid sequencing)
// ends within one step's cost of max_cpu_seconds with status max_cpu_seconds. The CPU clock is a
// work counter (ScopedCpuClock): each evaluation of the problem costs kTick seconds, so the
// tests are deterministic and assert where the loops stopped, never how fast anything ran.
#include <cmath>
#include <limits>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "core/discrete_ocp.h"
#include "core/timer.h"
#include "problems/registry.h"
#include "solvers/forwarding_ocp.h"
#include "solvers/hamiltonian_descent.h"
#include "solvers/hamiltonian_family.h"
#include "solvers/indirect_newton.h"
#include "tests/solvers/indirect_test_support.h"

namespace ocpb {
namespace {

constexpr double kTick = 1e-4;  // fake CPU seconds per problem evaluation

// A problem that counts its evaluations (the fake clock's work) and returns a NaN running cost
// (and gradient) at every state that is not one of `healthy` (the start's states, once set):
// every Armijo or line-search trial then fails, as the most backtracking options make them fail,
// while the start and its sweeps stay finite.
class CountingOcp final : public ForwardingOcp {
 public:
  explicit CountingOcp(const Ocp& inner) : ForwardingOcp(inner) {}
  mutable long work = 0;
  Mat healthy;  // nx x n; empty: nothing is poisoned

  void Dynamics(double t, ConstVecRef x, ConstVecRef u, VecRef f) const override {
    ++work;
    ForwardingOcp::Dynamics(t, x, u, f);
  }
  double RunningCost(double t, ConstVecRef x, ConstVecRef u) const override {
    ++work;
    return Poisoned(x) ? NAN : ForwardingOcp::RunningCost(t, x, u);
  }
  void DynamicsJacobian(
      double t, ConstVecRef x, ConstVecRef u, VecRef f, MatRef fx, MatRef fu) const override {
    ++work;
    ForwardingOcp::DynamicsJacobian(t, x, u, f, fx, fu);
  }
  void RunningCostGradient(
      double t, ConstVecRef x, ConstVecRef u, double* L, VecRef Lx, VecRef Lu) const override {
    ++work;
    ForwardingOcp::RunningCostGradient(t, x, u, L, Lx, Lu);
    if (Poisoned(x)) *L = NAN;
  }
  void PointHessian(double t,
                    ConstVecRef x,
                    ConstVecRef u,
                    double sigma,
                    ConstVecRef lambda,
                    ConstVecRef mu,
                    MatRef hess) const override {
    ++work;
    ForwardingOcp::PointHessian(t, x, u, sigma, lambda, mu, hess);
  }
  void MinimizeHamiltonian(double t, ConstVecRef x, ConstVecRef p, VecRef u) const override {
    ++work;
    ForwardingOcp::MinimizeHamiltonian(t, x, p, u);
  }
  void MinimizeAndCompareHamiltonian(double t,
                                     ConstVecRef x,
                                     ConstVecRef p,
                                     ConstVecRef u,
                                     VecRef u_star,
                                     double* h_star,
                                     double* h_now,
                                     VecRef f) const override {
    ++work;
    ForwardingOcp::MinimizeAndCompareHamiltonian(t, x, p, u, u_star, h_star, h_now, f);
  }

 private:
  bool Poisoned(ConstVecRef x) const {
    if (healthy.cols() == 0) return false;
    for (int k = 0; k < healthy.cols(); ++k) {
      if ((healthy.col(k).array() == x.array()).all()) return false;
    }
    return true;
  }
};

// The Euler states of the solvers' start (the nominal controls) on `ocp`'s N-interval grid.
Mat StartStates(const Ocp& ocp, int N) {
  const TimeGrid grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  Mat U = DefaultInitialGuess(ocp, grid).values();
  for (int k = 0; k < U.cols(); ++k) ocp.control_set().Project(U.col(k));
  Mat X;
  DiscreteOcp(ocp, grid, Integrator::kEuler, TerminalMode::kPenalty).Simulate(U, &X);
  return X;
}

// The fake clock of `ocp`'s work for the life of the returned object.
std::unique_ptr<ScopedCpuClock> WorkClock(const CountingOcp& ocp) {
  return std::make_unique<ScopedCpuClock>([&ocp] { return kTick * ocp.work; });
}

// The documented extreme of the Armijo rule (max_armijo_exponent 10^8) with every trial
// failing: without the limit inside the search it ran 10^8 trials (each a simulation).
TEST(CpuLimit, ArmijoSearchOfTheDescentStopsAtTheFirstTrialAfterTheLimit) {
  const auto vdp = MakeProblem("vanderpol", {}, 0);
  const int N = 20;
  const double limit = 0.5;
  const double trial = 2.0 * N * kTick;  // N dynamics and N running costs
  for (const char* solver : {"hamiltonian", "hamiltonian-proximal", "hamiltonian-polish"}) {
    SCOPED_TRACE(solver);
    CountingOcp ocp(*vdp);
    ocp.healthy = StartStates(*vdp, N);  // every trial's cost is NaN
    const auto clock = WorkClock(ocp);
    const SolveRequest request = Request(ocp,
                                         N,
                                         TerminalMode::kPenalty,
                                         {{"max_armijo_exponent", "100000000"},
                                          {"armijo_prefilter", "false"},
                                          {"max_cpu_seconds", std::to_string(limit)}});
    const SolveResult r = std::string(solver) == "hamiltonian"
                              ? HamiltonianDescent().Solve(ocp, request)
                              : HamiltonianFamily(std::string(solver) == "hamiltonian-polish"
                                                      ? HamiltonianFamily::Preset::kPolish
                                                      : HamiltonianFamily::Preset::kProximal)
                                    .Solve(ocp, request);
    EXPECT_EQ(r.status, SolveStatus::kMaxTime) << r.message;
    EXPECT_EQ(r.solver_status, "max_cpu_seconds");
    EXPECT_NE(r.message.find("Armijo search"), std::string::npos) << r.message;
    EXPECT_GE(r.cpu_seconds, limit);
    EXPECT_LE(r.cpu_seconds, limit + 2.0 * trial) << r.message;
  }
}

// The outer loop of the augmented Lagrangian (hard form): its inner search ends at the limit
// and the loop reports it.
TEST(CpuLimit, AugmentedLagrangianLoopStopsWithItsInnerSearch) {
  const auto di = MakeProblem("double-integrator", {}, 0);
  const int N = 20;
  const double limit = 0.5;
  CountingOcp ocp(*di);
  ocp.healthy = StartStates(*di, N);
  const auto clock = WorkClock(ocp);
  const SolveResult r = HamiltonianFamily(HamiltonianFamily::Preset::kAugmentedLagrangian)
                            .Solve(ocp,
                                   Request(ocp,
                                           N,
                                           TerminalMode::kHard,
                                           {{"max_armijo_exponent", "100000000"},
                                            {"armijo_prefilter", "false"},
                                            {"max_cpu_seconds", std::to_string(limit)}}));
  EXPECT_EQ(r.status, SolveStatus::kMaxTime) << r.message;
  EXPECT_EQ(r.solver_status, "max_cpu_seconds");
  EXPECT_LE(r.cpu_seconds, limit + 4.0 * N * kTick) << r.message;
}

// Newton's line search with the documented extreme backtrack = 0.999999, min_step = 1e-10
// (2.3e7 trials per step) and every trial failing.
TEST(CpuLimit, NewtonLineSearchStopsAtTheFirstTrialAfterTheLimit) {
  const auto vdp = MakeProblem("vanderpol", {}, 0);
  const int N = 20;
  const double limit = 0.5;
  CountingOcp ocp(*vdp);
  const SolveRequest request = Request(ocp,
                                       N,
                                       TerminalMode::kPenalty,
                                       {{"backtrack", "0.999999"},
                                        {"min_step", "1e-10"},
                                        {"max_cpu_seconds", std::to_string(limit)}});
  Mat X, P;
  IndirectNewton::StartFromControls(
      ocp, request.grid, request.terminal, DefaultInitialGuess(ocp, request.grid), &X, &P);
  ocp.healthy = X;  // the start's residual is finite, every trial's NaN
  const auto clock = WorkClock(ocp);
  const SolveResult r = IndirectNewton().SolveFrom(ocp, request, X, P);
  EXPECT_EQ(r.status, SolveStatus::kMaxTime) << r.message;
  EXPECT_EQ(r.solver_status, "max_cpu_seconds");
  EXPECT_NE(r.message.find("line search"), std::string::npos) << r.message;
  // One trial: N + 1 minimizers with their gradients (3 evaluations each); the result's
  // controls after the stop another N + 1.
  EXPECT_LE(r.cpu_seconds, limit + 5.0 * (N + 1) * kTick) << r.message;
}

// The polish's Newton gets what is left of the family's limit: with the limit in the middle of
// the Newton phase of an unlimited run, the solve stops there (the polish ran Newton to its end
// before, 12.1 s for a 10 s limit).
TEST(CpuLimit, PolishAndGridSequencingStopWithinOneNewtonStep) {
  const auto vdp = MakeProblem("vanderpol", {}, 0);
  for (const int N : {40, 200}) {  // 200: grid-sequenced (100 -> 200)
    SCOPED_TRACE(N);
    double descent = 0.0, total = 0.0, newton_steps = 0.0;
    {
      CountingOcp ocp(*vdp);
      const auto clock = WorkClock(ocp);
      const SolveResult r = HamiltonianFamily(HamiltonianFamily::Preset::kPolish)
                                .Solve(ocp, Request(ocp, N, TerminalMode::kHard));
      ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
      descent = N == 200 ? r.solver_stats.at("coarse_cpu_seconds")
                         : r.solver_stats.at("descent_cpu_seconds");
      total = r.cpu_seconds;
      newton_steps = r.solver_stats.at("newton_iterations");
      ASSERT_GE(newton_steps, 2.0);
    }
    const double limit = descent + 0.5 * (total - descent);
    CountingOcp ocp(*vdp);
    const auto clock = WorkClock(ocp);
    const SolveResult r =
        HamiltonianFamily(HamiltonianFamily::Preset::kPolish)
            .Solve(
                ocp,
                Request(ocp, N, TerminalMode::kHard, {{"max_cpu_seconds", std::to_string(limit)}}));
    EXPECT_EQ(r.status, SolveStatus::kMaxTime) << r.message;
    EXPECT_EQ(r.solver_status, "max_cpu_seconds");
    EXPECT_LT(r.solver_stats.at("newton_iterations"), newton_steps);
    // One Newton step (a Jacobian, a trial) plus the result's controls and J: about 8 (N + 1)
    // evaluations.
    EXPECT_LE(r.cpu_seconds, limit + 12.0 * (N + 1) * kTick) << r.message;
  }
}

}  // namespace
}  // namespace ocpb
