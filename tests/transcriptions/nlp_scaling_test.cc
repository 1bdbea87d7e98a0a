#include "transcriptions/nlp_scaling.h"

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

TEST(NlpScaling, ParsesItsOwnKeysOnly) {
  NlpScaling s;
  EXPECT_TRUE(ParseNlpScalingOption("objective_scale", "1e-3", &s));
  EXPECT_DOUBLE_EQ(s.objective, 1e-3);
  EXPECT_TRUE(ParseNlpScalingOption("state_scale", "10,0.5,2", &s));
  ASSERT_EQ(s.state.size(), 3);
  EXPECT_DOUBLE_EQ(s.state[1], 0.5);
  EXPECT_TRUE(ParseNlpScalingOption("control_scale", "4", &s));
  EXPECT_DOUBLE_EQ(s.control[0], 4.0);
  EXPECT_FALSE(ParseNlpScalingOption("max_iter", "3", &s));
  EXPECT_THROW(ParseNlpScalingOption("objective_scale", "-1", &s), std::invalid_argument);
  EXPECT_THROW(ParseNlpScalingOption("objective_scale", "abc", &s), std::invalid_argument);
  EXPECT_THROW(ParseNlpScalingOption("state_scale", "1,,2", &s), std::invalid_argument);
  EXPECT_THROW(ParseNlpScalingOption("state_scale", "1,inf", &s), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
