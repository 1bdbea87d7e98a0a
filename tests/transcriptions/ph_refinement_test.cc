// ph mesh refinement for LGR (transcriptions/mesh_refinement.h, lgr_mesh_error.h): the decision
// rule on constructed cases, the LGR transcription with a degree per interval, the
// Patterson-Hager-Rao estimate (exact on polynomials, its order in h at fixed degree on a smooth
// problem), the simulation estimate (closed form, order), the options, and LGR refined on a
// corner problem against uniform grids.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "core/autodiff_ocp.h"
#include "problems/registry.h"
#include "solvers/registry.h"
#include "transcriptions/lgr.h"
#include "transcriptions/lgr_mesh_error.h"
#include "transcriptions/mesh_refinement.h"
#include "transcriptions/registry.h"
#include "transcriptions/simulation_mesh_error.h"

namespace ocpb {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- the decision rule ---------------------------------------------------------------------

TEST(PhRefinement, DegreeIncreaseIsTheLogarithmInBaseN) {
  // e / tol = 50 at N = 10: log = 1.7, two more points; at N = 4: log_4(50) = 2.8, three.
  EXPECT_EQ(PhDegreeIncrease(5e-5, 1e-6, 10), 2);
  EXPECT_EQ(PhDegreeIncrease(5e-5, 1e-6, 4), 3);
  // Barely above: one; at or below, or NaN: none; N = 1 counts as 2.
  EXPECT_EQ(PhDegreeIncrease(1.001e-6, 1e-6, 10), 1);
  EXPECT_EQ(PhDegreeIncrease(1e-6, 1e-6, 10), 0);
  EXPECT_EQ(PhDegreeIncrease(kNaN, 1e-6, 10), 0);
  EXPECT_EQ(PhDegreeIncrease(6e-6, 1e-6, 1), 3);
  EXPECT_EQ(PhDegreeIncrease(1e300, 1e-300, 3), 1000);  // clamped, no overflow
}

TEST(PhRefinement, DegreeDecreaseKeepsOnePointOfMargin) {
  // tol / e = 5e4 at N = 10: log = 4.7, lowered by 3; at N = 5 log = 6.7, but not below
  // min_degree.
  EXPECT_EQ(PhDegreeDecrease(2e-11, 1e-6, 10, 3), 3);
  EXPECT_EQ(PhDegreeDecrease(2e-11, 1e-6, 5, 3), 2);
  // tol / e = 50 at N = 10: floor(1.7) - 1 = 0.
  EXPECT_EQ(PhDegreeDecrease(2e-8, 1e-6, 10, 3), 0);
  // Failing, NaN, or already at the floor: none; an exact interval (e = 0) down to the floor.
  EXPECT_EQ(PhDegreeDecrease(2e-6, 1e-6, 10, 3), 0);
  EXPECT_EQ(PhDegreeDecrease(kNaN, 1e-6, 10, 3), 0);
  EXPECT_EQ(PhDegreeDecrease(1e-12, 1e-6, 3, 3), 0);
  EXPECT_EQ(PhDegreeDecrease(0.0, 1e-6, 8, 3), 5);
}

TEST(PhRefinement, MergedErrorScalesEachHalfByItsOrder) {
  // Halves of equal length: each estimate times 2^(N + 1).
  EXPECT_DOUBLE_EQ(PhMergedError(1e-9, 0.5, 3, 1e-10, 0.5, 3), 1e-9 * 16.0);
  EXPECT_DOUBLE_EQ(PhMergedError(1e-12, 0.25, 4, 1e-10, 0.75, 2), 1e-12 * std::pow(4.0, 5));
}

PhMesh MakePhMesh(std::vector<double> points, std::vector<int> degrees) {
  return PhMesh{TimeGrid::FromPoints(std::move(points)), std::move(degrees)};
}

void ExpectMesh(const PhMesh& got,
                const std::vector<double>& points,
                const std::vector<int>& degrees) {
  ASSERT_EQ(got.grid.size(), static_cast<int>(points.size()));
  for (size_t k = 0; k < points.size(); ++k) EXPECT_NEAR(got.grid.t(k), points[k], 1e-15) << k;
  EXPECT_EQ(got.degrees, degrees);
}

TEST(PhRefinement, RaisesWhileThePredictedDegreeFitsElseSplits) {
  MeshRefinementOptions o;
  o.min_degree = 3;
  o.max_degree = 10;
  o.reduce = false;
  const PhMesh mesh = MakePhMesh({0.0, 0.25, 0.5, 0.75, 1.0}, {4, 8, 3, 5});
  Vec e(4);
  // Interval 0: 4 + ceil(log_4(1e2)) = 8 <= 10, raised; interval 1: 8 + ceil(log_8(1e6)) = 15
  // > 10, split into max(ceil(15 / 3), 2) = 5 pieces of degree 3; interval 2 meets the
  // tolerance (kept, no reduction); interval 3: NaN, kept.
  e << 1e-4, 1.0, 1e-7, kNaN;
  const PhMesh next = PhRefineMesh(mesh, e, 1e-6, o);
  ExpectMesh(next, {0.0, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.75, 1.0}, {8, 3, 3, 3, 3, 3, 3, 5});
  EXPECT_EQ(next.nodes(), 8 + 5 * 3 + 3 + 5 + 1);
  // A split always makes at least two pieces: 9 + 1 = 10 > max 9 -> max(ceil(10 / 3), 2) = 4.
  o.max_degree = 9;
  const PhMesh split = PhRefineMesh(MakePhMesh({0.0, 1.0}, {9}), Vec::Constant(1, 2e-6), 1e-6, o);
  ExpectMesh(split, {0.0, 0.25, 0.5, 0.75, 1.0}, {3, 3, 3, 3});
  EXPECT_THROW(PhRefineMesh(mesh, Vec::Zero(3), 1e-6, o), std::invalid_argument);
}

TEST(PhRefinement, ReductionMergesAndLowersOnlyWhereTheToleranceIsMetWithRoom) {
  MeshRefinementOptions o;
  o.min_degree = 3;
  o.max_degree = 10;
  const PhMesh mesh = MakePhMesh({0.0, 0.1, 0.2, 0.4, 0.6, 1.0}, {6, 6, 8, 4, 4});
  Vec e(5);
  // Intervals 0 and 1: merged estimate max(1e-14, 2e-14) 2^7 = 2.6e-12 <= tol / 10: merged
  // into degree 6, then lowered by floor(log_6(1e-6 / 2.56e-12)) - 1 = 6 (7.2) - 1 = 6 -> 3.
  // Interval 2 fails: raised to 8 + ceil(log_8(5)) = 9. Intervals 3 and 4 meet it but their
  // merge (4e-8 (0.6 / 0.2)^5 = 9.7e-6) would not: each lowered on its own, interval 3 by
  // floor(log_4(25)) - 1 = 1, interval 4 by floor(log_4(1e3)) - 1 = 3, not below 3.
  e << 1e-14, 2e-14, 5e-6, 4e-8, 1e-9;
  const PhMesh next = PhRefineMesh(mesh, e, 1e-6, o);
  ExpectMesh(next, {0.0, 0.2, 0.4, 0.6, 1.0}, {3, 9, 3, 3});
  // Without reduction the passing intervals are kept as they are.
  o.reduce = false;
  ExpectMesh(PhRefineMesh(mesh, e, 1e-6, o), {0.0, 0.1, 0.2, 0.4, 0.6, 1.0}, {6, 6, 9, 4, 4});
}

// With the previous mesh: an interval raised last time whose estimate fell by less than half
// the model's prediction is split (a corner), one that fell as predicted is raised again; an
// interval the last refinement made (not settled) is neither merged nor lowered.
TEST(PhRefinement, HistoryGuardsCornersAndFreshIntervals) {
  MeshRefinementOptions o;
  o.min_degree = 3;
  o.max_degree = 10;
  const PhMesh before = MakePhMesh({0.0, 0.5, 1.0}, {3, 3});
  Vec e_before(2);
  e_before << 1e-4, 1e-12;
  const PhMesh raised = MakePhMesh({0.0, 0.5, 1.0}, {5, 3});
  Vec e(2);
  // Interval 0 raised 3 -> 5, estimate 1e-4 -> 5e-5: log_3(2) = 0.63 < (5 - 3) / 2. The
  // target 5 + ceil(log_5(50)) = 8 fits the maximum, yet the interval is split into
  // max(ceil(8 / 3), 2) = 3 pieces of degree 3. Interval 1 is settled, at the minimum degree.
  e << 5e-5, 1e-12;
  ExpectMesh(PhRefineMesh(raised, e, 1e-6, o, &before, &e_before),
             {0.0, 0.5 / 3, 1.0 / 3, 0.5, 1.0},
             {3, 3, 3, 3});
  // Without the history the same mesh is raised.
  ExpectMesh(PhRefineMesh(raised, e, 1e-6, o), {0.0, 0.5, 1.0}, {8, 3});
  // 1e-4 -> 4e-6: log_3(25) = 2.9 >= 1, as predicted: raised to 5 + ceil(log_5(4)) = 6.
  e << 4e-6, 1e-12;
  ExpectMesh(PhRefineMesh(raised, e, 1e-6, o, &before, &e_before), {0.0, 0.5, 1.0}, {6, 3});

  // Two halves of a split, both far below the tolerance: merged without history, kept with it.
  const PhMesh whole = MakePhMesh({0.0, 1.0}, {4});
  const Vec e_whole = Vec::Constant(1, 1e-3);
  const PhMesh halves = MakePhMesh({0.0, 0.5, 1.0}, {4, 4});
  const Vec tiny = Vec::Constant(2, 1e-14);
  ExpectMesh(PhRefineMesh(halves, tiny, 1e-6, o), {0.0, 1.0}, {3});
  ExpectMesh(PhRefineMesh(halves, tiny, 1e-6, o, &whole, &e_whole), {0.0, 0.5, 1.0}, {4, 4});
}

// Each bad value is refused by lgr's schema in one line naming the option and its rule; the
// h-only option is not lgr's, the ph-only ones are not Hermite-Simpson's.
TEST(PhRefinement, OptionsAreValidatedByTheSchema) {
  const TranscriptionInfo& lgr = FindTranscription("lgr");
  struct Bad {
    const char* key;
    OptionValue value;
    const char* says;
  };
  for (const Bad& bad : {Bad{"mesh_min_degree", 0, "[1, 59]"},
                         Bad{"mesh_max_degree", 60, "[1, 59]"},
                         Bad{"mesh_estimate", "defect", "interpolation, simulation"},
                         Bad{"mesh_reduce", "maybe", "true or false"},
                         Bad{"mesh_max_new_points", 3, "unknown option"}}) {
    OptionMap given;
    given.Set(bad.key, bad.value);
    try {
      lgr.Configure(given);
      ADD_FAILURE() << bad.key << " accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(bad.key), std::string::npos) << what;
      EXPECT_NE(what.find(bad.says), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
  OptionMap crossed;
  crossed.Set("mesh_min_degree", 6);
  crossed.Set("mesh_max_degree", 5);
  try {
    lgr.Configure(crossed);
    ADD_FAILURE() << "mesh_min_degree > mesh_max_degree accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mesh_max_degree: must be in [mesh_min_degree"),
              std::string::npos)
        << e.what();
  }
  OptionMap good;
  good.Set("mesh_tolerance", 1e-8);
  good.Set("mesh_estimate", "simulation");
  good.Set("mesh_max_degree", 12);
  const TranscriptionOptions o = lgr.Configure(good);
  EXPECT_EQ(o.mesh.tolerance, 1e-8);
  EXPECT_EQ(o.mesh.estimate, MeshErrorEstimate::kSimulation);
  EXPECT_EQ(o.mesh.max_degree, 12);
  EXPECT_EQ(o.mesh.min_degree, MeshRefinementOptions{}.min_degree);
  EXPECT_TRUE(o.mesh.reduce);
  OptionMap ph_only;
  ph_only.Set("mesh_max_degree", 12);
  EXPECT_THROW(FindTranscription("hermite-simpson").Configure(ph_only), std::invalid_argument);
  OptionMap simulation;
  simulation.Set("mesh_estimate", "simulation");
  EXPECT_EQ(FindTranscription("trapezoid").Configure(simulation).mesh.estimate,
            MeshErrorEstimate::kSimulation);
}

// ---- LGR with a degree per interval ----------------------------------------------------------

SolveRequest LgrRequest(const Ocp& ocp, int N, double tol = 1e-12) {
  SolveRequest request;
  request.grid = TimeGrid::Uniform(ocp.t0(), ocp.tf(), N);
  request.terminal = TerminalMode::kHard;
  request.transcription = "lgr";
  request.options.Set("tol", tol);
  return request;
}

// degrees = {K, ..., K} is the uniform transcription; mixed degrees give the NLP sizes they
// should and solve Hager's problem to the accuracy of their lowest degree or better.
TEST(PhRefinement, LgrTakesADegreePerInterval) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("hager", {}, 1);
  TranscriptionOptions uniform;
  uniform.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 4);
  uniform.terminal = TerminalMode::kHard;
  uniform.degree = 3;
  TranscriptionOptions same = uniform;
  same.degrees = {3, 3, 3, 3};
  const LgrTranscription lgr;
  const auto a = lgr.Transcribe(*ocp, uniform);
  const auto b = lgr.Transcribe(*ocp, same);
  ASSERT_EQ(a->num_variables(), b->num_variables());
  EXPECT_EQ(a->jacobian_rows(), b->jacobian_rows());
  const Vec z = a->StartingPoint();
  double fa = 0, fb = 0;
  ASSERT_TRUE(a->Objective(z, &fa) && b->Objective(z, &fb));
  EXPECT_EQ(fa, fb);
  EXPECT_EQ(b->IntervalDegrees(), same.degrees);

  TranscriptionOptions mixed = uniform;
  mixed.degrees = {2, 5, 3, 4};
  const auto c = lgr.Transcribe(*ocp, mixed);
  const int nx = ocp->nx(), nu = ocp->nu();
  EXPECT_EQ(c->num_variables(), (2 + 5 + 3 + 4) * (nx + nu) + nx);
  EXPECT_EQ(c->state_grid().size(), 2 + 5 + 3 + 4 + 1);
  mixed.degrees = {2, 5, 3};
  EXPECT_THROW(lgr.Transcribe(*ocp, mixed), std::invalid_argument);
  mixed.degrees = {2, 5, 61, 3};
  EXPECT_THROW(lgr.Transcribe(*ocp, mixed), std::invalid_argument);
}

// ---- the estimates -------------------------------------------------------------------------

/// x' = (a polynomial of t of degree `power`) on [0, 1], x(0) = 0, with u unused but for the
/// cost: LGR of degree K > power represents x exactly.
class PolynomialRateOcp final : public AutoDiffOcp<PolynomialRateOcp, 1, 1> {
 public:
  explicit PolynomialRateOcp(int power) : power_(power) {
    SetHorizon(0.0, 1.0);
    SetInitialState(Vec::Zero(1));
  }
  std::string name() const override { return "polynomial-rate"; }
  template <class T>
  void EvalDynamics(double t, const VecT<T, 1>&, const VecT<T, 1>& u, VecT<T, 1>* f) const {
    (*f)[0] = 0.0 * u[0] + (power_ + 1.0) * std::pow(t, power_);
  }
  template <class T>
  T EvalRunningCost(double, const VecT<T, 1>&, const VecT<T, 1>& u) const {
    return u[0] * u[0];
  }
  double Exact(double t) const { return std::pow(t, power_ + 1); }

 private:
  int power_;
};

// The exact states at LGR's state points of `mesh` with `degrees`.
std::pair<TimeGrid, Mat> ExactLgrStates(const PolynomialRateOcp& ocp,
                                        const TimeGrid& mesh,
                                        const std::vector<int>& degrees) {
  std::vector<double> t;
  for (int k = 0; k < mesh.intervals(); ++k) {
    const RadauNodes nodes = ComputeRadauNodes(degrees[k]);
    for (int i = 0; i < nodes.K; ++i)
      t.push_back(mesh.t(k) + 0.5 * mesh.h(k) * (nodes.points[i] + 1));
  }
  t.push_back(mesh.tf());
  Mat X(1, t.size());
  for (size_t j = 0; j < t.size(); ++j) X(0, j) = ocp.Exact(t[j]);
  return {TimeGrid::FromPoints(t), X};
}

const TimeGrid kMesh = TimeGrid::FromPoints({0.0, 0.3, 0.45, 1.0});

// A state polynomial of degree <= K is exact: both estimates vanish. One degree more: the
// interpolation estimate sees it on the intervals of degree K only.
TEST(MeshError, LgrEstimatesVanishOnRepresentableSolutions) {
  const std::vector<int> degrees = {3, 4, 3};
  const ControlTrajectory u = ControlTrajectory::Constant(kMesh, Vec::Zero(1));
  const PolynomialRateOcp cubic(2);  // x = t^3
  const auto [times, X] = ExactLgrStates(cubic, kMesh, degrees);
  EXPECT_LT(LgrIntervalErrors(cubic, kMesh, degrees, X, u).maxCoeff(), 1e-14);
  EXPECT_LT(IntervalSimulationErrors(cubic, kMesh, times, X, u).maxCoeff(), 1e-14);
  const PolynomialRateOcp quartic(3);  // x = t^4
  const auto [times4, X4] = ExactLgrStates(quartic, kMesh, degrees);
  const Vec e = LgrIntervalErrors(quartic, kMesh, degrees, X4, u);
  EXPECT_GT(e[0], 1e-6);
  EXPECT_LT(e[1], 1e-14);
  EXPECT_GT(e[2], 1e-6);
}

// The simulation estimate of states that are the exact flow plus a known error: that error,
// scaled by Betts' weight, on the interval where it sits.
TEST(MeshError, SimulationEstimateIsTheScaledDistanceToTheFlow) {
  const PolynomialRateOcp rate(5);  // x = t^6: no scheme is exact, the simulation is (RK4 limit)
  const std::vector<int> degrees = {3, 4, 3};
  auto [times, X] = ExactLgrStates(rate, kMesh, degrees);
  const ControlTrajectory u = ControlTrajectory::Constant(kMesh, Vec::Zero(1));
  const Vec exact = IntervalSimulationErrors(rate, kMesh, times, X, u);
  EXPECT_LT(exact.maxCoeff(), 1e-12);
  X(0, 5) += 3e-5;  // interval 1's third point (columns 3..6 are interval 1's four points)
  const Vec e = IntervalSimulationErrors(rate, kMesh, times, X, u);
  const double weight = 1.0 + X.cwiseAbs().maxCoeff();
  EXPECT_LT(e[0], 1e-12);
  // The substeps are doubled until the simulation moves by <= 1e-2 of the estimate.
  EXPECT_NEAR(e[1], 3e-5 / weight, 1e-2 * 3e-5 / weight);
  EXPECT_LT(e[2], 1e-12);
  // A mesh node that is not a state point is refused.
  EXPECT_THROW(IntervalSimulationErrors(rate, TimeGrid::FromPoints({0.0, 0.31, 1.0}), times, X, u),
               std::invalid_argument);
}

// The least-squares slope of log y against log x.
double Slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    mx += std::log(x[i]) / x.size();
    my += std::log(y[i]) / x.size();
  }
  double num = 0, den = 0;
  for (size_t i = 0; i < x.size(); ++i) {
    num += (std::log(x[i]) - mx) * (std::log(y[i]) - my);
    den += (std::log(x[i]) - mx) * (std::log(x[i]) - mx);
  }
  return num / den;
}

// The largest estimate of the first (only) mesh of a refinement that stops there.
double FirstEstimate(const Ocp& ocp, const std::string& scheme, int N, OptionMap o) {
  SolveRequest request = LgrRequest(ocp, N);
  request.transcription = scheme;
  request.transcription_options = std::move(o);
  request.transcription_options.Set("mesh_tolerance", 1e-300);
  request.transcription_options.Set("mesh_max_iterations", 1);
  const SolveResult r = FindSolver("ipopt").make()->Solve(ocp, request);
  EXPECT_EQ(r.status, SolveStatus::kConverged) << scheme << " N " << N << ": " << r.message;
  EXPECT_EQ(r.mesh_history.size(), 1u);
  return r.mesh_history.empty() ? kNaN : r.mesh_history[0].max_error;
}

// At Ipopt's solutions of Hager's problem on N = 8, 16, 32, 64 uniform intervals: the
// interpolation estimate of LGR with K points decreases as h^(K + 1) (the slope PhMergedError
// assumes).
TEST(MeshError, LgrEstimateDecreasesAsHToTheDegreePlusOne) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("hager", {}, 1);
  for (const int K : {2, 3}) {
    std::vector<double> h, e;
    for (const int N : {8, 16, 32, 64}) {
      OptionMap o;
      o.Set("degree", K);
      h.push_back(1.0 / N);
      e.push_back(FirstEstimate(*ocp, "lgr", N, o));
    }
    EXPECT_NEAR(Slope(h, e), K + 1, 0.25) << "K " << K;
  }
}

// The simulation estimate's slopes on the same solutions: 3 (trapezoid), 4 (Hermite-Simpson),
// K + 1 (LGR), the orders the h-rule uses.
TEST(MeshError, SimulationEstimateDecreasesAtItsOrder) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("hager", {}, 1);
  struct Case {
    const char* scheme;
    int degree;
    double order;
  };
  for (const Case& c :
       {Case{"trapezoid", 0, 3}, Case{"hermite-simpson", 0, 4}, Case{"lgr", 3, 4}}) {
    std::vector<double> h, e;
    for (const int N : {8, 16, 32, 64}) {
      OptionMap o;
      o.Set("mesh_estimate", "simulation");
      if (c.degree > 0) o.Set("degree", c.degree);
      h.push_back(1.0 / N);
      e.push_back(FirstEstimate(*ocp, c.scheme, N, o));
    }
    EXPECT_NEAR(Slope(h, e), c.order, 0.25) << c.scheme;
  }
}

// ---- end to end ----------------------------------------------------------------------------

// LGR refined from 4 intervals of degree 3 on the double integrator with |u| <= 5 (two corners
// of u*) to tolerance 1e-7: it stops with the tolerance met, the history carries the degrees,
// the cost is within 1e-6 of the published optimum, and no uniform degree-3 grid of 4..64
// intervals is as accurate with as few NLP variables (measured: 110 variables and 3.2e-7;
// uniform N = 16: 146 and 4.1e-7, N = 64: 578 and 1.7e-8).
TEST(PhRefinement, LgrOnCornersMeetsTheToleranceWithFewerVariablesThanUniform) {
  const std::unique_ptr<Ocp> ocp = MakeProblem("double-integrator-bounded", {}, 1);
  const double J_star = 6.0450277563;
  SolveRequest request = LgrRequest(*ocp, 4, 1e-10);
  request.transcription_options.Set("mesh_tolerance", 1e-7);
  const SolveResult r = FindSolver("ipopt").make()->Solve(*ocp, request);
  ASSERT_EQ(r.status, SolveStatus::kConverged) << r.message;
  EXPECT_EQ(r.mesh_stop_reason, "tolerance_met") << r.message;
  ASSERT_GE(r.mesh_history.size(), 2u);
  for (const MeshIterationRecord& row : r.mesh_history) {
    ASSERT_EQ(static_cast<int>(row.degrees.size()), row.intervals);
    int points = 0;
    for (int d : row.degrees) points += d;
    EXPECT_EQ(row.nlp_variables, points * (ocp->nx() + ocp->nu()) + ocp->nx());
  }
  EXPECT_EQ(r.mesh_history.back().intervals, r.mesh.intervals());
  const double error = std::abs(r.objective - J_star) / J_star;
  // The estimate bounds the states' local error, not the cost's: within 1e-6 here (3.2e-7).
  EXPECT_LT(error, 1e-6);
  const int refined_size = r.mesh_history.back().nlp_variables;
  for (int N = 4; N <= 64; N *= 2) {
    const SolveResult u = FindSolver("ipopt").make()->Solve(*ocp, LgrRequest(*ocp, N, 1e-10));
    ASSERT_EQ(u.status, SolveStatus::kConverged);
    const double uniform_error = std::abs(u.objective - J_star) / J_star;
    const int size = static_cast<int>(u.solver_stats.at("nlp_variables"));
    EXPECT_TRUE(uniform_error > error || size > refined_size)
        << "uniform N = " << N << ": error " << uniform_error << " with " << size
        << " variables; refined: " << error << " with " << refined_size;
  }
}

}  // namespace
}  // namespace ocpb
