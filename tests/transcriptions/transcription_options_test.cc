// TranscriptionOptions::IsValid / IsValidFor: every rule rejects with a one-line reason.
#include <string>

#include <gtest/gtest.h>

#include "problems/registry.h"
#include "transcriptions/transcription.h"

namespace ocpb {
namespace {

TranscriptionOptions Valid() {
  TranscriptionOptions o;
  o.grid = TimeGrid::Uniform(0.0, 1.0, 10);
  return o;
}

std::string ErrorOf(const TranscriptionOptions& o) {
  std::string error;
  return o.IsValid(&error) ? "(valid)" : error;
}

std::string ErrorFor(const TranscriptionOptions& o, const Ocp& ocp) {
  std::string error;
  return o.IsValidFor(ocp, &error) ? "(valid)" : error;
}

TEST(TranscriptionOptions, DefaultsOnAGridAreValid) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);
  EXPECT_EQ(ErrorOf(Valid()), "(valid)");
  EXPECT_EQ(ErrorFor(Valid(), *ocp), "(valid)");
  EXPECT_TRUE(Valid().IsValid(nullptr));
}

TEST(TranscriptionOptions, EachRuleIsChecked) {
  EXPECT_EQ(ErrorOf(TranscriptionOptions()), "transcription: the grid has no interval");
  TranscriptionOptions o = Valid();
  o.degree = 0;
  EXPECT_EQ(ErrorOf(o), "transcription: degree must be in [1, 60], got 0");
  o.degree = 61;
  EXPECT_EQ(ErrorOf(o), "transcription: degree must be in [1, 60], got 61");
  o = Valid();
  o.scaling.objective = -1.0;
  EXPECT_EQ(ErrorOf(o), "transcription: scaling: objective must be positive and finite");
  o = Valid();
  o.initial_guess = ControlTrajectory::Constant(TimeGrid::Uniform(0.0, 0.5, 5), Vec::Zero(1));
  EXPECT_EQ(ErrorOf(o),
            "transcription: the initial guess is defined on [0, 0.5], which does not cover the "
            "grid [0, 1]");
  o.initial_guess = ControlTrajectory();
  EXPECT_EQ(ErrorOf(o), "transcription: the initial guess has no control components");
}

TEST(TranscriptionOptions, SizesAndHorizonAreCheckedAgainstTheProblem) {
  const auto ocp = MakeProblem("double-integrator", {}, 0);  // nx = 2, nu = 1 on [0, 1]
  TranscriptionOptions o = Valid();
  o.grid = TimeGrid::Uniform(0.0, 2.0, 10);
  EXPECT_EQ(ErrorOf(o), "(valid)");
  EXPECT_EQ(ErrorFor(o, *ocp),
            "transcription: the grid [0, 2] does not span the horizon [0, 1] of problem "
            "'double-integrator'");
  o = Valid();
  o.initial_guess = ControlTrajectory::Constant(o.grid, Vec::Zero(2));
  EXPECT_EQ(ErrorFor(o, *ocp),
            "transcription: the initial guess must have nu = 1 components, got 2");
  o = Valid();
  o.scaling.state = Vec::Ones(3);
  EXPECT_EQ(ErrorFor(o, *ocp),
            "transcription: scaling: state scales (state_scale) must be empty or of size nx = 2 "
            "(got 3)");
}

}  // namespace
}  // namespace ocpb
