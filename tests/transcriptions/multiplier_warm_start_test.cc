// Multiplier warm starts across meshes (transcriptions/multiplier_trajectories.h,
// CollocationNlp::MultiplierTrajectoriesAt / StartingMultipliers): the map is exact on the mesh
// it came from, it approaches the refined mesh's optimal multipliers as the mesh is refined,
// mesh refinement uses it when asked, and its option is validated.
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "problems/registry.h"
#include "solvers/ipopt_adapter.h"
#include "solvers/registry.h"
#include "transcriptions/collocation_nlp.h"
#include "transcriptions/registry.h"

namespace ocpb {
namespace {

struct WarmCase {
  const char* problem;
  const char* scheme;
  std::vector<int> degrees;  // LGR: one per interval (empty: `degree` on every one)
  int degree = 3;            // LGR
};

std::string WarmCaseName(const WarmCase& c) {
  std::string s = std::string(c.problem) + "_" + c.scheme;
  if (s.find("lgr") != std::string::npos && c.degrees.empty()) s += std::to_string(c.degree);
  for (char& ch : s) {
    if (ch == '-') ch = '_';
  }
  return s;
}

TranscriptionOptions WarmOptions(const Ocp& ocp, const WarmCase& c, int N) {
  TranscriptionOptions o;
  o.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  o.terminal = TerminalMode::kHard;
  o.degrees = c.degrees;
  o.degree = c.degree;
  return o;
}

std::unique_ptr<TranscribedNlp> WarmTranscribe(const Ocp& ocp,
                                               const std::string& scheme,
                                               const TranscriptionOptions& options) {
  return FindTranscription(scheme).make()->Transcribe(ocp, options);
}

NlpSolution WarmSolve(const Nlp& nlp) {
  IpoptOptions ipopt;
  ipopt.tol = 1e-11;
  return SolveNlpWithIpopt(nlp, nlp.StartingPoint(), ipopt);
}

// The largest |a_i - b_i| over the given indices, relative to the largest |b_i| there.
double RelativeDifference(const Vec& a, const Vec& b, const std::vector<int>& indices) {
  double diff = 0.0, size = 0.0;
  for (int i : indices) {
    diff = std::max(diff, std::abs(a[i] - b[i]));
    size = std::max(size, std::abs(b[i]));
  }
  return size > 0.0 ? diff / size : diff;
}

std::vector<int> IndexRange(int begin, int end) {
  std::vector<int> r;
  for (int i = begin; i < end; ++i) r.push_back(i);
  return r;
}

// The entries of z_lower / z_upper that belong to control blocks and a free final time (the
// bounded variables; x(t0) is fixed, Ipopt treats it as a parameter).
std::vector<int> BoundedVariables(const CollocationNlp& nlp) {
  std::vector<int> r;
  for (const auto& c : nlp.layout().controls) {
    for (int i = 0; i < nlp.layout().nu; ++i) r.push_back(c.offset + i);
  }
  if (nlp.HasFinalTimeVariable()) r.push_back(nlp.num_variables() - 1);
  return r;
}

class MultiplierMapOnTheSameMesh : public ::testing::TestWithParam<WarmCase> {};

// Trajectories from a solution, read back on the same mesh at the same z: every multiplier
// returns (the costate map inverted exactly; densities read at their own points). Cases cover
// path constraints (bryson-denham), control bounds (double-integrator-bounded), a free final
// time with its bounds (robot-arm), and LGR with mixed degrees.
TEST_P(MultiplierMapOnTheSameMesh, ReturnsTheMultipliersItCameFrom) {
  const WarmCase& c = GetParam();
  const std::unique_ptr<Ocp> ocp = MakeProblem(c.problem, {}, 1);
  const int N = c.degrees.empty() ? 8 : static_cast<int>(c.degrees.size());
  const std::unique_ptr<TranscribedNlp> nlp =
      WarmTranscribe(*ocp, c.scheme, WarmOptions(*ocp, c, N));
  const auto* collocation = dynamic_cast<const CollocationNlp*>(nlp.get());
  ASSERT_NE(collocation, nullptr);
  const NlpSolution sol = WarmSolve(*nlp);
  ASSERT_EQ(sol.status, SolveStatus::kConverged) << sol.message;
  const NlpMultipliers y{sol.lambda, sol.z_lower, sol.z_upper};
  const auto trajectories = nlp->MultiplierTrajectoriesAt(sol.z, y);
  ASSERT_TRUE(trajectories.has_value());
  const NlpMultipliers back = nlp->StartingMultipliers(sol.z, *trajectories);
  ASSERT_TRUE(back.Fits(nlp->num_variables(), nlp->num_constraints()));

  const int m = nlp->num_constraints();
  const int defects = collocation->path_row_begin();
  EXPECT_LT(RelativeDifference(back.lambda, sol.lambda, IndexRange(0, defects)), 1e-9);
  if (defects < m) {
    EXPECT_LT(RelativeDifference(back.lambda, sol.lambda, IndexRange(defects, m)), 1e-9);
  }
  const std::vector<int> bounded = BoundedVariables(*collocation);
  EXPECT_LT(RelativeDifference(back.z_lower, sol.z_lower, bounded), 1e-9);
  EXPECT_LT(RelativeDifference(back.z_upper, sol.z_upper, bounded), 1e-9);
  // The costates of the mapped multipliers are the trajectories' at the state points.
  const Mat P = nlp->Costates(sol.z, back.lambda);
  const Mat P0 = nlp->Costates(sol.z, sol.lambda);
  EXPECT_LT((P - P0).cwiseAbs().maxCoeff(), 1e-9 * std::max(1.0, P0.cwiseAbs().maxCoeff()));
}

INSTANTIATE_TEST_SUITE_P(
    Schemes,
    MultiplierMapOnTheSameMesh,
    ::testing::Values(WarmCase{"bryson-denham", "trapezoid", {}},
                      WarmCase{"bryson-denham", "hermite-simpson", {}},
                      WarmCase{"bryson-denham", "lgr", {3, 5, 2, 4, 3, 6}},
                      WarmCase{"double-integrator-bounded", "trapezoid", {}},
                      WarmCase{"double-integrator-bounded", "hermite-simpson", {}},
                      WarmCase{"double-integrator-bounded", "lgr", {4, 2, 3, 7, 3}},
                      WarmCase{"robot-arm", "hermite-simpson", {}},
                      WarmCase{"robot-arm", "lgr", {3, 4, 3, 5}}),
    [](const auto& info) { return WarmCaseName(info.param); });

}  // namespace
}  // namespace ocpb

namespace ocpb {
namespace {

// The multipliers of A's solution mapped to B = A with every interval halved, at B's starting
// point from A's solution (as mesh refinement starts it), against B's optimal multipliers: the
// largest difference over the defect rows, relative to their size.
double MappedDefectError(const Ocp& ocp, const WarmCase& c, int N) {
  WarmCase refined = c;
  TranscriptionOptions a = WarmOptions(ocp, c, N);
  const std::unique_ptr<TranscribedNlp> nlp_a = WarmTranscribe(ocp, c.scheme, a);
  const NlpSolution sol_a = WarmSolve(*nlp_a);
  EXPECT_EQ(sol_a.status, SolveStatus::kConverged) << sol_a.message;
  const auto trajectories =
      nlp_a->MultiplierTrajectoriesAt(sol_a.z, {sol_a.lambda, sol_a.z_lower, sol_a.z_upper});
  EXPECT_TRUE(trajectories.has_value());
  if (!trajectories) return NAN;

  TranscriptionOptions b = WarmOptions(ocp, c, 2 * N);
  b.initial_guess = nlp_a->Controls(sol_a.z);
  b.initial_states = nlp_a->StateTrajectory(sol_a.z);
  const std::unique_ptr<TranscribedNlp> nlp_b = WarmTranscribe(ocp, c.scheme, b);
  const Vec z0 = nlp_b->StartingPoint();
  const NlpMultipliers mapped = nlp_b->StartingMultipliers(z0, *trajectories);
  EXPECT_FALSE(mapped.empty());
  if (mapped.empty()) return NAN;
  const NlpSolution sol_b = WarmSolve(*nlp_b);
  EXPECT_EQ(sol_b.status, SolveStatus::kConverged) << sol_b.message;
  const int defects = dynamic_cast<const CollocationNlp&>(*nlp_b).path_row_begin();
  return RelativeDifference(mapped.lambda, sol_b.lambda, IndexRange(0, defects));
}

class MultiplierMapUnderRefinement : public ::testing::TestWithParam<WarmCase> {};

// On smooth problems the mapped defect multipliers approach B's optimal ones at the order of
// the schemes' costate estimates: measured slopes of the last halving (N = 32 -> 64) 1.95
// (trapezoid), 2.92 (Hermite-Simpson), 2.93 (LGR K = 3) on vanderpol; on hager 1.97, 2.99,
// 2.99 and 4.99 for LGR K = 5 (N = 16 -> 32: by N = 64 it is at Ipopt's tolerance). Asserted:
// each halving reduces the error, and the last one by at least 2^(q - 0.2), q = 2, 3, K.
TEST_P(MultiplierMapUnderRefinement, ApproachesTheRefinedMeshsOptimum) {
  const WarmCase& c = GetParam();
  const std::unique_ptr<Ocp> ocp = MakeProblem(c.problem, {}, 1);
  const std::string scheme = c.scheme;
  const double q = scheme == "trapezoid" ? 2.0 : scheme == "hermite-simpson" ? 3.0 : c.degree;
  std::vector<double> errors;
  for (int N = c.degree >= 5 ? 4 : 8; N <= (c.degree >= 5 ? 32 : 64); N *= 2) {
    errors.push_back(MappedDefectError(*ocp, c, N));
    ASSERT_TRUE(std::isfinite(errors.back()));
    if (errors.size() > 1) {
      EXPECT_LT(errors.back(), errors[errors.size() - 2]) << N;
    }
  }
  const double slope = std::log2(errors[errors.size() - 2] / errors.back());
  EXPECT_GT(slope, q - 0.2) << "errors " << errors[0] << " ... " << errors.back();
  RecordProperty("last_slope", std::to_string(slope));
}

INSTANTIATE_TEST_SUITE_P(Schemes,
                         MultiplierMapUnderRefinement,
                         ::testing::Values(WarmCase{"vanderpol", "trapezoid", {}},
                                           WarmCase{"vanderpol", "hermite-simpson", {}},
                                           WarmCase{"vanderpol", "lgr", {}},
                                           WarmCase{"hager", "trapezoid", {}},
                                           WarmCase{"hager", "hermite-simpson", {}},
                                           WarmCase{"hager", "lgr", {}},
                                           WarmCase{"hager", "lgr", {}, 5}),
                         [](const auto& info) { return WarmCaseName(info.param); });

SolveRequest WarmMeshRequest(const Ocp& ocp, const std::string& scheme, bool warm) {
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), 10);
  request.terminal = TerminalMode::kHard;
  request.transcription = scheme;
  request.transcription_options.Set("mesh_tolerance", 1e-7);
  request.transcription_options.Set("mesh_warm_multipliers", warm);
  request.options = {{"tol", "1e-10"}};
  return request;
}

// Mesh refinement with and without the multipliers: the same meshes and solution (the solves
// converge to the same optima), every mesh after the first offered mapped multipliers, and
// fewer Ipopt iterations on those meshes (on double-integrator-bounded, whose control bounds
// are where a primal-only start loses iterations: Ipopt re-centers every bound multiplier).
TEST(MeshWarmMultipliers, SameMeshesFewerIterationsOnCorners) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("double-integrator-bounded", {}, 1);
  const std::unique_ptr<Solver> ipopt = FindSolver("ipopt").make();
  for (const char* scheme : {"hermite-simpson", "lgr"}) {
    const SolveResult warm = ipopt->Solve(*ocp, WarmMeshRequest(*ocp, scheme, true));
    const SolveResult cold = ipopt->Solve(*ocp, WarmMeshRequest(*ocp, scheme, false));
    ASSERT_EQ(warm.status, SolveStatus::kConverged) << scheme << ": " << warm.message;
    ASSERT_EQ(cold.status, SolveStatus::kConverged) << scheme << ": " << cold.message;
    EXPECT_EQ(warm.mesh_stop_reason, "tolerance_met") << scheme;
    ASSERT_EQ(warm.mesh_history.size(), cold.mesh_history.size()) << scheme;
    ASSERT_GE(warm.mesh_history.size(), 3u) << scheme;
    int warm_iterations = 0, cold_iterations = 0;
    for (size_t i = 0; i < warm.mesh_history.size(); ++i) {
      EXPECT_EQ(warm.mesh_history[i].intervals, cold.mesh_history[i].intervals) << scheme << i;
      EXPECT_EQ(warm.mesh_history[i].degrees, cold.mesh_history[i].degrees) << scheme << i;
      if (i == 0) {
        EXPECT_EQ(warm.mesh_history[i].iterations, cold.mesh_history[i].iterations);
        continue;
      }
      warm_iterations += warm.mesh_history[i].iterations;
      cold_iterations += cold.mesh_history[i].iterations;
    }
    EXPECT_NEAR(warm.objective, cold.objective, 1e-8 * std::abs(cold.objective)) << scheme;
    EXPECT_EQ(warm.solver_stats.at("mesh_multiplier_starts"),
              static_cast<double>(warm.mesh_history.size() - 1));
    EXPECT_EQ(cold.solver_stats.at("mesh_multiplier_starts"), 0.0);
    EXPECT_LT(warm_iterations, cold_iterations) << scheme;
    RecordProperty(std::string(scheme) + "_iterations_after_the_first_mesh",
                   std::to_string(warm_iterations) + " warm, " + std::to_string(cold_iterations) +
                       " primal only");
  }
}

// The option is on the schemes that refine, with its default, and a bad value is refused in
// one line naming it and the rule.
TEST(MeshWarmMultipliers, OptionIsOnTheRefiningSchemesAndChecked) {
  for (const char* scheme : {"trapezoid", "hermite-simpson", "lgr"}) {
    const TranscriptionInfo& info = FindTranscription(scheme);
    ASSERT_TRUE(info.options.Contains("mesh_warm_multipliers")) << scheme;
    EXPECT_EQ(info.Configure({}).mesh.warm_multipliers, MeshRefinementOptions{}.warm_multipliers);
    OptionMap off;
    off.Set("mesh_warm_multipliers", false);
    EXPECT_FALSE(info.Configure(off).mesh.warm_multipliers) << scheme;
    OptionMap bad;
    bad.Set("mesh_warm_multipliers", "maybe");
    try {
      info.Configure(bad);
      ADD_FAILURE() << scheme << ": 'maybe' accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("mesh_warm_multipliers"), std::string::npos) << what;
      EXPECT_NE(what.find("true or false"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  EXPECT_FALSE(FindTranscription("euler").options.Contains("mesh_warm_multipliers"));
}

}  // namespace
}  // namespace ocpb
