#include "transcriptions/nlp_scaling.h"

#include "transcriptions/radau_nodes.h"
#include "transcriptions/registry.h"

#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

namespace ocpb {
namespace {

TEST(NlpScaling, DefaultsAreValidAndIdentity) {
  const NlpScaling s;
  std::string error;
  EXPECT_TRUE(s.IsValid(&error)) << error;
  EXPECT_TRUE(s.IsValidFor(3, 2, &error)) << error;
  EXPECT_TRUE(s.IsIdentity());
}

TEST(NlpScaling, RejectsBadValuesAndSizes) {
  std::string error;
  NlpScaling s;
  s.objective = 0.0;
  EXPECT_FALSE(s.IsValid(&error));
  EXPECT_NE(error.find("objective"), std::string::npos);
  s = NlpScaling();
  s.state = Vec::Ones(2);
  s.state[1] = -1.0;
  EXPECT_FALSE(s.IsValid(&error));
  s.state[1] = 2.0;
  EXPECT_TRUE(s.IsValid(&error));
  EXPECT_FALSE(s.IsValidFor(3, 1, &error));
  EXPECT_NE(error.find("nx = 3"), std::string::npos);
  EXPECT_FALSE(s.IsIdentity());
}

TEST(NlpScaling, EveryTranscriptionTakesTheScalingKeysByItsSchema) {
  for (const TranscriptionInfo& info : Transcriptions()) {
    const TranscriptionOptions o = info.Configure(
        {{"objective_scale", "1e-3"}, {"state_scale", "10,0.5,2"}, {"control_scale", 4}});
    EXPECT_DOUBLE_EQ(o.scaling.objective, 1e-3) << info.name;
    ASSERT_EQ(o.scaling.state.size(), 3) << info.name;
    EXPECT_DOUBLE_EQ(o.scaling.state[1], 0.5) << info.name;
    ASSERT_EQ(o.scaling.control.size(), 1) << info.name;
    EXPECT_DOUBLE_EQ(o.scaling.control[0], 4.0) << info.name;
    EXPECT_THROW(info.Configure({{"max_iter", "3"}}), std::invalid_argument) << info.name;
    EXPECT_THROW(info.Configure({{"objective_scale", "-1"}}), std::invalid_argument);
    EXPECT_THROW(info.Configure({{"objective_scale", "abc"}}), std::invalid_argument);
    EXPECT_THROW(info.Configure({{"state_scale", "1,,2"}}), std::invalid_argument);
    EXPECT_THROW(info.Configure({{"state_scale", "1,inf"}}), std::invalid_argument);
  }
}

TEST(TranscriptionRegistry, OnlyLgrTakesADegreeWithinItsRadauLimit) {
  EXPECT_EQ(FindTranscription("lgr").Configure({{"degree", 7}}).degree, 7);
  EXPECT_EQ(FindTranscription("lgr").PointsPerInterval({{"degree", 7}}), 7);
  EXPECT_EQ(FindTranscription("hermite-simpson").PointsPerInterval({}), 2);
  EXPECT_EQ(FindTranscription("euler").PointsPerInterval({}), 1);
  EXPECT_THROW(FindTranscription("lgr").Configure({{"degree", kMaxRadauPoints + 1}}),
               std::invalid_argument);
  EXPECT_THROW(FindTranscription("trapezoid").Configure({{"degree", 3}}), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
