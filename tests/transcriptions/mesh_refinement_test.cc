// Adaptive h-refinement (transcriptions/mesh_refinement.h, solvers/mesh_refinement_loop.h):
// the refinement rule, the options' validation, the mesh history's invariants and stops, and
// the gain on a problem with corners (the double integrator with |u| <= 5).
#include "transcriptions/mesh_refinement.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "problems/registry.h"
#include "solvers/judge.h"
#include "solvers/registry.h"
#include "transcriptions/mesh_error.h"
#include "transcriptions/registry.h"

namespace ocpb {
namespace {

TEST(MeshRefinement, NodesToAddFollowsTheEstimatesOrder) {
  // error / tol = 8 with order 3: two pieces of error 1 each, so one node.
  EXPECT_EQ(NodesToAdd(8.0, 1.0, 3, 5), 1);
  // error / tol = 64, order 3: four pieces; order 4 (Hermite-Simpson): ceil(64^(1/4)) = 3.
  EXPECT_EQ(NodesToAdd(64.0, 1.0, 3, 5), 3);
  EXPECT_EQ(NodesToAdd(64.0, 1.0, 4, 5), 2);
  // Barely above the tolerance still adds one; far above is capped.
  EXPECT_EQ(NodesToAdd(1.0001, 1.0, 3, 5), 1);
  EXPECT_EQ(NodesToAdd(1e9, 1.0, 3, 5), 5);
  EXPECT_EQ(NodesToAdd(1e300, 1e-300, 3, 2), 2);
  // At or below the tolerance, or not a number: nothing.
  EXPECT_EQ(NodesToAdd(1.0, 1.0, 3, 5), 0);
  EXPECT_EQ(NodesToAdd(std::numeric_limits<double>::quiet_NaN(), 1.0, 3, 5), 0);
}

TEST(MeshRefinement, RefineMeshSplitsOnlyTheFailingIntervalsEqually) {
  const TimeGrid mesh = TimeGrid::FromPoints({0.0, 0.2, 0.6, 1.0});
  Vec errors(3);
  errors << 0.5, 27.0, 1.0;  // tol 1, order 3: interval 1 into 3 pieces
  const TimeGrid refined = RefineMesh(mesh, errors, 1.0, 3, 5);
  const std::vector<double> expected = {0.0, 0.2, 0.2 + 0.4 / 3, 0.2 + 0.8 / 3, 0.6, 1.0};
  ASSERT_EQ(refined.size(), static_cast<int>(expected.size()));
  for (int k = 0; k < refined.size(); ++k) EXPECT_NEAR(refined.t(k), expected[k], 1e-15);
  EXPECT_THROW(RefineMesh(mesh, Vec::Zero(2), 1.0, 3, 5), std::invalid_argument);
}

// Each bad value is refused by the schema in one line naming the option and its rule.
TEST(MeshRefinement, OptionsAreValidatedByTheSchema) {
  EXPECT_TRUE(MeshRefinementOptions{}.IsValid(nullptr));
  EXPECT_FALSE(MeshRefinementOptions{}.enabled());  // default: no refinement
  struct Bad {
    const char* key;
    OptionValue value;
    const char* rule;
  };
  // A named array, not a braced list in the loop: GCC 12 at -O3 reports a false
  // -Wmaybe-uninitialized for the variant inside the temporaries of the braced list.
  const std::vector<Bad> bad_values = {Bad{"mesh_tolerance", -1e-3, ">= 0"},
                                       Bad{"mesh_max_iterations", 0, ">= 1"},
                                       Bad{"mesh_max_nodes", 1, ">= 2"},
                                       Bad{"mesh_max_new_points", 0, ">= 1"},
                                       Bad{"mesh_max_nodes", 2.5, "integer"}};
  for (const char* scheme : {"trapezoid", "hermite-simpson"}) {
    const TranscriptionInfo& info = FindTranscription(scheme);
    for (const Bad& bad : bad_values) {
      OptionMap given;
      given.Set(bad.key, bad.value);
      try {
        info.Configure(given);
        ADD_FAILURE() << scheme << ": " << bad.key << " accepted";
      } catch (const std::invalid_argument& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find(bad.key), std::string::npos) << what;
        EXPECT_NE(what.find(bad.rule), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      }
    }
    OptionMap good;
    good.Set("mesh_tolerance", 1e-6);
    good.Set("mesh_max_nodes", 300);
    const TranscriptionOptions o = info.Configure(good);
    EXPECT_EQ(o.mesh.tolerance, 1e-6);
    EXPECT_EQ(o.mesh.max_nodes, 300);
    EXPECT_EQ(o.mesh.max_iterations, MeshRefinementOptions{}.max_iterations);
  }
  // Options built in code go through the same rules (TranscriptionOptions::IsValid).
  TranscriptionOptions code;
  code.grid = TimeGrid::Uniform(0, 1, 4);
  code.mesh.max_nodes = 0;
  std::string why;
  EXPECT_FALSE(code.IsValid(&why));
  EXPECT_NE(why.find("mesh_max_nodes"), std::string::npos) << why;
  // Schemes without an estimate do not take the options (lgr's ph-refinement: its own test).
  OptionMap on;
  on.Set("mesh_tolerance", 1e-6);
  EXPECT_THROW(FindTranscription("euler").Configure(on), std::invalid_argument);
  EXPECT_THROW(FindTranscription("single-shooting").Configure(on), std::invalid_argument);
}

SolveRequest MeshRequest(const Ocp& ocp,
                         const std::string& scheme,
                         int N,
                         double tolerance,
                         OptionMap mesh_options = {}) {
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  request.terminal = TerminalMode::kHard;
  request.transcription = scheme;
  request.transcription_options = std::move(mesh_options);
  if (tolerance > 0) request.transcription_options.Set("mesh_tolerance", tolerance);
  request.options = {{"tol", "1e-10"}};
  return request;
}

double LargestUniformEstimate(const Ocp& ocp, const std::string& scheme, int N) {
  OptionMap once;
  once.Set("mesh_max_iterations", 1);
  const SolveResult r =
      FindSolver("ipopt").make()->Solve(ocp, MeshRequest(ocp, scheme, N, 1e-300, once));
  EXPECT_EQ(r.status, SolveStatus::kConverged) << scheme << " N " << N;
  return r.mesh_history.at(0).max_error;
}

// Tolerance 0 (the default) is the uniform grid as before: no mesh fields at all.
TEST(MeshRefinement, DefaultIsOneSolveOnTheGivenGrid) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("hager", {}, 1);
  const SolveResult r =
      FindSolver("ipopt").make()->Solve(*ocp, MeshRequest(*ocp, "trapezoid", 20, 0));
  EXPECT_EQ(r.status, SolveStatus::kConverged);
  EXPECT_TRUE(r.mesh_history.empty());
  EXPECT_TRUE(r.mesh_stop_reason.empty());
  EXPECT_EQ(r.mesh.size(), 0);
  EXPECT_EQ(r.solver_stats.count("mesh_iterations"), 0u);
}

// The switching times of u* = clip(6.4549722 - 12.9099445 t, -5, 5) (reference-problems.md 2.2).
const double kCorners[] = {0.1127017, 0.8872983};

double DistanceToCorner(double t) {
  return std::min(std::abs(t - kCorners[0]), std::abs(t - kCorners[1]));
}

SolveResult RefineFromTen(const Ocp& ocp, const std::string& scheme, double tol) {
  const SolveResult r = FindSolver("ipopt").make()->Solve(ocp, MeshRequest(ocp, scheme, 10, tol));
  EXPECT_EQ(r.status, SolveStatus::kConverged) << r.message;
  EXPECT_EQ(r.mesh_stop_reason, "tolerance_met") << r.message;
  return r;
}

// Mean interval length of `mesh` over the intervals whose midpoint satisfies `inside`, and over
// the others.
std::pair<double, double> MeanLengths(const TimeGrid& mesh,
                                      const std::function<bool(double)>& inside) {
  double in_sum = 0, out_sum = 0;
  int in = 0, out = 0;
  for (int k = 0; k < mesh.intervals(); ++k) {
    if (inside(mesh.t(k) + 0.5 * mesh.h(k))) {
      in_sum += mesh.h(k);
      ++in;
    } else {
      out_sum += mesh.h(k);
      ++out;
    }
  }
  EXPECT_GT(in, 0);
  EXPECT_GT(out, 0);
  return {in_sum / std::max(in, 1), out_sum / std::max(out, 1)};
}

class MeshOnCorners : public ::testing::TestWithParam<const char*> {};

// From 10 intervals to the tolerance on the double integrator with |u| <= 5 (two corners of
// u*): the history's invariants, the evaluator judging the final mesh, and fewer nodes than the
// uniform grid reaching the same largest estimate.
TEST_P(MeshOnCorners, HistoryIsMonotoneAndRefinementNeedsFewerNodesThanUniform) {
  const std::string scheme = GetParam();
  const std::unique_ptr<Ocp> ocp = MakeProblem("double-integrator-bounded", {}, 1);
  const double tol = scheme == "trapezoid" ? 1e-5 : 1e-7;
  const SolveResult r = RefineFromTen(*ocp, scheme, tol);
  ASSERT_GE(r.mesh_history.size(), 2u);

  // History: meshes grow strictly, each solve converged, the last meets the tolerance and no
  // earlier one did; iterations add up; the final row is the result's solve.
  int iterations = 0;
  for (size_t i = 0; i < r.mesh_history.size(); ++i) {
    const MeshIterationRecord& row = r.mesh_history[i];
    EXPECT_EQ(row.status, SolveStatus::kConverged) << i;
    if (i > 0) {
      EXPECT_GT(row.intervals, r.mesh_history[i - 1].intervals) << i;
      EXPECT_GT(row.nlp_variables, r.mesh_history[i - 1].nlp_variables) << i;
    }
    EXPECT_EQ(row.max_error <= tol, i + 1 == r.mesh_history.size()) << i << " " << row.max_error;
    EXPECT_GE(row.cpu_seconds, 0.0);
    iterations += row.iterations;
  }
  EXPECT_EQ(r.iterations, iterations);
  EXPECT_EQ(r.mesh_history.back().intervals, r.mesh.intervals());
  EXPECT_EQ(r.mesh_history.back().solver_status, r.solver_status);
  ASSERT_FALSE(r.history.empty());
  EXPECT_EQ(r.history.back().iteration, r.iterations);
  for (size_t i = 1; i < r.history.size(); ++i) {
    EXPECT_GE(r.history[i].iteration, r.history[i - 1].iteration);
    EXPECT_GE(r.history[i].cpu_seconds, r.history[i - 1].cpu_seconds);
  }

  // The evaluator judges the final mesh.
  const Judgement j = JudgeResult(*ocp, MeshRequest(*ocp, scheme, 10, tol), r);
  ASSERT_TRUE(j.judged);
  EXPECT_EQ(j.grid.points(), r.mesh.points());

  // No uniform grid with as many intervals or fewer (from 4) reaches the refined mesh's
  // largest estimate: every one is solved, so no monotonicity in N is assumed.
  const double refined_error = r.mesh_history.back().max_error;
  for (int N = 4; N <= r.mesh.intervals(); ++N) {
    EXPECT_GT(LargestUniformEstimate(*ocp, scheme, N), refined_error)
        << scheme << ": uniform N = " << N << " reaches the estimate " << refined_error
        << " of the refined mesh's " << r.mesh.intervals() << " intervals";
  }
}

INSTANTIATE_TEST_SUITE_P(Schemes,
                         MeshOnCorners,
                         ::testing::Values("trapezoid", "hermite-simpson"),
                         [](const auto& info) {
                           return std::string(info.param) == "trapezoid" ? "Trapezoid"
                                                                         : "HermiteSimpson";
                         });

// Hermite-Simpson's estimate sees the corners (the quadratic control bends across a kink of
// u*, and the defect of x1' = x2 is the cubic remainder of x2~, whose third derivative is
// u~''): the shortest interval is next to a corner, intervals within 0.05 of one are on
// average shorter than a third of the others, and the cost is within 1e-4 of the published
// optimum.
TEST(MeshRefinement, HermiteSimpsonNodesClusterAtTheCorners) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("double-integrator-bounded", {}, 1);
  const SolveResult r = RefineFromTen(*ocp, "hermite-simpson", 1e-7);
  const TimeGrid& mesh = r.mesh;
  ASSERT_GE(mesh.size(), 2);
  int shortest = 0;
  for (int k = 0; k < mesh.intervals(); ++k) {
    if (mesh.h(k) < mesh.h(shortest)) shortest = k;
  }
  EXPECT_LT(DistanceToCorner(mesh.t(shortest) + 0.5 * mesh.h(shortest)), 0.05);
  const auto lengths = MeanLengths(mesh, [](double t) { return DistanceToCorner(t) < 0.05; });
  EXPECT_LT(lengths.first, lengths.second / 3.0);
  EXPECT_LT(std::abs(r.objective - 6.0450277563) / 6.0450277563, 1e-4);
}

// The trapezoid's estimate does not see them: with x1' = x2, x2' = u and u~ linear, the x2
// defect vanishes identically and the x1 defect integrates to |u_k+1 - u_k| h^2 / 12, so the
// refinement goes where u changes (the unsaturated arc), not to the kinks of u*.
TEST(MeshRefinement, TrapezoidRefinesWhereTheControlChanges) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("double-integrator-bounded", {}, 1);
  const SolveResult r = RefineFromTen(*ocp, "trapezoid", 1e-5);
  ASSERT_GE(r.mesh.size(), 2);
  const auto lengths =
      MeanLengths(r.mesh, [](double t) { return t > kCorners[0] && t < kCorners[1]; });
  EXPECT_LT(lengths.first, lengths.second / 2.0);
}

// The limits stop the refinement and say so; the status stays the last solve's.
TEST(MeshRefinement, LimitsStopAndSaySo) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("double-integrator-bounded", {}, 1);
  const std::unique_ptr<Solver> ipopt = FindSolver("ipopt").make();
  {
    OptionMap o;
    o.Set("mesh_max_iterations", 2);
    const SolveResult r = ipopt->Solve(*ocp, MeshRequest(*ocp, "trapezoid", 10, 1e-12, o));
    EXPECT_EQ(r.mesh_stop_reason, "max_iterations");
    EXPECT_EQ(r.mesh_history.size(), 2u);
    EXPECT_GT(r.mesh_history.back().max_error, 1e-12);
    EXPECT_EQ(r.status, r.mesh_history.back().status);
    EXPECT_NE(r.message.find("max_iterations"), std::string::npos) << r.message;
  }
  {
    OptionMap o;
    o.Set("mesh_max_nodes", 30);
    const SolveResult r = ipopt->Solve(*ocp, MeshRequest(*ocp, "trapezoid", 10, 1e-12, o));
    EXPECT_EQ(r.mesh_stop_reason, "max_nodes");
    EXPECT_LE(r.mesh.size(), 30);
    EXPECT_GE(r.mesh_history.size(), 1u);
    EXPECT_NE(r.message.find("max_nodes"), std::string::npos) << r.message;
  }
  {
    // A first solve that fails is not refined, and its status is the result's.
    SolveRequest request = MeshRequest(*ocp, "hermite-simpson", 10, 1e-8);
    request.options = {{"max_iter", "2"}};
    const SolveResult r = ipopt->Solve(*ocp, request);
    EXPECT_EQ(r.status, SolveStatus::kMaxIterations);
    EXPECT_EQ(r.mesh_stop_reason, "solve_failed");
    ASSERT_EQ(r.mesh_history.size(), 1u);
    EXPECT_EQ(r.mesh_history[0].status, SolveStatus::kMaxIterations);
    EXPECT_TRUE(std::isnan(r.mesh_history[0].max_error));
  }
}

}  // namespace
}  // namespace ocpb
