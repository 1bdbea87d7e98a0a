// The reference problems as a family: registry entries, derivatives (AD and the hand-written
// penalty reformulation) against finite differences, the closed-form Hamiltonian minimizers
// against a brute-force search, and runtime registration.
#include "problems/reference/reference_problems.h"

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/derivative_check.h"
#include "problems/double_integrator.h"
#include "problems/reference/bryson_denham.h"
#include "problems/reference/catmix.h"
#include "problems/reference/path_penalty_ocp.h"
#include "problems/reference/rayleigh.h"
#include "problems/registry.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

const std::vector<std::string> kNames = {
    "bryson-denham", "lqr", "hager", "vanderpol", "rayleigh", "catmix"};

TEST(ReferenceProblems, AreRegisteredWithTheirReferenceValuesAndSources) {
  const std::map<std::string, double> expected = {{"bryson-denham", 4.0},
                                                  {"lqr", 0.6739990459},
                                                  {"hager", 0.8641644977691},
                                                  {"vanderpol", 1.0478069082},
                                                  {"rayleigh", 44.8044433},
                                                  {"catmix", -0.0480556}};
  for (const std::string& name : kNames) {
    SCOPED_TRACE(name);
    const ProblemInfo& info = FindProblem(name);
    ASSERT_TRUE(info.reference_value.has_value());
    EXPECT_EQ(*info.reference_value, expected.at(name));
    EXPECT_EQ(info.reference_quantity, "J");
    EXPECT_FALSE(info.reference_source.empty());
    EXPECT_FALSE(info.uses_seed);
    EXPECT_EQ(info.default_intervals, 100);
    const auto ocp = MakeProblem(name, {}, 0);
    EXPECT_EQ(ocp->name(), name);
  }
}

TEST(ReferenceProblems, OnlyProblemsThatNeedItHaveAHamiltonianReformulation) {
  for (const std::string& name : kNames) {
    SCOPED_TRACE(name);
    const auto ocp = MakeProblem(name, {}, 0);
    const auto re = ocp->HamiltonianReformulation({});
    const bool needs = ocp->num_path() > 0 || name == "catmix";
    EXPECT_EQ(re != nullptr, needs);
    EXPECT_EQ(FindProblem(name).hamiltonian_note.empty(), !needs);
    EXPECT_TRUE(ocp->HasHamiltonianMinimizer());
    if (!re) continue;
    // What the Hamiltonian method needs: no path constraints, a minimizer, same sizes and data.
    EXPECT_EQ(re->num_path(), 0);
    EXPECT_TRUE(re->HasHamiltonianMinimizer());
    EXPECT_EQ(re->nx(), ocp->nx());
    EXPECT_EQ(re->nu(), ocp->nu());
    EXPECT_EQ(re->num_terminal(), ocp->num_terminal());
    EXPECT_EQ(re->t0(), ocp->t0());
    EXPECT_EQ(re->tf(), ocp->tf());
    EXPECT_EQ(re->x0(), ocp->x0());
    EXPECT_EQ(re->terminal_weights(), ocp->terminal_weights());
  }
  // A catmix that is regularized already fits as stated.
  EXPECT_EQ(MakeProblem("catmix", {"eps=0.01"}, 0)->HamiltonianReformulation({}), nullptr);
}

TEST(ReferenceProblems, ReformulationOptionsOverrideTheParameters) {
  const auto bd = MakeProblem("bryson-denham", {"rho=50"}, 0);
  const auto by_param = bd->HamiltonianReformulation({});
  HamiltonianReformulationOptions o;
  o.path_penalty = 2e3;
  const auto by_option = bd->HamiltonianReformulation(o);
  EXPECT_EQ(dynamic_cast<const PathPenaltyOcp&>(*by_param).rho(), 50.0);
  EXPECT_EQ(dynamic_cast<const PathPenaltyOcp&>(*by_option).rho(), 2e3);
  // x1 = l + 0.1 with u = 0: L = rho * 0.01.
  const Eigen::Vector2d x(1.0 / 9.0 + 0.1, 0.0);
  EXPECT_NEAR(by_option->RunningCost(0.3, x, Vec::Zero(1)), 2e3 * 0.01, 1e-12);

  const auto cat = MakeProblem("catmix", {"hamiltonian_eps=0.02"}, 0);
  o.regularization = 0.5;
  EXPECT_EQ(dynamic_cast<const Catmix&>(*cat->HamiltonianReformulation({})).eps(), 0.02);
  EXPECT_EQ(dynamic_cast<const Catmix&>(*cat->HamiltonianReformulation(o)).eps(), 0.5);
  o.regularization = -1.0;
  EXPECT_THROW(cat->HamiltonianReformulation(o), std::invalid_argument);
  o.path_penalty = 0.0;
  EXPECT_THROW(bd->HamiltonianReformulation(o), std::invalid_argument);
}

// (t, x, u, lambda, mu, nu) drawn around the problem's scale.
struct Point {
  double t;
  Vec x, u, lambda, mu, nu;
};

Point RandomPoint(const Ocp& ocp, std::mt19937_64* rng) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Point p;
  p.t = ocp.t0() + 0.5 * (1.0 + unit(*rng)) * (ocp.tf() - ocp.t0());
  p.x = Vec(ocp.nx());
  for (int i = 0; i < ocp.nx(); ++i) p.x[i] = ocp.x0()[i] + 0.8 * unit(*rng);
  p.u = Vec(ocp.nu());
  for (int i = 0; i < ocp.nu(); ++i) p.u[i] = 0.5 + 0.4 * unit(*rng);  // inside catmix's [0, 1]
  p.lambda = Vec(ocp.nx());
  for (int i = 0; i < ocp.nx(); ++i) p.lambda[i] = 2.0 * unit(*rng);
  p.mu = Vec(ocp.num_path());
  for (int i = 0; i < ocp.num_path(); ++i) p.mu[i] = 1.0 + unit(*rng);
  p.nu = Vec(ocp.num_terminal());
  for (int i = 0; i < ocp.num_terminal(); ++i) p.nu[i] = 2.0 * unit(*rng);
  return p;
}

// ReferenceProblems' derivatives: tests/problems/registered_problems_test.cc checks every
// registered problem (these among them) by iterating the registry.

// The penalty reformulation's derivatives are hand-assembled (PathPenaltyOcp): check them where
// the constraint is active (c > 0, the penalty's second derivative is on) and inactive.
TEST(PathPenaltyOcp, DerivativesMatchFiniteDifferencesWithActiveAndInactiveConstraints) {
  HamiltonianReformulationOptions o;
  o.path_penalty = 37.0;  // moderate, so that finite differences stay accurate
  for (const char* name : {"bryson-denham", "rayleigh"}) {
    const auto ocp = MakeProblem(name, {}, 0);
    const auto re = ocp->HamiltonianReformulation(o);
    std::mt19937_64 rng(5);
    int active = 0, inactive = 0;
    for (int trial = 0; trial < 40 && (active < 4 || inactive < 4); ++trial) {
      Point p = RandomPoint(*ocp, &rng);
      // Spread x1 across the bound of each problem.
      std::uniform_real_distribution<double> spread(-6.0, 6.0);
      p.x[0] = std::string(name) == "rayleigh" ? spread(rng) : 1.0 / 9.0 + 0.05 * spread(rng);
      Vec c(1);
      ocp->PathConstraints(p.t, p.x, p.u, c);
      if (std::abs(c[0]) < 1e-3) continue;  // the kink of max(0, c)^2 is not for FD
      (c[0] > 0 ? active : inactive)++;
      const DerivativeCheck check = CheckOcpDerivatives(*re, p.t, p.x, p.u, p.lambda, Vec(0), p.nu);
      EXPECT_LT(check.max_error, 1e-6) << name << " c = " << c[0] << "\n" << check.log;
      // The penalized running cost is L + rho max(0, c)^2.
      EXPECT_NEAR(re->RunningCost(p.t, p.x, p.u),
                  ocp->RunningCost(p.t, p.x, p.u) + 37.0 * std::pow(std::max(c[0], 0.0), 2),
                  1e-12 * (1.0 + std::abs(re->RunningCost(p.t, p.x, p.u))));
    }
    EXPECT_GE(active, 4) << name;
    EXPECT_GE(inactive, 4) << name;
  }
}

TEST(PathPenaltyOcp, RejectsBadArguments) {
  const auto ocp = MakeProblem("bryson-denham", {}, 0);
  Parameters params(BrysonDenham::ParameterSpecs());
  EXPECT_THROW(PathPenaltyOcp(nullptr, 1.0), std::invalid_argument);
  EXPECT_THROW(PathPenaltyOcp(std::make_unique<BrysonDenham>(params), 0.0), std::invalid_argument);
  EXPECT_THROW(PathPenaltyOcp(std::make_unique<BrysonDenham>(params),
                              std::numeric_limits<double>::infinity()),
               std::invalid_argument);
  const PathPenaltyOcp ok(std::make_unique<BrysonDenham>(params), 3.0);
  EXPECT_EQ(ok.name(), "bryson-denham+penalty");
  EXPECT_EQ(ok.base().num_path(), 1);
}

// The closed-form minimizers are hand-written: u* must not be beaten by any u of a fine scan of
// U (clipped to [-50, 50] when unbounded), for random (t, x, p): H(u*) <= min over the scan.
void ExpectMinimizerIsExact(const Ocp& ocp,
                            int trials,
                            std::mt19937_64* rng,
                            const std::string& what) {
  ASSERT_TRUE(ocp.HasHamiltonianMinimizer()) << what;
  ASSERT_EQ(ocp.nu(), 1) << what;
  Vec lo, hi;
  ocp.control_set().BoundingBox(&lo, &hi);
  const double a = std::max(lo[0], -50.0), b = std::min(hi[0], 50.0);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int trial = 0; trial < trials; ++trial) {
    const double t = ocp.t0() + 0.5 * (1.0 + unit(*rng)) * (ocp.tf() - ocp.t0());
    Vec x(ocp.nx()), p(ocp.nx());
    for (int i = 0; i < ocp.nx(); ++i) {
      x[i] = ocp.x0()[i] + 2.0 * unit(*rng);
      p[i] = 3.0 * unit(*rng);
    }
    Vec u(1);
    ocp.MinimizeHamiltonian(t, x, p, u);
    ASSERT_LE(ocp.control_set().Violation(u), 0.0) << what;
    const double h_star = ocp.Hamiltonian(t, x, u, p);
    // A scan of [a, b], then a finer one around its best point (spacing 100 / 1000^2 = 1e-4).
    double best = std::numeric_limits<double>::infinity(), best_v = a;
    auto scan = [&](double lo, double hi) {
      const int n = 1000;
      for (int k = 0; k <= n; ++k) {
        const Vec v = Vec::Constant(1, lo + (hi - lo) * k / n);
        const double H = ocp.Hamiltonian(t, x, v, p);
        if (H < best) {
          best = H;
          best_v = v[0];
        }
      }
    };
    scan(a, b);
    const double step = (b - a) / 1000;
    scan(std::max(a, best_v - step), std::min(b, best_v + step));
    EXPECT_LE(h_star, best + 1e-9 * (1.0 + std::abs(best)))
        << what << ": u* = " << u[0] << " t = " << t << " x = " << x.transpose()
        << " p = " << p.transpose();
  }
}

// free-start's and double-integrator-time-parameter's minimizers exist only where H is convex in
// u (p2 > 0; T > 0): there u* beats every perturbation, elsewhere they answer NaN.
TEST(ReferenceProblems, MinimizersWhereHIsConvexAreExactAndNaNElsewhere) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (const std::string name : {"free-start", "double-integrator-time-parameter"}) {
    const auto ocp = MakeProblem(name, {}, 0);
    const int convex_index = name == "free-start" ? 1 : 2;  // p2, or the state T
    for (int trial = 0; trial < 20; ++trial) {
      Vec x(ocp->nx()), p(ocp->nx()), u(1);
      for (int i = 0; i < ocp->nx(); ++i) {
        x[i] = 2.0 * unit(rng);
        p[i] = 3.0 * unit(rng);
      }
      Vec& v = name == "free-start" ? p : x;
      v[convex_index] = 0.1 + std::abs(v[convex_index]);
      ocp->MinimizeHamiltonian(0.5, x, p, u);
      const double h_star = ocp->Hamiltonian(0.5, x, u, p);
      for (const double d : {-10.0, -1.0, -1e-3, 1e-3, 1.0, 10.0}) {
        EXPECT_LE(h_star, ocp->Hamiltonian(0.5, x, u + Vec::Constant(1, d), p)) << name;
      }
      v[convex_index] = -v[convex_index];
      ocp->MinimizeHamiltonian(0.5, x, p, u);
      EXPECT_TRUE(std::isnan(u[0])) << name;
    }
  }
}

TEST(ReferenceProblems, HamiltonianMinimizersAreExact) {
  std::mt19937_64 rng(3);
  for (const std::string& name : kNames) {
    const auto ocp = MakeProblem(name, {}, 0);
    ExpectMinimizerIsExact(*ocp, 12, &rng, name);
    if (const auto re = ocp->HamiltonianReformulation({})) {
      ExpectMinimizerIsExact(*re, 12, &rng, name + " reformulated");
    }
  }
  // catmix regularized by its own parameter, and Rayleigh with a weak and a strong penalty
  // (both branches of the piecewise minimizer).
  ExpectMinimizerIsExact(*MakeProblem("catmix", {"eps=0.05"}, 0), 12, &rng, "catmix eps=0.05");
  for (double rho : {0.5, 1e3}) {
    HamiltonianReformulationOptions o;
    o.path_penalty = rho;
    ExpectMinimizerIsExact(*MakeProblem("rayleigh", {}, 0)->HamiltonianReformulation(o),
                           12,
                           &rng,
                           "rayleigh rho=" + std::to_string(rho));
  }
}

TEST(Rayleigh, PenalizedMinimizerApproachesTheConstrainedOneAsRhoGrows) {
  // u*(rho) -> min(-2 p2, -x1/6) on both branches.
  for (const auto& [x1, p2] : {std::pair{3.0, -1.0}, std::pair{-3.0, 0.1}, std::pair{6.0, 0.5}}) {
    const double limit = std::min(-2.0 * p2, -x1 / 6.0);
    double previous = std::numeric_limits<double>::infinity();
    for (double rho : {1.0, 1e2, 1e4, 1e6}) {
      const double gap = std::abs(Rayleigh::PenalizedMinimizer(rho, x1, p2) - limit);
      EXPECT_LE(gap, previous);
      previous = gap;
    }
    EXPECT_LT(previous, 1e-5);
  }
}

// The "hamiltonian" solver solves a problem's reformulation by itself, with the reformulation
// options passed as solver options: the same run as on the reformulated problem directly.
TEST(ReferenceProblems, HamiltonianSolverSolvesTheReformulation) {
  for (const auto& [name, option, value] : {std::tuple{"bryson-denham", "path_penalty", 2e3},
                                            std::tuple{"rayleigh", "path_penalty", 50.0},
                                            std::tuple{"catmix", "regularization", 1e-3}}) {
    SCOPED_TRACE(name);
    const auto ocp = MakeProblem(name, {}, 0);
    HamiltonianReformulationOptions o;
    (std::string(option) == "path_penalty" ? o.path_penalty : o.regularization) = value;
    const auto re = ocp->HamiltonianReformulation(o);
    ASSERT_NE(re, nullptr);
    SolveRequest req;
    req.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 40);
    req.options = {{"max_iterations", "30"}};
    const SolveResult direct = FindSolver("hamiltonian").make()->Solve(*re, req);
    req.options.Set(option, std::to_string(value));
    const SolveResult through = FindSolver("hamiltonian").make()->Solve(*ocp, req);
    EXPECT_EQ(through.status, direct.status) << through.message;
    EXPECT_EQ(through.iterations, direct.iterations);
    EXPECT_EQ(through.objective, direct.objective);
    EXPECT_EQ(through.controls.values(), direct.controls.values());
  }
}

// ProblemInfo::hamiltonian_note is documentation; the solver decides from the problem itself.
// Every registered problem's note must agree with that verdict: "not applicable" exactly where
// the descent refuses (a stale note would tell users the wrong thing).
TEST(ProblemRegistry, EveryHamiltonianNoteAgreesWithTheSolversVerdict) {
  for (const ProblemInfo& info : Problems()) {
    SCOPED_TRACE(info.name);
    Parameters params(info.parameters);
    // make_for_checks: the same problem without its expensive parts (no channel simulated).
    const auto ocp = info.make_for_checks ? info.make_for_checks(params, 1) : info.make(params, 1);
    ASSERT_NE(ocp, nullptr);
    SolveRequest request;
    request.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 10);
    request.options.Set("max_iterations", 0);
    const SolveResult r = FindSolver("hamiltonian").make()->Solve(*ocp, request);
    const bool says_not_applicable =
        info.hamiltonian_note.find("not applicable") != std::string::npos;
    EXPECT_EQ(r.status == SolveStatus::kNotApplicable, says_not_applicable)
        << ToString(r.status) << ": " << r.message << " / note: " << info.hamiltonian_note;
  }
}

TEST(RegisterProblem, AddsAUserProblemAndRejectsDuplicatesAndEmptyEntries) {
  ProblemInfo info;
  info.name = "registry-test-double-integrator";
  info.parameters = DoubleIntegrator::ParameterSpecs(1e300);
  info.make = [](const Parameters& params, std::uint64_t) -> std::unique_ptr<Ocp> {
    return std::make_unique<DoubleIntegrator>(params, "registry-test-double-integrator");
  };
  info.reference_value = 6.0;
  // A complete entry (description, source, tags): the registry's consistency tests in this
  // binary may run after this one and see it.
  info.description = "double-integrator registered by a test";
  info.reference_source = "analytic (as double-integrator)";
  info.tags = {"smooth"};
  const size_t before = Problems().size();
  RegisterProblem(info);
  EXPECT_EQ(Problems().size(), before + 1);
  EXPECT_EQ(FindProblem(info.name).reference_value, 6.0);
  EXPECT_EQ(MakeProblem(info.name, {"C=5"}, 0)->terminal_weights()[0], 5.0);
  EXPECT_THROW(RegisterProblem(info), std::invalid_argument);  // taken
  ProblemInfo nameless = info;
  nameless.name = "";
  EXPECT_THROW(RegisterProblem(nameless), std::invalid_argument);
  ProblemInfo no_make = info;
  no_make.name = "registry-test-no-make";
  no_make.make = nullptr;
  EXPECT_THROW(RegisterProblem(no_make), std::invalid_argument);
  EXPECT_THROW(RegisterProblem(FindProblem("lqr")), std::invalid_argument);  // a built-in name
  ProblemInfo bad_tag = info;
  bad_tag.name = "registry-test-bad-tag";
  bad_tag.tags = {"smoth"};
  EXPECT_THROW(RegisterProblem(bad_tag), std::invalid_argument);  // a tag not in ProblemTags()
  EXPECT_EQ(Problems().size(), before + 1);
}

}  // namespace
}  // namespace ocpb
