// The rate a first-order stop reports (solvers/descent_rate.h): measured on synthetic histories
// whose rate is known, and said in the family's messages when a limit stops it.
#include "solvers/descent_rate.h"

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "problems/registry.h"
#include "solvers/hamiltonian_family.h"

namespace ocpb {
namespace {

// Rows iteration first .. last with theta = -theta0 factor^k (k from 0).
std::vector<IterationRecord> Geometric(int first, int last, double theta0, double factor) {
  std::vector<IterationRecord> rows;
  for (int k = first; k <= last; ++k) {
    IterationRecord row;
    row.iteration = k;
    row.theta = -theta0 * std::pow(factor, k - first);
    rows.push_back(row);
  }
  return rows;
}

TEST(DescentRate, MeasuresTheFactorAndTheStepsToTheTarget) {
  const std::vector<IterationRecord> rows = Geometric(0, 300, 1.0, 0.995);
  const auto rate = MeasureDescentRate(rows, 0, 1e-6);
  ASSERT_TRUE(rate.has_value());
  EXPECT_EQ(rate->steps, 200);  // the window
  EXPECT_NEAR(rate->factor, 0.995, 1e-12);
  EXPECT_NEAR(rate->last_theta, std::pow(0.995, 300), 1e-15);
  // 0.995^n = 1e-6 / 0.995^300: n = log(1e-6) / log(0.995) - 300.
  EXPECT_NEAR(rate->steps_to_target, std::log(1e-6) / std::log(0.995) - 300.0, 1e-6);
  const std::string note = DescentRateNote(rate, 1e-6);
  EXPECT_NE(note.find("over its last 200 steps |theta| fell by a factor 1 - 0.005 per step"),
            std::string::npos)
      << note;
  EXPECT_NE(note.find("about 2457 more to |theta| <= 1e-06"), std::string::npos) << note;
  EXPECT_NE(note.find("polish=true"), std::string::npos) << note;
}

TEST(DescentRate, SkipsCoarseGridRowsRowsBeforeBeginAndNonFiniteTheta) {
  std::vector<IterationRecord> rows = Geometric(0, 10, 1.0, 0.5);
  for (IterationRecord& row : rows) row.intervals = 50;  // a coarser grid's rows
  const std::vector<IterationRecord> fine = Geometric(11, 20, 1.0, 0.25);
  rows.insert(rows.end(), fine.begin(), fine.end());
  rows.back().theta = NAN;  // a row without theta (a Newton row) is not a descent row
  const auto rate = MeasureDescentRate(rows, 0, 0.0);
  ASSERT_TRUE(rate.has_value());
  EXPECT_EQ(rate->steps, 8);  // iterations 11 .. 19
  EXPECT_NEAR(rate->factor, 0.25, 1e-12);
  EXPECT_EQ(rate->steps_to_target, -1.0);  // no target
  EXPECT_EQ(DescentRateNote(rate, 0.0).find("more to"), std::string::npos);
  // Only rows from `begin` on: one row left, no rate.
  EXPECT_FALSE(MeasureDescentRate(rows, rows.size() - 2, 0.0).has_value());
  EXPECT_EQ(DescentRateNote(std::nullopt, 1.0), "");
}

TEST(DescentRate, SaysWhenThetaDidNotFall) {
  const auto rate = MeasureDescentRate(Geometric(0, 20, 2.0, 1.01), 0, 1e-3);
  ASSERT_TRUE(rate.has_value());
  EXPECT_GT(rate->factor, 1.0);
  EXPECT_EQ(rate->steps_to_target, -1.0);
  EXPECT_NE(DescentRateNote(rate, 1e-3).find("did not fall"), std::string::npos);
}

// The family's limited first-order solves say their rate: the descent in the penalty form and
// the augmented-Lagrangian loop in the hard form, on Euler and on RK4; a converged solve and a
// polished one do not.
TEST(DescentRate, FamilyMessagesAtTheIterationLimit) {
  const auto ocp = MakeProblem("comm-path2d", {"gamma=1e-5"}, 1);
  struct Case {
    HamiltonianFamily::Preset preset;
    TerminalMode terminal;
    const char* scheme;
  };
  for (const Case& c :
       {Case{HamiltonianFamily::Preset::kProximal, TerminalMode::kPenalty, "euler"},
        Case{HamiltonianFamily::Preset::kAugmentedLagrangian, TerminalMode::kHard, "euler"},
        Case{HamiltonianFamily::Preset::kAugmentedLagrangian, TerminalMode::kHard, "rk4"}}) {
    SCOPED_TRACE(std::string(c.scheme) + (c.terminal == TerminalMode::kHard ? ", hard" : ""));
    SolveRequest r;
    r.grid = TimeGrid::Uniform(ocp->t0(), ocp->tf(), 100);
    r.terminal = c.terminal;
    r.options = {{"max_iterations", "300"}, {"scheme", c.scheme}};
    const SolveResult result = HamiltonianFamily(c.preset).Solve(*ocp, r);
    EXPECT_EQ(result.status, SolveStatus::kMaxIterations) << result.message;
    // "fell by a factor ... per step (linear)" or "did not fall" (the AL's inner solve, whose
    // |theta| can grow after a multiplier update).
    EXPECT_NE(result.message.find("; over its last "), std::string::npos) << result.message;
  }
  const auto hager = MakeProblem("hager", {}, 1);
  SolveRequest r;
  r.grid = TimeGrid::Uniform(hager->t0(), hager->tf(), 50);
  r.options = {{"max_iterations", "5000"}, {"relative_theta_tolerance", "1e-10"}};
  const SolveResult converged =
      HamiltonianFamily(HamiltonianFamily::Preset::kProximal).Solve(*hager, r);
  EXPECT_EQ(converged.status, SolveStatus::kConverged) << converged.message;
  EXPECT_EQ(converged.message.find("per step"), std::string::npos) << converged.message;
  r.options = {{"max_iterations", "3"}};
  const SolveResult polished =
      HamiltonianFamily(HamiltonianFamily::Preset::kPolish).Solve(*hager, r);
  EXPECT_EQ(polished.message.find("per step"), std::string::npos) << polished.message;
}

}  // namespace
}  // namespace ocpb
