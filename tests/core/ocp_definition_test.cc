// What a problem's author gets wrong most easily, refused or reported: dimensions stated twice,
// terminal weights never chosen, a free final time judged on the nominal horizon.
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/evaluator.h"
#include "problems/registry.h"
#include "tests/core/slip_ocp.h"
#include "tests/core/user_double_integrator.h"

namespace ocpb {
namespace {

using testing::SlipOcp;
using testing::UserDoubleIntegrator;

TEST(AutoDiffOcpDimensions, AreTheTemplateArgumentsWithoutSetDimensions) {
  const UserDoubleIntegrator ocp(/*declared_npsi=*/-1, /*weight=*/1000.0);
  EXPECT_EQ(ocp.nx(), 2);
  EXPECT_EQ(ocp.nu(), 1);
  EXPECT_EQ(ocp.num_terminal(), 2);
  EXPECT_EQ(ocp.num_path(), 0);
  EXPECT_EQ(ocp.control_set().dimension(), 1);
}

// The mistake: two terminal constraints in the template, one in SetDimensions. It used
// to solve a different problem (Ipopt: Solve_Succeeded); now the constructor refuses it.
TEST(AutoDiffOcpDimensions, ASecondStatementThatDisagreesIsRefusedNamingTheDimension) {
  try {
    const UserDoubleIntegrator ocp(/*declared_npsi=*/1);
    FAIL() << "a disagreeing SetDimensions was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("npsi = 1"), std::string::npos) << what;
    EXPECT_NE(what.find("template argument says 2"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << "one line: " << what;
  }
}

TEST(AutoDiffOcpDimensions, AnAgreeingStatementChangesNothingSetBeforeIt) {
  const UserDoubleIntegrator ocp(/*declared_npsi=*/2, /*weight=*/0.0, /*x0_first=*/true);
  EXPECT_EQ(ocp.num_terminal(), 2);
  EXPECT_EQ(ocp.x0(), Vec::Constant(2, 0.5));  // not reset to 0 by the second statement
}

// A NominalControl of the wrong size used to crash a method (an empty one: a segfault in
// ControlSet::Project); every method starts from CheckedNominalControl, which names the problem.
// (tests/solvers/judge_test.cc: each method refuses it.)
TEST(NominalControl, OfTheWrongSizeIsRefusedNamingTheProblem) {
  EXPECT_EQ(SlipOcp(1).CheckedNominalControl().size(), 1);
  for (const int size : {0, 2}) {
    try {
      SlipOcp(size).CheckedNominalControl();
      FAIL() << size << " components accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()),
                "problem 'slip': NominalControl() must return nu = 1 finite values (got " +
                    std::to_string(size) + ")");
    }
  }
}

// SetFreeFinalTime before SetHorizon was checked against the default tf, and the horizon set
// after it was not checked at all: the constructor now says so.
TEST(FreeFinalTime, AHorizonOutsideBoundsDeclaredBeforeIsRefused) {
  EXPECT_NO_THROW(SlipOcp(1, /*free_upper=*/5.0, /*tf=*/2.0));
  try {
    SlipOcp(1, /*free_upper=*/5.0, /*tf=*/8.0);
    FAIL() << "a horizon outside the free final time's bounds was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("[0, 8] does not fit the free final time's bounds [0.5, 5]"),
              std::string::npos)
        << what;
  }
}

TEST(TerminalWeights, AreMarkedChosenOnlyWhenTheProblemSetsThem) {
  EXPECT_FALSE(UserDoubleIntegrator(2).terminal_weights_chosen());
  EXPECT_EQ(UserDoubleIntegrator(2).terminal_weights(), Vec::Ones(2));  // the default
  EXPECT_TRUE(UserDoubleIntegrator(2, /*weight=*/1000.0).terminal_weights_chosen());
  // Built-in problems choose theirs; a problem without terminal constraints has none to choose.
  EXPECT_TRUE(MakeProblem("double-integrator", {}, 0)->terminal_weights_chosen());
  EXPECT_TRUE(MakeProblem("hager", {}, 0)->terminal_weights_chosen());
}

// The documented recipe of old, Evaluate on the request's grid, judged a free final time on
// [t0, nominal tf] although the solution ends at its own T: a plausible but wrong cost and
// terminal miss. The evaluator now refuses a grid that stops before the controls do.
TEST(EvaluateFreeFinalTime, RefusesAGridThatEndsBeforeTheControls) {
  const auto ocp = MakeProblem("double-integrator-free-time", {}, 0);
  ASSERT_TRUE(ocp->free_final_time().has_value());
  const double nominal = ocp->tf();
  const double T = nominal + 0.5;  // a solution's T, within the bounds
  ASSERT_TRUE(ocp->AdmitsFinalTime(T));
  const TimeGrid own = TimeGrid::Uniform(ocp->t0(), T, 20);
  const ControlTrajectory u = ControlTrajectory::Constant(own, Vec::Ones(1));
  const TimeGrid nominal_grid = TimeGrid::Uniform(ocp->t0(), nominal, 20);
  try {
    Evaluate(*ocp, u, nominal_grid.Refined(10), Integrator::kRk4);
    FAIL() << "a truncated free-time trajectory was judged";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("free final time"), std::string::npos) << e.what();
  }
  // On the solution's own horizon it is judged.
  EXPECT_TRUE(Evaluate(*ocp, u, nominal_grid.StretchedTo(T), Integrator::kRk4).finite);
}

}  // namespace
}  // namespace ocpb
