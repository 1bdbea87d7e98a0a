// One table for the reference problems solved by the NLP solvers: Ipopt on every collocation
// transcription (hard terminal form) against the published optimum, and NLopt SLSQP against
// Ipopt on the same small NLP. Each row's tolerance is the accuracy measured for that scheme on
// that grid, rounded up (the measurements are in the rows' comments). A new reference problem
// adds rows here, not a new copy of the test.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "problems/reference/hager.h"
#include "problems/reference/lqr.h"
#include "problems/reference/rayleigh.h"
#include "problems/reference/vanderpol.h"
#include "problems/registry.h"
#include "tests/problems/reference_test_support.h"

namespace ocpb {
namespace {

using reference_testing::FineEvaluation;
using reference_testing::RelativeError;
using reference_testing::Request;
using reference_testing::SolveWith;
using reference_testing::SolveWithIpopt;

// What a row is judged on.
enum class Judged {
  kJbarFine,   ///< Jbar of the controls on a 10x finer RK4 grid (a continuous optimum)
  kObjective,  ///< the NLP's own objective (the minimum-time problems: J = tf at the optimum)
};

constexpr double kNone = -1.0;  // a check the row does not make

struct IpoptRow {
  const char* problem;
  const char* transcription;
  int N;
  double reference;
  double tolerance;  ///< on the relative error of what the row is judged on
  Judged judged = Judged::kJbarFine;
  double path_tolerance = kNone;    ///< the fine grid's path violation
  double objective_factor = kNone;  ///< also |objective - reference| < factor * tolerance
  bool exact_control_set = false;   ///< the fine grid's control violation is 0
  bool acceptable_counts = false;   ///< Ipopt's acceptable level counts as success
  const char* tol = nullptr;        ///< Ipopt's tol, when not its default
};

constexpr double kBrysonDenham = 4.0;  // 4 / (9 l), l = 1/9
// Catmix's continuous optimum, estimated by COPS' scheme at nh = 400 (reference_catmix_test.cc
// checks the approach); the methods are judged against it, not against the discrete COPS value.
constexpr double kCatmixContinuous = -0.0480556813;
constexpr double kBoundedDoubleIntegrator = 6.0450277563;

std::vector<IpoptRow> IpoptRows() {
  return {
      // Bryson-Denham: Euler is first order in the states (its controls miss x(1) by ~1e-2 on the
      // fine grid); trapezoid second order; Hermite-Simpson and LGR are limited by the junctions
      // of the boundary arc (the solution is only C^1 in u there), not by their smooth order.
      {"bryson-denham", "euler", 100, kBrysonDenham, 3e-3, Judged::kJbarFine, 1e-12, 4.0},
      {"bryson-denham", "trapezoid", 100, kBrysonDenham, 6e-4, Judged::kJbarFine, 1e-12, 4.0},
      {"bryson-denham", "hermite-simpson", 50, kBrysonDenham, 1e-6, Judged::kJbarFine, 1e-6, 4.0},
      {"bryson-denham", "lgr", 50, kBrysonDenham, 3e-6, Judged::kJbarFine, 2e-6, 4.0},
      // Catmix against its continuous estimate (the COPS value belongs to one discrete NLP).
      {"catmix", "euler", 50, kCatmixContinuous, 5e-3, Judged::kJbarFine, kNone, kNone, true, true},
      {"catmix",
       "trapezoid",
       100,
       kCatmixContinuous,
       5e-6,
       Judged::kJbarFine,
       kNone,
       kNone,
       true,
       true},
      {"catmix",
       "hermite-simpson",
       50,
       kCatmixContinuous,
       1.2e-3,
       Judged::kJbarFine,
       kNone,
       kNone,
       true,
       true},
      {"catmix", "lgr", 50, kCatmixContinuous, 2e-3, Judged::kJbarFine, kNone, kNone, true, true},
      // |u| <= 5: u* = clip(6.4549722 - 12.9099445 t, -5, 5) (CTProblems.jl). The kinks of u* at
      // t = 0.1127 and 0.8873 limit every scheme: Hermite-Simpson measured 1.3e-4 at N = 50 and
      // 1.0e-7 at N = 100 (whose mesh points 0.11 and 0.89 lie close to the kinks).
      {"double-integrator-bounded",
       "hermite-simpson",
       100,
       kBoundedDoubleIntegrator,
       5e-7,
       Judged::kJbarFine,
       kNone,
       kNone,
       true},
      {"hager", "euler", 100, Hager::kReferenceCost, 6e-5},
      {"hager", "trapezoid", 50, Hager::kReferenceCost, 6e-6},
      {"hager", "hermite-simpson", 25, Hager::kReferenceCost, 1.5e-8},
      {"hager", "lgr", 25, Hager::kReferenceCost, 1e-11},
      // LQR. Euler: first order in the states, second in J (measured 5.5e-3 at N = 100);
      // trapezoid 1.5e-5 at N = 100; Hermite-Simpson 1.1e-7 at N = 50; LGR 5.7e-9 at N = 25.
      {"lqr", "euler", 100, Lqr::kReferenceCost, 8e-3},
      {"lqr", "trapezoid", 100, Lqr::kReferenceCost, 3e-5},
      {"lqr", "hermite-simpson", 50, Lqr::kReferenceCost, 2e-7},
      {"lqr", "lgr", 25, Lqr::kReferenceCost, 1e-8},
      // Rayleigh (mixed constraint). Measured: Euler 7.4e-4 (N = 100), trapezoid 2.5e-4, Hermite-
      // Simpson 6.1e-6 (N = 50), LGR 1.8e-9 (N = 50; from N = 100 on LGR settles at 3.5e-8 above
      // Betts' 44.8044433, the difference to the PMP value 44.80444491: the reference's own
      // precision). The fine-grid path violation is the constraint along the re-simulated
      // states, which differ from the scheme's by its state error.
      {"rayleigh", "euler", 100, Rayleigh::kReferenceCost, 1.2e-3, Judged::kJbarFine, 5e-2},
      {"rayleigh", "trapezoid", 100, Rayleigh::kReferenceCost, 4e-4, Judged::kJbarFine, 1.5e-2},
      {"rayleigh", "hermite-simpson", 50, Rayleigh::kReferenceCost, 1e-5, Judged::kJbarFine, 5e-3},
      {"rayleigh", "lgr", 50, Rayleigh::kReferenceCost, 1e-7, Judged::kJbarFine, 5e-3},
      {"vanderpol", "euler", 100, VanDerPol::kReferenceCost, 1.3e-4},
      {"vanderpol", "trapezoid", 50, VanDerPol::kReferenceCost, 1.5e-5},
      {"vanderpol", "hermite-simpson", 25, VanDerPol::kReferenceCost, 2e-7},
      {"vanderpol", "lgr", 25, VanDerPol::kReferenceCost, 2e-10},
      // The minimum-time problems, time-scaled (J = tf at the optimum), Ipopt at tol 1e-12 (its
      // bound_relax_factor 1e-8 still loosens the cone |v|^2 <= sigma^2, which shortens tf by
      // about 7e-9 relative); judged on the NLP's own J, the value the scheme's optimum has.
      {"brachistochrone",
       "euler",
       100,
       0.824759143157,
       4e-3,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"brachistochrone",
       "trapezoid",
       100,
       0.824759143157,
       7e-6,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"brachistochrone",
       "hermite-simpson",
       25,
       0.824759143157,
       2e-8,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"brachistochrone",
       "lgr",
       10,
       0.824759143157,
       2e-8,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"zermelo",
       "euler",
       100,
       5.2649320661,
       5e-3,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"zermelo",
       "trapezoid",
       100,
       5.2649320661,
       9e-5,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"zermelo",
       "hermite-simpson",
       25,
       5.2649320661,
       2e-8,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"zermelo",
       "lgr",
       10,
       5.2649320661,
       2e-8,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"steering",
       "euler",
       100,
       0.5545708783,
       2e-6,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"steering",
       "trapezoid",
       100,
       0.5545708783,
       5e-5,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"steering",
       "hermite-simpson",
       25,
       0.5545708783,
       2e-8,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
      {"steering",
       "lgr",
       10,
       0.5545708783,
       2e-8,
       Judged::kObjective,
       kNone,
       kNone,
       false,
       false,
       "1e-12"},
  };
}

std::string RowName(const std::string& problem, const std::string& transcription, int N) {
  std::string n = problem + "_" + transcription + "_N" + std::to_string(N);
  for (char& ch : n) ch = ch == '-' ? '_' : ch;
  return n;
}

class IpoptReference : public ::testing::TestWithParam<IpoptRow> {};

TEST_P(IpoptReference, ReachesTheReference) {
  const IpoptRow c = GetParam();
  const auto ocp = MakeProblem(c.problem, {}, 0);
  SolveRequest request = Request(*ocp, c.N, TerminalMode::kHard, c.transcription);
  if (c.tol != nullptr) request.options.Set("tol", c.tol);
  const SolveResult r = SolveWith("ipopt", *ocp, request);
  if (c.acceptable_counts) {
    ASSERT_TRUE(IsSuccess(r.status)) << r.solver_status << " " << r.message;
  } else {
    ASSERT_EQ(r.status, SolveStatus::kConverged) << r.solver_status << " " << r.message;
  }
  if (c.judged == Judged::kObjective) {
    EXPECT_LT(RelativeError(r.objective, c.reference), c.tolerance) << "J = " << r.objective;
    return;
  }
  const Evaluation fine = FineEvaluation(*ocp, r, c.N);
  EXPECT_LT(RelativeError(fine.Jbar, c.reference), c.tolerance) << "Jbar_fine = " << fine.Jbar;
  if (c.path_tolerance != kNone) {
    EXPECT_LT(fine.path_violation, c.path_tolerance);
  }
  if (c.exact_control_set) {
    EXPECT_EQ(fine.control_violation, 0.0);
  }
  if (c.objective_factor != kNone) {
    // The NLP's own objective is the scheme's quadrature of the same cost.
    EXPECT_LT(RelativeError(r.objective, c.reference), c.objective_factor * c.tolerance)
        << "objective = " << r.objective;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Table, IpoptReference, ::testing::ValuesIn(IpoptRows()), [](const auto& info) {
      return RowName(info.param.problem, info.param.transcription, info.param.N);
    });

// NLopt's SLSQP solves the same NLP as Ipopt (the same transcription and grid, hard form):
// their objectives agree, and its controls reach the reference like Ipopt's.
struct NloptRow {
  const char* problem;
  const char* transcription;
  int N;
  double reference;
  double objective_agreement;  ///< |J_nlopt - J_ipopt| below this ...
  bool relative_to_ipopt;      ///< ... times |J_ipopt| when true
  double tolerance;            ///< on |Jbar_fine - reference| / |reference|
};

std::vector<NloptRow> NloptRows() {
  return {
      {"bryson-denham", "hermite-simpson", 20, kBrysonDenham, 1e-6, false, 2e-5},
      {"catmix", "trapezoid", 10, kCatmixContinuous, 1e-5, true, 5e-3},
      {"hager", "hermite-simpson", 20, Hager::kReferenceCost, 1e-8, false, 5e-8},  // 2.0e-8
      {"lqr", "hermite-simpson", 20, Lqr::kReferenceCost, 1e-7, false, 1e-5},      // 4.3e-6
      // Rayleigh at N = 20 (N = 40 is 10x slower for SLSQP's dense subproblems): the scheme's
      // error at N = 20 is 2.0e-4.
      {"rayleigh",
       "hermite-simpson",
       20,
       Rayleigh::kReferenceCost,
       1e-7 * Rayleigh::kReferenceCost,
       false,
       3e-4},
      {"vanderpol", "hermite-simpson", 20, VanDerPol::kReferenceCost, 1e-7, false, 6e-7},  // 3e-7
  };
}

class NloptSlsqpReference : public ::testing::TestWithParam<NloptRow> {};

TEST_P(NloptSlsqpReference, ReachesTheSameOptimumAsIpopt) {
  const NloptRow c = GetParam();
  const auto ocp = MakeProblem(c.problem, {}, 0);
  SolveRequest req = Request(*ocp, c.N, TerminalMode::kHard, c.transcription);
  req.options.Set("algorithm", "LD_SLSQP");
  const SolveResult nlopt = SolveWith("nlopt", *ocp, req);
  ASSERT_EQ(nlopt.status, SolveStatus::kConverged) << nlopt.solver_status << " " << nlopt.message;
  const SolveResult ipopt = SolveWithIpopt(*ocp, c.transcription, c.N);
  ASSERT_TRUE(IsSuccess(ipopt.status)) << ipopt.solver_status;
  const double agreement = c.relative_to_ipopt ? c.objective_agreement * std::abs(ipopt.objective)
                                               : c.objective_agreement;
  EXPECT_NEAR(nlopt.objective, ipopt.objective, agreement);
  EXPECT_LT(RelativeError(FineEvaluation(*ocp, nlopt, c.N).Jbar, c.reference), c.tolerance);
}

INSTANTIATE_TEST_SUITE_P(
    Table, NloptSlsqpReference, ::testing::ValuesIn(NloptRows()), [](const auto& info) {
      return RowName(info.param.problem, info.param.transcription, info.param.N);
    });

}  // namespace
}  // namespace ocpb
