#include "core/parameters.h"

#include <gtest/gtest.h>

#include "problems/registry.h"

namespace ocpb {
namespace {

std::string ThrownMessage(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Parameters, SetFromStringParsesScalarsAndVectors) {
  Parameters p({{"S", {20.0, 40.0}, "start"}, {"tf", {40.0}, "horizon", 0.0, 1e6, true}});
  p.SetFromString("S=1.5,-2");
  p.SetFromString("tf=12");
  EXPECT_EQ(p.Vector("S")[1], -2.0);
  EXPECT_EQ(p.Scalar("tf"), 12.0);
}

TEST(Parameters, InvalidValuesAreRejectedWithOneLineMessages) {
  Parameters p({{"S", {20.0, 40.0}, "start"}, {"tf", {40.0}, "horizon", 0.0, 1e6, true}});
  EXPECT_EQ(ThrownMessage([&] { p.SetFromString("tf=-1"); }),
            "parameter 'tf' = -1 out of range: need > 0 and <= 1e+06");
  // NaN is no number in the option grammar; infinity is one, refused by the parameter's rule.
  EXPECT_EQ(ThrownMessage([&] { p.SetFromString("tf=nan"); }),
            "malformed --set 'tf=nan': 'nan' is not a number");
  EXPECT_EQ(ThrownMessage([&] { p.SetFromString("tf=inf"); }),
            "parameter 'tf' must be finite (got NaN or inf)");
  EXPECT_EQ(ThrownMessage([&] { p.SetFromString("S=1"); }),
            "parameter 'S' takes 2 value(s), got 1");
  EXPECT_EQ(ThrownMessage([&] { p.SetFromString("gamma=1"); }),
            "unknown parameter 'gamma' (valid: S, tf)");
  EXPECT_EQ(ThrownMessage([&] { p.SetFromString("tf"); }),
            "malformed --set 'tf': expected key=value or key=v1,v2");
  EXPECT_EQ(ThrownMessage([&] { p.SetFromString("tf=4x"); }),
            "malformed --set 'tf=4x': '4x' is not a number");
  // Empty items are typos, not shorter lists (a trailing ',' used to be dropped silently).
  EXPECT_EQ(ThrownMessage([&] { p.SetFromString("tf=1,"); }),
            "malformed --set 'tf=1,': value 2 is empty");
  EXPECT_EQ(ThrownMessage([&] { p.SetFromString("S=,1"); }),
            "malformed --set 'S=,1': value 1 is empty");
  EXPECT_EQ(ThrownMessage([&] { p.SetFromString("S=1,,2"); }),
            "malformed --set 'S=1,,2': value 2 is empty");
  EXPECT_EQ(p.Scalar("tf"), 40.0);  // failed sets change nothing
}

TEST(ProblemRegistry, UnknownNameListsTheValidOnes) {
  const std::string msg = ThrownMessage([] { FindProblem("no-such-problem"); });
  EXPECT_NE(msg.find("unknown problem 'no-such-problem' (valid: "), std::string::npos);
  EXPECT_NE(msg.find("double-integrator"), std::string::npos);
}

TEST(ProblemRegistry, HorizonMustBePositive) {
  EXPECT_THROW(MakeProblem("double-integrator", {"tf=0"}, 0), std::invalid_argument);
}

}  // namespace
}  // namespace ocpb
