// `ocpbench compare`: the rules on synthetic records (bench/cli/compare.h), and end to end on two
// runs of a tiny suite: a deliberate change (an option that worsens one method) is reported as
// that regression and nothing else; identical runs report no change.
#include "bench/cli/compare.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/cli/compare_report.h"
#include "tests/cli/run_ocpbench.h"

namespace ocpb {
namespace {

using nlohmann::json;
using testing::ProgramRun;
using testing::RunOcpbenchProgram;

// ---- synthetic records -----------------------------------------------------------------------

struct Case {
  std::string solver = "ipopt", transcription = "euler", terminal = "penalty";
  std::string status = "converged";
  int seed = 1;
  double J_fine = 10.0, Jbar_fine = 9.0, terminal_violation_fine = 1e-3, path_violation = 0.0;
  int iterations = 12;
  std::vector<double> cpu = {1.0, 1.1, 0.9};
  std::map<std::string, std::string> options = {};
};

json CaseRecord(const Case& c) {
  std::string key = fmt::format("p|seed={}|{}|{}||N=100|deg=3|{}|euler|eval=euler",
                                c.seed,
                                c.solver,
                                c.transcription,
                                c.terminal);
  json options = json::object();
  for (const auto& [k, v] : c.options) {
    key += "|opt:" + k + "=" + v;
    options[k] = v;
  }
  std::vector<double> sorted = c.cpu;
  std::sort(sorted.begin(), sorted.end());
  return json{{"key", key},
              {"problem", "p"},
              {"seed", c.seed},
              {"parameters", {{"C", 10.0}}},
              {"solver", c.solver},
              {"transcription", c.transcription},
              {"N", 100},
              {"terminal", c.terminal},
              {"options", options},
              {"status", c.status},
              {"J", c.J_fine},
              {"J_fine", c.J_fine},
              {"Jbar_fine", c.Jbar_fine},
              {"terminal_violation_fine", c.terminal_violation_fine},
              {"path_violation", c.path_violation},
              {"iterations", c.iterations},
              {"cpu_seconds", sorted[sorted.size() / 2]},
              {"cpu_seconds_repeats", c.cpu},
              {"history", json::array()},
              {"versions", {{"commit", "abc"}}}};
}

CompareSide Side(const std::vector<Case>& cases, const std::string& name) {
  CompareSide side;
  side.path = side.records_path = name;
  for (const Case& c : cases) side.records.push_back(Record::FromJson(CaseRecord(c)));
  return side;
}

Comparison CompareCases(const std::vector<Case>& base,
                        const std::vector<Case>& next,
                        CompareOptions options = {}) {
  return Compare(Side(base, "base"), Side(next, "new"), options);
}

std::vector<std::string> Measures(const CaseComparison& c, bool worse) {
  std::vector<std::string> out;
  for (const Finding& f : c.findings) {
    if (f.worse == worse) out.push_back(f.measure);
  }
  return out;
}

using Names = std::vector<std::string>;

TEST(Compare, IdenticalSidesShowNoChange) {
  const std::vector<Case> cases = {Case{}, Case{.solver = "hamiltonian", .transcription = ""}};
  const Comparison c = CompareCases(cases, cases);
  ASSERT_EQ(c.cases.size(), 2u);
  for (const CaseComparison& cc : c.cases) {
    EXPECT_TRUE(cc.findings.empty());
    EXPECT_EQ(cc.cost_change, 0.0);
    EXPECT_EQ(cc.Jbar_fine_change, 0.0);
    EXPECT_EQ(cc.terminal_violation_change, 0.0);
    EXPECT_EQ(cc.cpu_ratio, 1.0);
    EXPECT_EQ(cc.cpu_test.p_value, 1.0);
  }
  EXPECT_FALSE(c.HasRegression());
  EXPECT_TRUE(c.only_in_base.empty());
  EXPECT_TRUE(c.only_in_new.empty());
  ASSERT_EQ(c.methods.size(), 2u);
  EXPECT_EQ(c.methods[0].cpu_ratio, 1.0);
  EXPECT_EQ(c.overall_cpu_ratio, 1.0);
}

TEST(Compare, AWorseStatusTierIsARegressionWhateverTheCost) {
  Case worse;
  worse.status = "max_iterations";
  worse.J_fine = 9.0;  // cheaper, yet the method stopped on its limit
  const Comparison c = CompareCases({Case{}}, {worse});
  ASSERT_EQ(c.cases.size(), 1u);
  EXPECT_EQ(Measures(c.cases[0], true), Names{"status"});
  EXPECT_EQ(Measures(c.cases[0], false), Names{"cost"});
  EXPECT_TRUE(c.cases[0].Regressed());
  EXPECT_TRUE(c.HasRegression());
  EXPECT_EQ(c.methods[0].status_changes.at("converged -> max_iterations"), 1);

  // Within a tier a change is reported, not judged; a better tier is an improvement.
  Case step = worse;
  step.status = "step_too_small";
  const Comparison within = CompareCases({worse}, {step});
  EXPECT_TRUE(within.cases[0].findings.empty());
  EXPECT_EQ(within.methods[0].status_changes.at("max_iterations -> step_too_small"), 1);
  Case converged = worse;
  converged.status = "converged";
  EXPECT_EQ(Measures(CompareCases({worse}, {converged}).cases[0], false), Names{"status"});
  EXPECT_LT(StatusTier("converged"), StatusTier("acceptable"));
  EXPECT_LT(StatusTier("acceptable"), StatusTier("max_iterations"));
  EXPECT_EQ(StatusTier("max_iterations"), StatusTier("roundoff_limited"));
  EXPECT_LT(StatusTier("step_too_small"), StatusTier("not_applicable"));
  EXPECT_LT(StatusTier("not_applicable"), StatusTier("numerical_failure"));
  EXPECT_EQ(StatusTier("error"), StatusTier("invalid_input"));
}

TEST(Compare, CostThresholdIsRelative) {
  Case up;
  up.J_fine = 10.0 * (1 + 2e-4);
  Case tiny;
  tiny.J_fine = 10.0 * (1 + 5e-5);
  EXPECT_EQ(Measures(CompareCases({Case{}}, {up}).cases[0], true), Names{"cost"});
  EXPECT_NEAR(CompareCases({Case{}}, {up}).cases[0].cost_change, 2e-4, 1e-12);
  EXPECT_TRUE(CompareCases({Case{}}, {tiny}).cases[0].findings.empty());
  CompareOptions loose;
  loose.thresholds.cost = 1e-3;
  EXPECT_TRUE(CompareCases({Case{}}, {up}, loose).cases[0].findings.empty());
  EXPECT_EQ(Measures(CompareCases({up}, {Case{}}).cases[0], false), Names{"cost"});
  // A cost that is gone (a failed solve) is worse; Jbar fine is reported, never judged.
  Case gone;
  gone.J_fine = NAN;
  gone.status = "error";
  EXPECT_EQ(Measures(CompareCases({Case{}}, {gone}).cases[0], true), (Names{"status", "cost"}));
  Case jbar;
  jbar.Jbar_fine = 20.0;
  const Comparison c = CompareCases({Case{}}, {jbar});
  EXPECT_TRUE(c.cases[0].findings.empty());
  EXPECT_NEAR(c.cases[0].Jbar_fine_change, 11.0 / 9.0, 1e-12);
}

TEST(Compare, HardFormCostsAreComparedOnlyWhenBothConverged) {
  Case base{.terminal = "hard", .status = "step_too_small", .J_fine = 8.0};
  Case next{.terminal = "hard", .J_fine = 10.0};  // feasible now, and dearer
  const Comparison c = CompareCases({base}, {next});
  EXPECT_EQ(Measures(c.cases[0], false), Names{"status"});
  EXPECT_TRUE(Measures(c.cases[0], true).empty());
  Case dearer{.terminal = "hard", .J_fine = 10.1};
  EXPECT_EQ(Measures(CompareCases({next}, {dearer}).cases[0], true), Names{"cost"});
}

TEST(Compare, ViolationsMustRiseByBothThresholds) {
  auto with = [](double v) {
    Case c;
    c.terminal_violation_fine = v;
    return c;
  };
  // Far below any tolerance, and 0.7 % of a penalty-form miss: no finding.
  EXPECT_TRUE(CompareCases({with(1e-12)}, {with(1e-9)}).cases[0].findings.empty());
  EXPECT_TRUE(CompareCases({with(0.149)}, {with(0.150)}).cases[0].findings.empty());
  EXPECT_EQ(Measures(CompareCases({with(0.149)}, {with(0.16)}).cases[0], true),
            Names{"terminal viol. fine"});
  EXPECT_EQ(Measures(CompareCases({with(1e-7)}, {with(5e-6)}).cases[0], true),
            Names{"terminal viol. fine"});
  EXPECT_EQ(Measures(CompareCases({with(5e-6)}, {with(1e-7)}).cases[0], false),
            Names{"terminal viol. fine"});
  Case path;
  path.path_violation = 1e-3;
  EXPECT_EQ(Measures(CompareCases({Case{}}, {path}).cases[0], true), Names{"path viol."});
  EXPECT_NEAR(CompareCases({Case{}}, {path}).cases[0].path_violation_change, 1e-3, 1e-15);
}

TEST(Compare, CpuNeedsTheRatioAndASignificantRankTest) {
  Case five{.cpu = {1.0, 1.01, 1.02, 1.03, 1.04}};
  Case slow{.cpu = {2.0, 2.01, 2.02, 2.03, 2.04}};
  const Comparison c = CompareCases({five}, {slow});
  EXPECT_EQ(Measures(c.cases[0], true), Names{"CPU"});
  EXPECT_NEAR(c.cases[0].cpu_test.p_value, 2.0 / 252, 1e-12);
  EXPECT_NEAR(c.cases[0].cpu_ratio, 2.02 / 1.02, 1e-12);
  EXPECT_EQ(Measures(CompareCases({slow}, {five}).cases[0], false), Names{"CPU"});
  // Significant but within the ratio: no finding.
  Case bit_slower{.cpu = {1.1, 1.11, 1.12, 1.13, 1.14}};
  EXPECT_TRUE(CompareCases({five}, {bit_slower}).cases[0].findings.empty());
  // 3 repeats cannot make one case significant (p >= 0.1), whatever the ratio...
  Case three{.cpu = {1.0, 1.01, 1.02}};
  Case three_slow{.cpu = {3.0, 3.01, 3.02}};
  const Comparison one = CompareCases({three}, {three_slow});
  EXPECT_TRUE(one.cases[0].findings.empty());
  EXPECT_NEAR(one.cases[0].cpu_test.p_value, 0.1, 1e-12);
  EXPECT_FALSE(one.HasRegression());
  // ... but three such cases of one method can, through the test stratified over the cases.
  std::vector<Case> base, next;
  for (int seed = 1; seed <= 3; ++seed) {
    base.push_back(three);
    base.back().seed = seed;
    next.push_back(three_slow);
    next.back().seed = seed;
  }
  const Comparison many = CompareCases(base, next);
  EXPECT_EQ(many.RegressedCases(), 0);
  ASSERT_EQ(many.methods.size(), 1u);
  EXPECT_NEAR(many.methods[0].cpu_test.p_value, 2.0 / 8000, 1e-12);
  EXPECT_NEAR(many.methods[0].cpu_ratio, 3.01 / 1.01, 1e-12);
  EXPECT_NEAR(many.overall_cpu_ratio, 3.01 / 1.01, 1e-12);
  ASSERT_EQ(many.methods[0].findings.size(), 1u);
  EXPECT_TRUE(many.methods[0].findings[0].worse);
  EXPECT_EQ(many.RegressedMethods(), 1);
  EXPECT_TRUE(many.HasRegression());
}

TEST(Compare, CasesInOneSideAreListedAndMissingOnesCount) {
  Case other{.seed = 2};
  const Comparison added = CompareCases({Case{}}, {Case{}, other});
  ASSERT_EQ(added.only_in_new.size(), 1u);
  EXPECT_NE(added.only_in_new[0].key.find("seed=2"), std::string::npos);
  EXPECT_TRUE(added.only_in_base.empty());
  EXPECT_FALSE(added.HasRegression());
  const Comparison missing = CompareCases({Case{}, other}, {Case{}});
  ASSERT_EQ(missing.only_in_base.size(), 1u);
  EXPECT_TRUE(missing.HasRegression());
  const std::string md = CompareMarkdown(missing);
  EXPECT_NE(md.find("| only in BASE | p |"), std::string::npos) << md;
}

TEST(Compare, NotTwoRunsOfOneSuiteIsRefused) {
  CompareSide a = Side({Case{}}, "a"), b = Side({Case{}}, "b");
  a.suite = "paper";
  b.suite = "references";
  try {
    Compare(a, b, {});
    FAIL() << "different suites compared";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "compare: a is a run of suite 'paper', b of suite 'references': not two runs of "
                 "one suite");
  }
  try {
    CompareCases({Case{}}, {Case{.seed = 2}});
    FAIL() << "no case in common";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no case in common"), std::string::npos) << e.what();
  }
}

TEST(Compare, IgnoredOptionsMatchAnABTestOfAnOption) {
  Case base{.options = {{"max_iter", "100"}, {"tol", "1e-08"}}};
  Case next{.options = {{"max_iter", "5"}, {"tol", "1e-08"}}};
  EXPECT_THROW(CompareCases({base}, {next}), std::invalid_argument);  // nothing in common
  CompareOptions options;
  options.ignore_options = {"max_iter"};
  const Comparison c = CompareCases({base}, {next}, options);
  ASSERT_EQ(c.cases.size(), 1u);
  EXPECT_EQ(c.cases[0].base.ignored_options.at("max_iter"), "100");
  EXPECT_EQ(c.cases[0].next.ignored_options.at("max_iter"), "5");
  EXPECT_EQ(c.cases[0].key.find("max_iter"), std::string::npos);
  EXPECT_NE(c.cases[0].key.find("|opt:tol=1e-08"), std::string::npos);
  // The method's row is one label for both sides.
  ASSERT_EQ(c.methods.size(), 1u);
  // Two cases of one side that differ only in the ignored option cannot be told apart.
  try {
    CompareCases({base, next}, {next}, options);
    FAIL() << "two cases merged";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "--ignore-option: base: lines 1 and 2 differ only in the ignored options, so "
                 "they cannot be told apart");
  }
  options.ignore_options = {"max_iterations"};
  try {
    CompareCases({base}, {next}, options);
    FAIL() << "an option no case sets";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(),
                 "--ignore-option 'max_iterations': no case of base or new sets this option");
  }
}

TEST(Compare, TimeToTargetUsesOneTargetForBothSides) {
  // BASE alone: Ipopt's J = 10 is the best and the descent's 10.05 within 1 % of it: both reach
  // the target. NEW's Ipopt finds J = 9, and the target of the group (the best over both sides)
  // drops to 9 for both sides: only NEW's Ipopt reaches it.
  Case ipopt;
  Case descent{.solver = "hamiltonian", .transcription = "", .J_fine = 10.05};
  Case better = ipopt;
  better.J_fine = 9.0;
  const Comparison c = CompareCases({ipopt, descent}, {better, descent});
  ASSERT_EQ(c.cases.size(), 2u);
  EXPECT_TRUE(std::isnan(c.cases[0].base.time_to_target));
  EXPECT_DOUBLE_EQ(c.cases[0].next.time_to_target, 1.0);  // no history: its CPU seconds
  EXPECT_TRUE(std::isnan(c.cases[1].base.time_to_target));
  EXPECT_TRUE(std::isnan(c.cases[1].next.time_to_target));
  EXPECT_EQ(c.methods[0].reached_base, 0);
  EXPECT_EQ(c.methods[0].reached_new, 1);
  // One profile over (method, side): one group whose best is NEW's Ipopt.
  ASSERT_EQ(c.profiles.size(), 2u);
  EXPECT_EQ(c.profiles[0].instances, 1);
  EXPECT_DOUBLE_EQ(c.profiles[0].base.back(), 0.0);
  EXPECT_DOUBLE_EQ(c.profiles[0].next[0], 1.0);
  EXPECT_DOUBLE_EQ(c.profiles[1].base.back(), 0.0);
  EXPECT_DOUBLE_EQ(c.profiles[1].next.back(), 0.0);
}

TEST(Compare, ThresholdsAreTypedOptions) {
  const CompareThresholds d = ResolveCompareThresholds({});
  EXPECT_EQ(d.cost, 1e-4);
  EXPECT_EQ(d.cpu_ratio, 1.5);
  EXPECT_EQ(d.violation_abs, 1e-6);
  EXPECT_EQ(d.violation_rel, 0.01);
  EXPECT_EQ(d.alpha, 0.05);
  OptionMap given;
  given.Set("alpha", "0.01");
  given.Set("cost", "1e-3");
  const CompareThresholds t = ResolveCompareThresholds(given);
  EXPECT_EQ(t.alpha, 0.01);
  EXPECT_EQ(t.cost, 1e-3);
  OptionMap bad;
  bad.Set("alpha", "1");
  try {
    ResolveCompareThresholds(bad);
    FAIL() << "alpha = 1 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "compare option 'alpha': must be a number in (0, 1) (got '1')");
  }
  OptionMap unknown;
  unknown.Set("costs", "1");
  EXPECT_THROW(ResolveCompareThresholds(unknown), std::invalid_argument);
}

TEST(Compare, ReportPutsRegressionsFirst) {
  Case worse;
  worse.status = "max_iterations";
  Case better{.seed = 2, .J_fine = 9.0};
  const Comparison c = CompareCases({Case{}, Case{.seed = 2}}, {worse, better});
  const std::string md = CompareMarkdown(c);
  const size_t regressions = md.find("## Regressions (1 case)");
  const size_t improvements = md.find("## Improvements (1 case)");
  const size_t every = md.find("## Every matched case");
  ASSERT_NE(regressions, std::string::npos) << md;
  ASSERT_NE(improvements, std::string::npos) << md;
  EXPECT_LT(md.find("**Regression: 1 of 2 matched cases regressed"), regressions) << md;
  EXPECT_LT(regressions, improvements);
  EXPECT_LT(improvements, every);
  EXPECT_NE(md.find("| p, seed 1 | ipopt + euler, penalty, N=100 | status: converged -> "
                    "max_iterations |"),
            std::string::npos)
      << md;
  const json j = CompareJson(c);
  EXPECT_EQ(j["verdict"]["regression"], true);
  EXPECT_EQ(j["verdict"]["regressed_cases"], 1);
  EXPECT_EQ(j["verdict"]["improved_cases"], 1);
  EXPECT_EQ(j["cases"][0]["verdict"], "regressed");
  EXPECT_EQ(j["cases"][1]["verdict"], "improved");
  EXPECT_EQ(j["cases"][0]["findings"][0]["measure"], "status");
  EXPECT_EQ(j["thresholds"]["cpu_ratio"], 1.5);
}

// ---- reading the sides -----------------------------------------------------------------------

std::string CompareErrorOf(const std::string& path) {
  try {
    LoadCompareSide(path);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(LoadCompareSide, DamagedInputIsNamedByFileLineAndField) {
  const std::string dir = testing::FreshDirectory("compare-load");
  EXPECT_EQ(CompareErrorOf(dir + "/nothing"),
            "compare: " + dir + "/nothing: no such file or folder");
  EXPECT_EQ(CompareErrorOf(dir),
            dir + "/records.jsonl: no such file (not a result folder of ocpbench run)");
  testing::WriteText(dir + "/records.jsonl", "");
  EXPECT_EQ(CompareErrorOf(dir), dir + "/records.jsonl: no records");
  const std::string good = CaseRecord(Case{}).dump();
  json bad = CaseRecord(Case{.seed = 2});
  bad["J_fine"] = "high";
  testing::WriteText(dir + "/records.jsonl", good + "\n" + bad.dump() + "\n");
  EXPECT_EQ(CompareErrorOf(dir), dir + "/records.jsonl:2: J_fine: must be a number or null");
  testing::WriteText(dir + "/records.jsonl", good + "\n" + good + "\n");
  EXPECT_EQ(CompareErrorOf(dir),
            dir + "/records.jsonl:2: key: the case of line 1 again (a case recorded twice)");
  json keyless = CaseRecord(Case{});
  keyless.erase("key");
  testing::WriteText(dir + "/records.jsonl", keyless.dump() + "\n");
  EXPECT_EQ(CompareErrorOf(dir),
            dir +
                "/records.jsonl:1: key: missing (a record without a case key cannot be "
                "matched)");
  testing::WriteText(dir + "/records.jsonl", good + "\n");
  testing::WriteText(dir + "/suite.json", "{\"records\": 1}");
  EXPECT_EQ(CompareErrorOf(dir), dir + "/suite.json: suite: must be a string (the suite's name)");
  testing::WriteText(dir + "/suite.json", "{\"suite\": \"tiny\", \"records\": 1}\n");
  const CompareSide side = LoadCompareSide(dir);
  EXPECT_EQ(side.suite, "tiny");
  EXPECT_EQ(side.records.size(), 1u);
  // A last line cut short by a killed run is left out, and said so.
  testing::WriteText(dir + "/records.jsonl", good + "\n" + good.substr(0, 40));
  EXPECT_TRUE(LoadCompareSide(dir).dropped_partial);
}

// ---- end to end: two runs of a tiny suite ----------------------------------------------------

// One case per method with 3 repeats each: the descent converges (theta tolerance) in about 100
// iterations, Ipopt in one. The deliberate change: the descent's max_iterations 300 -> 5.
std::string CompareSuite(int max_iterations, bool extra_method = false) {
  return fmt::format(
      R"({{"name": "tiny", "groups": [{{"problem": "double-integrator", "N": 50, "repeats": 3,
           "methods": [{{"solver": "hamiltonian",
                         "options": {{"max_iterations": {}, "theta_tolerance": 1e-8}}}},
                       {{"solver": "ipopt", "transcription": "euler"}}{}]}}]}})",
      max_iterations,
      extra_method ? R"(, {"solver": "ipopt", "transcription": "trapezoid"})" : "");
}

class CompareRuns : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new std::string(testing::FreshDirectory("compare-runs"));
    testing::WriteText(*dir_ + "/base.json", CompareSuite(300));
    testing::WriteText(*dir_ + "/worse.json", CompareSuite(5));
    testing::WriteText(*dir_ + "/extra.json", CompareSuite(300, true));
    for (const auto& [suite, out] :
         std::vector<std::pair<std::string, std::string>>{{"base.json", "base"},
                                                          {"base.json", "again"},
                                                          {"worse.json", "worse"},
                                                          {"extra.json", "extra"}}) {
      const ProgramRun run = RunOcpbenchProgram({"run", suite, "--out", out}, *dir_);
      ASSERT_EQ(run.exit_code, 0) << run.err;
    }
  }
  static void TearDownTestSuite() { delete dir_; }

  static ProgramRun CompareProgram(std::vector<std::string> args) {
    args.insert(args.begin(), "compare");
    return RunOcpbenchProgram(args, *dir_);
  }
  static json ReadJson(const std::string& name) {
    return json::parse(testing::ReadText(*dir_ + "/" + name));
  }
  static std::string* dir_;
};
std::string* CompareRuns::dir_ = nullptr;

TEST_F(CompareRuns, ADeliberateChangeIsThatRegressionAndNothingElse) {
  const ProgramRun run = CompareProgram(
      {"base", "worse", "--ignore-option", "max_iterations", "--json", "worse.json.out"});
  ASSERT_EQ(run.exit_code, 1) << run.err;
  const json j = ReadJson("worse.json.out");
  EXPECT_EQ(j["verdict"]["regressed_cases"], 1);
  EXPECT_EQ(j["verdict"]["regressed_methods"], 0);
  EXPECT_EQ(j["verdict"]["matched_cases"], 2);
  EXPECT_EQ(j["verdict"]["only_in_base"], 0);
  EXPECT_EQ(j["verdict"]["only_in_new"], 0);
  for (const json& c : j["cases"]) {
    if (c["method"].get<std::string>().rfind("hamiltonian", 0) == 0) {
      EXPECT_EQ(c["verdict"], "regressed");
      EXPECT_EQ(c["base"]["status"], "converged");
      EXPECT_EQ(c["new"]["status"], "max_iterations");
      EXPECT_EQ(c["base"]["ignored_options"]["max_iterations"], "300");
      EXPECT_EQ(c["new"]["ignored_options"]["max_iterations"], "5");
      std::vector<std::string> worse;
      for (const json& f : c["findings"]) {
        if (f["worse"].get<bool>()) worse.push_back(f["measure"]);
      }
      EXPECT_EQ(worse, (Names{"status", "cost", "terminal viol. fine"})) << c.dump(1);
      EXPECT_GT(c["cost_change"].get<double>(), 1.0);
    } else {
      // The untouched method: the same numbers to the last bit, no finding of any kind.
      EXPECT_EQ(c["verdict"], "unchanged") << c.dump(1);
      EXPECT_EQ(c["cost_change"], 0.0);
      EXPECT_EQ(c["Jbar_fine_change"], 0.0);
      EXPECT_EQ(c["terminal_violation_change"], 0.0);
      EXPECT_EQ(c["base"]["iterations"], c["new"]["iterations"]);
      EXPECT_TRUE(c["findings"].empty());
    }
  }
  EXPECT_NE(run.out.find("## Regressions (1 case)"), std::string::npos) << run.out;
  EXPECT_LT(run.out.find("## Regressions"), run.out.find("## Every matched case"));
}

TEST_F(CompareRuns, IdenticalRunsReportNoChange) {
  const ProgramRun run = CompareProgram({"base", "again", "--json", "again.json.out"});
  ASSERT_EQ(run.exit_code, 0) << run.err << run.out;
  const json j = ReadJson("again.json.out");
  EXPECT_EQ(j["verdict"]["regression"], false);
  EXPECT_EQ(j["verdict"]["improved_cases"], 0);
  ASSERT_EQ(j["cases"].size(), 2u);
  for (const json& c : j["cases"]) {
    EXPECT_EQ(c["cost_change"], 0.0) << c.dump(1);
    EXPECT_EQ(c["Jbar_fine_change"], 0.0);
    EXPECT_EQ(c["base"]["status"], c["new"]["status"]);
    EXPECT_EQ(c["base"]["iterations"], c["new"]["iterations"]);
    EXPECT_TRUE(c["findings"].empty());
    // Two runs' CPU times differ by noise only: with 3 repeats a side a case's rank test
    // cannot fall below p = 0.1, so no CPU verdict is possible, and the ratio is reported.
    // Within a factor 5 even on a loaded machine under the sanitizers (a wrong field, a wrong
    // unit would be far off).
    EXPECT_GT(c["cpu_ratio"].get<double>(), 0.2);
    EXPECT_LT(c["cpu_ratio"].get<double>(), 5.0);
    EXPECT_GE(c["cpu_test"]["p_value"].get<double>(), 0.1 - 1e-12);
    EXPECT_EQ(c["cpu_test"]["n_base"], 3);
  }
  EXPECT_NE(run.out.find("**No regression beyond the thresholds**"), std::string::npos);
  // A run against itself: every CPU ratio is exactly 1 and every p-value 1.
  const ProgramRun self = CompareProgram({"base", "base/records.jsonl", "--json", "self.json.out"});
  ASSERT_EQ(self.exit_code, 0) << self.err;
  const json self_report = ReadJson("self.json.out");  // a named value: the loop reads into it
  for (const json& c : self_report["cases"]) {
    EXPECT_EQ(c["cpu_ratio"], 1.0);
    EXPECT_EQ(c["cpu_test"]["p_value"], 1.0);
  }
}

TEST_F(CompareRuns, CasesInOneSideOnlyAreListed) {
  const ProgramRun added = CompareProgram({"base", "extra", "--json", "added.json.out"});
  EXPECT_EQ(added.exit_code, 0) << added.err;
  const json a = ReadJson("added.json.out");
  ASSERT_EQ(a["only_in_new"].size(), 1u);
  EXPECT_NE(a["only_in_new"][0]["key"].get<std::string>().find("trapezoid"), std::string::npos);
  EXPECT_NE(added.out.find("| only in NEW | double-integrator | ipopt + trapezoid"),
            std::string::npos)
      << added.out;
  // The other way round the case is missing from NEW: its result is unknown, exit 1.
  const ProgramRun missing = CompareProgram({"extra", "base"});
  EXPECT_EQ(missing.exit_code, 1) << missing.err;
  EXPECT_NE(missing.out.find("| only in BASE | double-integrator | ipopt + trapezoid"),
            std::string::npos)
      << missing.out;
}

TEST_F(CompareRuns, InvalidInputIsOneLineAndExitTwoAndWritesNothing) {
  const std::string dir = *dir_;
  std::filesystem::create_directories(dir + "/other");
  std::filesystem::copy_file(dir + "/base/records.jsonl",
                             dir + "/other/records.jsonl",
                             std::filesystem::copy_options::overwrite_existing);
  testing::WriteText(dir + "/other/suite.json", R"({"suite": "paper", "records": 2})");
  std::filesystem::create_directories(dir + "/damaged");
  std::string text = testing::ReadText(dir + "/base/records.jsonl");
  text.replace(text.find("\"iterations\":"), 13, "\"iterations\":\"many\",\"x\":");
  testing::WriteText(dir + "/damaged/records.jsonl", text);
  testing::WriteText(dir + "/stranger.jsonl",
                     R"({"key": "lqr|seed=1|ipopt|euler||N=10", "status": "converged"})"
                     "\n");
  const struct {
    std::vector<std::string> args;
    std::string message;
  } kCases[] = {
      {{"base", "missing"}, "compare: missing: no such file or folder"},
      {{"base", "other"},
       "compare: base is a run of suite 'tiny', other of suite 'paper': not two runs of one "
       "suite"},
      {{"base", "damaged"}, "damaged/records.jsonl:1: iterations: must be an integer"},
      {{"base", "again", "--cpu-ratio", "0.5"},
       "compare option 'cpu_ratio': must be a number >= 1 (got '0.5')"},
      {{"base", "stranger.jsonl"},
       "compare: base and stranger.jsonl have no case in common: not two runs of one suite"},
      {{"base", "again", "--ignore-option", "tol"},
       "--ignore-option 'tol': no case of base or again sets this option"},
      {{"base", "again", "--json", "base"}, "--json 'base': is a folder (expected a file name)"},
      // A side's suite.json is an input too (compare reads the suite's name from it).
      {{"base", "again", "--json", "base/suite.json"},
       "--json base/suite.json: is also BASE base/suite.json (an output never replaces an "
       "input)"},
      {{"base", "again", "--json", "./again/suite.json"},
       "--json ./again/suite.json: is also NEW again/suite.json (an output never replaces an "
       "input)"},
      // A place that cannot take the file is found before the comparison, not after it (exit 3).
      {{"base", "again", "--json", "base/records.jsonl/x.json"},
       "--json base/records.jsonl/x.json: base/records.jsonl is a file, not a folder"},
      {{"base", "again", "--json", "never.md"},
       "--markdown never.md: is also --json never.md (two outputs in one file: one would "
       "replace the other)"},
  };
  for (const auto& c : kCases) {
    std::vector<std::string> args = c.args;
    args.insert(args.end(), {"--markdown", "never.md"});
    const ProgramRun run = CompareProgram(args);
    EXPECT_EQ(run.exit_code, 2) << c.args[1] << ": " << run.err;
    EXPECT_EQ(run.err, "ocpbench: error: " + c.message + "\n");
    EXPECT_TRUE(run.out.empty()) << run.out;
    EXPECT_FALSE(std::filesystem::exists(dir + "/never.md"));
  }
}

}  // namespace
}  // namespace ocpb
