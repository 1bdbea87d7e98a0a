// Every transcription's gradient, constraint Jacobian and Hessian of the Lagrangian against
// central differences, on ten problems (two with a free final time, one with affine dynamics,
// four with a free initial state, an initial cost, boundary constraints or a static parameter),
// both terminal modes, with and without scaling; and the declared sparsity (unique triplets,
// Hessian lower triangle) covers every nonzero found.
#include <cmath>
#include <random>
#include <set>
#include <sstream>
#include <utility>

#include <gtest/gtest.h>

#include "core/derivative_check.h"
#include "problems/registry.h"
#include "tests/core/test_problems.h"
#include "tests/transcriptions/nlp_test_util.h"
#include "tests/transcriptions/test_ocps.h"

namespace ocpb {
namespace {

struct Case {
  std::string scheme;
  int degree;
  std::string problem;  // "double-integrator", "nonlinear", "ball", "free-time", "free-time-ball",
                        // "comm", "free-start", "coupled-ends", "boundary", "time-parameter"
  TerminalMode mode;
  bool scaled;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.scheme << " degree " << c.degree << " on " << c.problem << ", " << ToString(c.mode)
      << (c.scaled ? ", scaled" : "");
}

std::string CaseName(const ::testing::TestParamInfo<Case>& info) {
  const Case& c = info.param;
  std::string s = c.scheme + (c.scheme == "lgr" ? std::to_string(c.degree) : "") + "_" + c.problem +
                  "_" + ToString(c.mode) + (c.scaled ? "_scaled" : "");
  for (char& ch : s) {
    if (ch == '-') ch = '_';
  }
  return s;
}

std::unique_ptr<Ocp> MakeOcp(const std::string& name) {
  if (name == "nonlinear") return std::make_unique<testing::NonlinearTestOcp>();
  if (name == "ball") return std::make_unique<testing::BallTestOcp>();
  // A free final time: T is the NLP's last variable (its column, row and cross terms).
  if (name == "free-time") return MakeProblem("double-integrator-free-time", {}, 0);
  if (name == "free-time-ball") return MakeProblem("brachistochrone-free-time", {}, 0);
  // A partly free initial state with an initial cost (its gradient and Hessian block at x(t0)).
  if (name == "free-start") return MakeProblem("free-start", {}, 0);
  // A boundary constraint coupling x(t0) and x(tf) (its rows, Jacobian and Hessian blocks).
  if (name == "coupled-ends") return MakeProblem("coupled-ends", {}, 0);
  // Nonlinear boundary constraints, an initial cost, a partly free x(t0) and state bounds.
  if (name == "boundary") return std::make_unique<testing::BoundaryTestOcp>();
  // A static parameter in the dynamics and the running cost.
  if (name == "time-parameter") return MakeProblem("double-integrator-time-parameter", {}, 0);
  // Affine dynamics (the constant defect Jacobian) with a ball, the hand-written Hessian, and
  // k5, k6 > 0 (every motion term); moving from the start (the smoothed |v| is stiff at v = 0),
  // D = S and c = 1 so that the terminal penalty (2e5 at the paper's D and c) leaves finite
  // differences of the objective their digits.
  if (name == "comm") {
    return MakeProblem(
        "comm-path2d",
        {"channel=0", "v0=0.5,-0.4", "k=17.75,1.16,10.46,1175,0.3,0.2", "D=20,40", "c=1"},
        0);
  }
  return MakeProblem("double-integrator", {}, 0);
}

// max |a - b| / max(1, |b|) over entries.
double MaxRelError(const Mat& a, const Mat& b) {
  return ((a - b).array().abs() / b.array().abs().max(1.0)).maxCoeff();
}

class TranscriptionDerivatives : public ::testing::TestWithParam<Case> {};

TEST_P(TranscriptionDerivatives, MatchFiniteDifferencesAndStructureCoversThem) {
  const Case& c = GetParam();
  const auto ocp = MakeOcp(c.problem);
  TranscriptionOptions options;
  const double t0 = ocp->t0(), T = ocp->tf() - ocp->t0();
  options.grid = TimeGrid::FromPoints(
      {t0, t0 + 0.15 * T, t0 + 0.4 * T, t0 + 0.5 * T, t0 + 0.8 * T, ocp->tf()});
  options.terminal = c.mode;
  options.degree = c.degree;
  if (c.scaled) {
    options.scaling.objective = 0.37;
    options.scaling.state = Vec::LinSpaced(ocp->nx(), 0.5, 3.0);
    options.scaling.control = Vec::LinSpaced(ocp->nu(), 2.0, 0.25);
  }
  const auto nlp = testing::MakeScheme(c.scheme)->Transcribe(*ocp, options);
  const int n = nlp->num_variables(), m = nlp->num_constraints();

  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> dist(-1.0, 1.0);
  Vec z = nlp->StartingPoint();
  ASSERT_EQ(z.size(), n);
  for (int i = 0; i < n; ++i) z[i] += 0.3 * dist(rng);
  Vec lambda(m);
  for (int i = 0; i < m; ++i) lambda[i] = dist(rng);
  const double sigma = 0.7;

  // Objective gradient.
  Vec grad(n);
  ASSERT_TRUE(nlp->Gradient(z, grad));
  const Mat fd_grad = CentralJacobian(
      [&](const Vec& v) {
        double f;
        EXPECT_TRUE(nlp->Objective(v, &f));
        return Vec::Constant(1, f);
      },
      z);
  EXPECT_LT(MaxRelError(grad.transpose(), fd_grad), 1e-6);

  // Constraint Jacobian: values and coverage.
  const Mat J = testing::DenseJacobian(*nlp, z);
  const Mat fd_J = CentralJacobian(
      [&](const Vec& v) {
        Vec g(m);
        EXPECT_TRUE(nlp->Constraints(v, g));
        return g;
      },
      z);
  EXPECT_LT(MaxRelError(J, fd_J), 1e-6);
  std::set<std::pair<int, int>> jac_entries;
  for (size_t s = 0; s < nlp->jacobian_rows().size(); ++s) {
    const int r = nlp->jacobian_rows()[s], col = nlp->jacobian_cols()[s];
    ASSERT_TRUE(r >= 0 && r < m && col >= 0 && col < n);
    EXPECT_TRUE(jac_entries.emplace(r, col).second)
        << "repeated Jacobian triplet " << r << "," << col;
  }
  int uncovered = 0;
  for (int r = 0; r < m; ++r) {
    for (int col = 0; col < n; ++col) {
      if (std::abs(fd_J(r, col)) > 1e-8 && !jac_entries.count({r, col})) ++uncovered;
    }
  }
  EXPECT_EQ(uncovered, 0) << "Jacobian nonzeros outside the declared structure";

  // Hessian of sigma f + lambda^T g: central differences of the analytic Lagrangian gradient.
  const Mat H = testing::DenseHessian(*nlp, z, sigma, lambda);
  const Mat fd_H = CentralJacobian(
      [&](const Vec& v) { return testing::LagrangianGradient(*nlp, v, sigma, lambda); }, z);
  EXPECT_LT(MaxRelError(H, fd_H), 1e-6);
  std::set<std::pair<int, int>> hess_entries;
  for (size_t s = 0; s < nlp->hessian_rows().size(); ++s) {
    const int r = nlp->hessian_rows()[s], col = nlp->hessian_cols()[s];
    ASSERT_TRUE(r >= 0 && r < n && col >= 0 && col < n);
    EXPECT_GE(r, col) << "Hessian triplet above the diagonal";
    EXPECT_TRUE(hess_entries.emplace(r, col).second)
        << "repeated Hessian triplet " << r << "," << col;
  }
  uncovered = 0;
  for (int r = 0; r < n; ++r) {
    for (int col = 0; col <= r; ++col) {
      if (std::abs(fd_H(r, col)) > 1e-7 && !hess_entries.count({r, col})) ++uncovered;
    }
  }
  EXPECT_EQ(uncovered, 0) << "Hessian nonzeros outside the declared lower triangle";
  EXPECT_TRUE(nlp->HasHessian());
}

std::vector<Case> AllCases() {
  std::vector<Case> cases;
  const std::vector<std::pair<std::string, int>> schemes = {
      {"euler", 0}, {"trapezoid", 0}, {"hermite-simpson", 0}, {"lgr", 1}, {"lgr", 3}, {"lgr", 4}};
  for (const auto& [scheme, degree] : schemes) {
    for (const std::string problem : {"double-integrator",
                                      "nonlinear",
                                      "ball",
                                      "free-time",
                                      "free-time-ball",
                                      "comm",
                                      "free-start",
                                      "coupled-ends",
                                      "boundary",
                                      "time-parameter"}) {
      for (TerminalMode mode : {TerminalMode::kPenalty, TerminalMode::kHard}) {
        for (bool scaled : {false, true}) cases.push_back({scheme, degree, problem, mode, scaled});
      }
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllSchemes,
                         TranscriptionDerivatives,
                         ::testing::ValuesIn(AllCases()),
                         CaseName);

}  // namespace
}  // namespace ocpb
