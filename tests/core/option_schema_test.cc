// The option mechanism every solver, transcription and driver uses: the one text grammar, typed
// resolution against a spec, schemas with nested prefixes, and bindings to options structs.
#include "core/option_schema.h"

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "core/option_binding.h"

namespace ocpb {
namespace {

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(ParseNumberText, TheOneGrammar) {
  EXPECT_EQ(ParseNumberText("500"), 500.0);
  EXPECT_EQ(ParseNumberText("-2.5"), -2.5);
  EXPECT_EQ(ParseNumberText("1e-8"), 1e-8);
  EXPECT_EQ(ParseNumberText("1E3"), 1000.0);
  EXPECT_EQ(ParseNumberText(".5"), 0.5);
  EXPECT_EQ(ParseNumberText("+7"), 7.0);
  EXPECT_EQ(ParseNumberText("5."), 5.0);
  EXPECT_TRUE(std::isinf(*ParseNumberText("inf")));
  EXPECT_TRUE(std::isinf(*ParseNumberText("Infinity")));
  EXPECT_LT(*ParseNumberText("-inf"), 0.0);
  for (const char* bad : {"",
                          " 1",
                          "1 ",
                          "1e",
                          "e3",
                          "1e+",
                          "nan",
                          "NaN",
                          "0x10",
                          "1,5",
                          "++1",
                          "+-1",
                          "1e999",
                          "-1e999",
                          ".",
                          "-",
                          "4x",
                          "1.2.3"}) {
    EXPECT_FALSE(ParseNumberText(bad).has_value()) << bad;
  }
  EXPECT_EQ(ParseNumberText("1e-320"), 1e-320);  // subnormal, not out of range
}

TEST(OptionValue, CanonicalTextReadsBackAndMatchesTheRecordsOfOldKeys) {
  // Shortest round-trip text, fixed notation for exponents -4..15 (the record keys of suites
  // written before typed options used exactly this text).
  EXPECT_EQ(OptionValue(1e-10).ToText(), "1e-10");
  EXPECT_EQ(OptionValue(2000.0).ToText(), "2000");
  EXPECT_EQ(OptionValue(0.0001).ToText(), "0.0001");
  EXPECT_EQ(OptionValue(1e-5).ToText(), "1e-05");
  EXPECT_EQ(OptionValue(123456.789).ToText(), "123456.789");
  EXPECT_EQ(OptionValue(1e16).ToText(), "1e+16");
  EXPECT_EQ(OptionValue(1e15).ToText(), "1000000000000000");
  EXPECT_EQ(OptionValue(-0.25).ToText(), "-0.25");
  EXPECT_EQ(OptionValue(std::numeric_limits<double>::infinity()).ToText(), "inf");
  EXPECT_EQ(OptionValue(500).ToText(), "500");
  EXPECT_EQ(OptionValue(true).ToText(), "true");
  EXPECT_EQ(OptionValue(std::vector<double>{10, 50, 10}).ToText(), "10,50,10");
  for (double v : {0.1, 1.0 / 3.0, 6.02214076e23, 5e-324, 1.7976931348623157e308, -123.456e-7}) {
    EXPECT_EQ(*ParseNumberText(OptionValue(v).ToText()), v) << OptionValue(v).ToText();
  }
}

OptionSpec Spec(OptionType type, OptionBounds bounds = {}) {
  OptionSpec s;
  // Constructed, not assigned from the literal: GCC 12 at -O3 reports a false -Wrestrict inside
  // std::string's assignment of a short literal in this unity batch.
  s.name = std::string(1, 'k');
  s.type = type;
  s.bounds = bounds;
  return s;
}

TEST(OptionSpec, ResolvesTypedValuesAndTextByOneRule) {
  const OptionSpec number = Spec(OptionType::kNumber, OptionBounds::Open(0, 1));
  EXPECT_EQ(number.Resolve("0.5").number(), 0.5);
  EXPECT_EQ(number.Resolve(0.5).number(), 0.5);
  EXPECT_EQ(ErrorOf([&] { number.Resolve(1); }), "option 'k': must be a number in (0, 1) (got 1)");
  EXPECT_EQ(ErrorOf([&] { number.Resolve("fast"); }),
            "option 'k': must be a number in (0, 1) (got 'fast')");
  EXPECT_EQ(ErrorOf([&] { number.Resolve(true); }),
            "option 'k': must be a number in (0, 1) (got true)");
  // Infinity only where the bounds admit it.
  EXPECT_NE(ErrorOf([&] { Spec(OptionType::kNumber).Resolve("inf"); }), "(accepted)");
  EXPECT_TRUE(std::isinf(
      Spec(OptionType::kNumber, OptionBounds::Above(0).WithInfinity()).Resolve("inf").number()));

  const OptionSpec integer = Spec(OptionType::kInteger, OptionBounds::AtLeast(0));
  EXPECT_EQ(integer.Resolve("1e3").integer(), 1000);
  EXPECT_EQ(integer.Resolve(2000.0).integer(), 2000);
  EXPECT_EQ(integer.Resolve(7).integer(), 7);
  EXPECT_NE(ErrorOf([&] { integer.Resolve("2.5"); }), "(accepted)");
  EXPECT_NE(ErrorOf([&] { integer.Resolve(-1); }), "(accepted)");
  // Beyond an int: the message says so (the rule "integer >= 0" alone would be wrong).
  EXPECT_EQ(ErrorOf([&] { integer.Resolve("2147483648"); }),
            "option 'k': must be an integer >= 0 and within an int, [-2147483648, 2147483647] "
            "(got '2147483648')");
  EXPECT_EQ(integer.Resolve("2147483647").integer(), 2147483647);

  const OptionSpec flag = Spec(OptionType::kBool);
  EXPECT_TRUE(flag.Resolve("1").boolean());
  EXPECT_FALSE(flag.Resolve("false").boolean());
  EXPECT_TRUE(flag.Resolve(1).boolean());
  EXPECT_NE(ErrorOf([&] { flag.Resolve("yes"); }), "(accepted)");
  EXPECT_NE(ErrorOf([&] { flag.Resolve(2); }), "(accepted)");

  OptionSpec choice = Spec(OptionType::kEnum);
  choice.choices = {"klu", "umfpack"};
  EXPECT_EQ(choice.Resolve("klu").text(), "klu");
  EXPECT_EQ(ErrorOf([&] { choice.Resolve("lu"); }),
            "option 'k': must be one of: klu, umfpack (got 'lu')");

  OptionSpec vector = Spec(OptionType::kVector, OptionBounds::Above(0));
  vector.size = 3;
  EXPECT_EQ(vector.Resolve("1,2,3").vector(), (std::vector<double>{1, 2, 3}));
  EXPECT_NE(ErrorOf([&] { vector.Resolve("1,,3"); }), "(accepted)");
  EXPECT_NE(ErrorOf([&] { vector.Resolve("1,2"); }), "(accepted)");
  EXPECT_NE(ErrorOf([&] { vector.Resolve("1,-2,3"); }), "(accepted)");
  // A raw newline in a value never reaches a message (one line).
  EXPECT_EQ(ErrorOf([&] { number.Resolve("a\nb"); }).find('\n'), std::string::npos);
}

struct Demo {
  double step = 1.0;
  int iterations = 10;
  bool verbose = false;
  enum class Mode { kFast, kSafe } mode = Mode::kSafe;
  std::optional<double> rho;
  OptionMap nested;
};

const OptionBinding<Demo>& DemoBinding() {
  static const OptionBinding<Demo> b = [] {
    OptionSchema inner("inner");
    OptionSpec alpha;
    alpha.name = "alpha";
    alpha.default_value = 0.5;
    alpha.bounds = OptionBounds::Open(0, 1);
    inner.Add(alpha);
    OptionBinding<Demo> t("demo");
    t.Number("step", &Demo::step, "a step", OptionBounds::Above(0));
    t.Integer("iterations", &Demo::iterations, "a count", OptionBounds::AtLeast(0));
    t.Bool("verbose", &Demo::verbose, "talk");
    t.Enum("mode", &Demo::mode, {{"fast", Demo::Mode::kFast}, {"safe", Demo::Mode::kSafe}}, "m");
    t.OptionalNumber("rho", &Demo::rho, "a weight", OptionBounds::Above(0), "the default");
    t.Nested("inner", &Demo::nested, inner, "the inner owner's options");
    return t;
  }();
  return b;
}

TEST(OptionBinding, DefaultsComeFromTheStructAndValuesAreApplied) {
  const OptionSchema& s = DemoBinding().schema();
  EXPECT_EQ(s.Find("step")->default_value.number(), 1.0);
  EXPECT_EQ(s.Find("iterations")->default_value.integer(), 10);
  EXPECT_EQ(s.Find("mode")->default_value.text(), "safe");
  EXPECT_TRUE(s.Find("rho")->default_value.empty());
  EXPECT_EQ(s.Find("inner.alpha")->name, "alpha");
  const Demo d = DemoBinding().Apply(
      {{"step", "0.25"}, {"iterations", 3}, {"mode", "fast"}, {"rho", 2}, {"inner.alpha", "0.1"}},
      Demo());
  EXPECT_EQ(d.step, 0.25);
  EXPECT_EQ(d.iterations, 3);
  EXPECT_EQ(d.mode, Demo::Mode::kFast);
  EXPECT_EQ(*d.rho, 2.0);
  EXPECT_EQ(d.nested.Find("alpha")->number(), 0.1);  // resolved by the inner schema: typed
  EXPECT_EQ(ErrorOf([&] {
              DemoBinding().Apply({{"stepp", 1}}, Demo());
            }),
            "demo: unknown option 'stepp' (valid: step, iterations, verbose, mode, rho, "
            "inner.<inner option>)");
  EXPECT_EQ(ErrorOf([&] {
              DemoBinding().Apply({{"inner.alpha", 2}}, Demo());
            }),
            "demo option 'inner.alpha': must be a number in (0, 1) (got 2)");
  EXPECT_NE(ErrorOf([&] { DemoBinding().Apply({{"inner.beta", 2}}, Demo()); }), "(accepted)");
}

TEST(OptionBinding, CheckAppliesTheSameRulesToAStructBuiltInCode) {
  Demo d;
  std::string error;
  EXPECT_TRUE(DemoBinding().Check(d, &error)) << error;
  d.step = -1.0;
  EXPECT_FALSE(DemoBinding().Check(d, &error));
  EXPECT_EQ(error, "demo option 'step': must be a number > 0 (got -1)");
  d.step = 1.0;
  d.nested.Set("alpha", 7.0);
  EXPECT_FALSE(DemoBinding().Check(d, &error));
  EXPECT_NE(error.find("inner.alpha"), std::string::npos) << error;
  // Values() lists what a struct holds: what a record reports as the options used.
  const OptionMap v = DemoBinding().Values(Demo());
  EXPECT_EQ(v.Find("iterations")->integer(), 10);
  EXPECT_FALSE(v.Has("rho"));
}

TEST(OptionSchema, ADefaultThatBreaksItsOwnRuleIsAProgrammingError) {
  OptionSchema s("owner");
  OptionSpec bad = Spec(OptionType::kNumber, OptionBounds::Above(0));
  bad.default_value = -1.0;
  EXPECT_THROW(s.Add(bad), std::logic_error);
  OptionSpec ok = Spec(OptionType::kNumber);
  s.Add(ok);
  EXPECT_THROW(s.Add(ok), std::logic_error);  // duplicate
  OptionSpec e = Spec(OptionType::kEnum);
  e.name = "e";
  EXPECT_THROW(s.Add(e), std::logic_error);  // no choices
}

}  // namespace
}  // namespace ocpb
