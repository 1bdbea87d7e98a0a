// The target rule of DeriveTargets and the reference column of SummaryMarkdown, on synthetic
// records shaped like those `ocpbench run` writes (bench/cli/case_runner.cc).
#include "bench/cli/summary.h"

#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

namespace ocpb {
namespace {

using nlohmann::json;

json History(std::vector<std::vector<double>> entries) {  // {J, cpu_seconds[, primal_inf]}
  json h = json::array();
  for (size_t i = 0; i < entries.size(); ++i) {
    const auto& e = entries[i];
    h.push_back({{"iteration", i},
                 {"J", e[0]},
                 {"cpu_seconds", e[1]},
                 {"primal_inf", e.size() > 2 ? json(e[2]) : json(nullptr)}});
  }
  return h;
}

json MakeRecord(const std::string& solver,
                const std::string& transcription,
                double J,
                double J_fine,
                const std::string& terminal = "penalty",
                const std::string& status = "converged") {
  return json{{"problem", "p"},
              {"seed", 1},
              {"parameters", {{"C", 10.0}}},
              {"solver", solver},
              {"transcription", transcription},
              {"algorithm", ""},
              {"N", 100},
              {"terminal", terminal},
              {"integrator", "euler"},
              {"evaluated_with", "euler"},
              {"options", json::object()},
              {"status", status},
              {"J", J},
              {"J_fine", J_fine},
              {"cpu_seconds", 2.0},
              {"history", json::array()}};
}

std::vector<Record> Typed(const std::vector<json>& records) {
  std::vector<Record> out;
  for (const json& r : records) out.push_back(Record::FromJson(r));
  return out;
}

// The records as derived.jsonl holds them: each with its derived fields.
std::vector<json> Derived(const std::vector<json>& records) {
  return DerivedRecordsJson(Typed(records));
}

std::string SummaryMarkdown(const std::string& name, const std::vector<json>& records) {
  return ocpb::SummaryMarkdown(name, Typed(records));
}

TEST(DeriveTargets, TheBestIsTheLowestJFineNotTheMethodGridJ) {
  // A collocation method: its J on the Euler grid is 1% above the Euler NLP's, its J_fine lower.
  auto r = Derived(
      {MakeRecord("ipopt", "euler", 474.3, 474.4), MakeRecord("ipopt", "trapezoid", 479.6, 474.2)});
  EXPECT_DOUBLE_EQ(r[0]["best_J"].get<double>(), 474.2);
  EXPECT_DOUBLE_EQ(r[1]["final_J"].get<double>(), 474.2);
  EXPECT_TRUE(r[0]["reached_target"].get<bool>());
  EXPECT_TRUE(r[1]["reached_target"].get<bool>());
}

TEST(DeriveTargets, JStandsInWhereJFineIsMissing) {
  json a = MakeRecord("hamiltonian", "", 10.0, 0.0);
  a["J_fine"] = nullptr;
  auto r = Derived({a, MakeRecord("ipopt", "euler", 12.0, 11.0)});
  EXPECT_DOUBLE_EQ(r[0]["final_J"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(r[1]["best_J"].get<double>(), 10.0);
  EXPECT_FALSE(r[1]["reached_target"].get<bool>());
}

TEST(DeriveTargets, InTheHardFormOnlyConvergedRecordsSetTheBest) {
  auto r = Derived({MakeRecord("ipopt", "euler", 100.0, 100.0, "hard"),
                    MakeRecord("ipopt", "lgr", 50.0, 50.0, "hard", "max_iterations")});
  EXPECT_DOUBLE_EQ(r[0]["best_J"].get<double>(), 100.0);
  // ... and a non-converged record far from the best (below it) has not reached it.
  EXPECT_FALSE(r[1]["reached_target"].get<bool>());
  EXPECT_TRUE(r[1]["time_to_target"].is_null());
  // In the penalty form every finite record counts.
  auto p = Derived({MakeRecord("ipopt", "euler", 100.0, 100.0),
                    MakeRecord("ipopt", "lgr", 50.0, 50.0, "penalty", "max_iterations")});
  EXPECT_DOUBLE_EQ(p[0]["best_J"].get<double>(), 50.0);
}

TEST(DeriveTargets, AFinalJFineMoreThanOnePercentOffNeverReachesItWhateverTheHistory) {
  json far = MakeRecord("ipopt", "lgr", 2470.0, 480.0);  // 1.2% above the best J_fine
  far["history"] = History({{500.0, 0.1}, {474.0, 0.2}});
  auto r = Derived({MakeRecord("ipopt", "euler", 474.0, 474.0), far});
  EXPECT_FALSE(r[1]["reached_target"].get<bool>());
  EXPECT_TRUE(r[1]["time_to_target"].is_null());
}

TEST(DeriveTargets, TheFirstFeasibleIterateWithinOnePercentGivesTheTime) {
  json a = MakeRecord("ipopt", "euler", 474.0, 474.0);
  // Iterate 1 is within 1% but infeasible (primal_inf 3.9e-4), iterate 2 is too far, iterate 3
  // qualifies; the rule holds in the penalty form as well.
  a["history"] =
      History({{600.0, 0.1, 1.0}, {475.0, 0.2, 3.9e-4}, {490.0, 0.3, 0.0}, {474.5, 0.4, 1e-7}});
  auto r = Derived({a});
  EXPECT_DOUBLE_EQ(r[0]["time_to_target"].get<double>(), 0.4);
  // The same in the hard form.
  a["terminal"] = "hard";
  EXPECT_DOUBLE_EQ(Derived({a})[0]["time_to_target"].get<double>(), 0.4);
}

TEST(DeriveTargets, AnIterateWithoutPrimalInfeasibilityCounts) {
  json h = MakeRecord("hamiltonian", "", 474.0, 474.0);
  h["history"] = History({{900.0, 0.1}, {478.0, 0.25}, {474.0, 0.5}});
  EXPECT_DOUBLE_EQ(Derived({h})[0]["time_to_target"].get<double>(), 0.25);
}

TEST(DeriveTargets, IteratesOfACoarserGridDoNotCount) {
  // A grid-sequenced solve: rows 0-1 on a 100-interval grid (their J is that grid's, here
  // within 1 % of the best), row 2 the first on the request's grid within 1 %. The record's
  // intervals survive the reader.
  json h = MakeRecord("hamiltonian-polish", "", 474.0, 474.0);
  h["history"] = History({{900.0, 0.1}, {474.1, 0.2}, {474.0, 0.3}});
  h["history"][0]["intervals"] = 100;
  h["history"][1]["intervals"] = 100;
  EXPECT_EQ(Record::FromJson(h).history[1].intervals, 100);
  EXPECT_EQ(Record::FromJson(h).history[2].intervals, -1);
  EXPECT_DOUBLE_EQ(Derived({h})[0]["time_to_target"].get<double>(), 0.3);
  EXPECT_EQ(Derived({h})[0]["history"][1]["intervals"], 100);
  EXPECT_FALSE(Derived({h})[0]["history"][2].contains("intervals"));
  h["history"][1]["intervals"] = 0;
  EXPECT_THROW(Record::FromJson(h), std::invalid_argument);
}

TEST(DeriveTargets, WithoutAQualifyingIterateTheTotalCpuTimeCounts) {
  // The history holds the method's own objective (here its trapezoid quadrature, 1.1% above).
  json t = MakeRecord("ipopt", "trapezoid", 479.6, 474.3);
  t["history"] = History({{600.0, 0.1, 0.0}, {479.5, 0.3, 0.0}});
  auto r = Derived({MakeRecord("ipopt", "euler", 474.2, 474.2), t});
  EXPECT_TRUE(r[1]["reached_target"].get<bool>());
  EXPECT_DOUBLE_EQ(r[1]["time_to_target"].get<double>(), 2.0);
}

TEST(DeriveTargets, GroupsSplitBySeedParametersAndTerminalForm) {
  json seed2 = MakeRecord("ipopt", "euler", 10.0, 10.0);
  seed2["seed"] = 2;
  json c500 = MakeRecord("ipopt", "euler", 20.0, 20.0);
  c500["parameters"]["C"] = 500.0;
  json hard = MakeRecord("ipopt", "euler", 30.0, 30.0, "hard");
  auto r = Derived({MakeRecord("ipopt", "euler", 40.0, 40.0), seed2, c500, hard});
  EXPECT_DOUBLE_EQ(r[0]["best_J"].get<double>(), 40.0);
  EXPECT_DOUBLE_EQ(r[1]["best_J"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(r[2]["best_J"].get<double>(), 20.0);
  EXPECT_DOUBLE_EQ(r[3]["best_J"].get<double>(), 30.0);
  EXPECT_NE(r[0]["section"], r[2]["section"]);  // C splits the tables
}

TEST(DeriveTargets, RecordsWithoutACostHaveNoTarget) {
  json na = MakeRecord("hamiltonian", "", 0.0, 0.0, "penalty", "not_applicable");
  na["J"] = nullptr;
  na["J_fine"] = nullptr;
  auto r = Derived({na});
  EXPECT_TRUE(r[0]["best_J"].is_null());
  EXPECT_TRUE(r[0]["final_J"].is_null());
  EXPECT_FALSE(r[0]["reached_target"].get<bool>());
}

TEST(DeriveTargets, OptionsNameRowsOnlyWhereTheyTellMethodsApart) {
  json cold = MakeRecord("indirect-newton", "", 1.0, 1.0);
  json warm = cold;
  warm["options"] = {{"warm_start", "hamiltonian"}};
  auto r = Derived({cold, warm, MakeRecord("ipopt", "euler", 1.0, 1.0)});
  EXPECT_EQ(r[0]["method_label"], "indirect-newton, penalty, N=100, default options");
  EXPECT_EQ(r[1]["method_label"], "indirect-newton, penalty, N=100, warm_start=hamiltonian");
  EXPECT_EQ(r[2]["method_label"], "ipopt + euler, penalty, N=100");
  // The summary's rows carry the same labels.
  const std::string md = SummaryMarkdown("s", r);
  EXPECT_NE(md.find("| indirect-newton, penalty, N=100, warm_start=hamiltonian |"),
            std::string::npos);
}

// ---- the reference column

json WithReference(json r, const std::string& scheme, int N) {
  r["reference"] = {{"value", 2.0}, {"quantity", "J"}, {"source", "test"}};
  if (!scheme.empty()) r["reference"]["scheme"] = scheme;
  if (N > 0) r["reference"]["N"] = N;
  return r;
}

// The last cell of the table row that starts with `label`.
std::string LastCell(const std::string& md, const std::string& label) {
  const size_t row = md.find("| " + label + " |");
  if (row == std::string::npos) return "(no row)";
  const size_t end = md.find(" |\n", row);
  const size_t start = md.rfind("| ", end - 1);
  return md.substr(start + 2, end - start - 2);
}

TEST(SummaryMarkdown, AContinuousReferenceIsComparedWithEveryRowsJbarFine) {
  json a = MakeRecord("ipopt", "euler", 2.5, 2.4, "hard");
  a["Jbar_fine"] = 2.2;
  json b = MakeRecord("ipopt", "lgr", 2.5, 2.4, "hard");
  b["Jbar_fine"] = 2.02;
  b["N"] = 25;
  std::vector<json> r = {WithReference(a, "continuous", 0), WithReference(b, "continuous", 0)};
  const std::string md = SummaryMarkdown("s", r);
  EXPECT_EQ(LastCell(md, "ipopt + euler, hard, N=100"), "0.1");
  EXPECT_EQ(LastCell(md, "ipopt + lgr, hard, N=25"), "0.01");
}

TEST(SummaryMarkdown, ADiscreteReferenceIsComparedOnlyAtItsSchemeGridAndHardForm) {
  json at = MakeRecord("ipopt", "trapezoid", 2.5, 2.4, "hard");
  at["objective"] = 2.002;
  at["Jbar_fine"] = 2.4;
  json other_scheme = at;
  other_scheme["transcription"] = "hermite-simpson";
  json other_grid = at;
  other_grid["N"] = 50;
  json penalty = at;
  penalty["terminal"] = "penalty";
  std::vector<json> r;
  for (const json& x : {at, other_scheme, other_grid, penalty}) {
    r.push_back(WithReference(x, "trapezoid", 100));
  }
  const std::string md = SummaryMarkdown("s", r);
  EXPECT_EQ(LastCell(md, "ipopt + trapezoid, hard, N=100"), "0.001");  // |objective - 2| / 2
  EXPECT_EQ(LastCell(md, "ipopt + hermite-simpson, hard, N=100"), "-");
  EXPECT_EQ(LastCell(md, "ipopt + trapezoid, hard, N=50"), "-");
  EXPECT_EQ(LastCell(md, "ipopt + trapezoid, penalty, N=100"), "-");
}

TEST(SummaryMarkdown, AReferenceOfUnknownSchemeIsComparedWithNothing) {
  std::vector<json> r = {WithReference(MakeRecord("ipopt", "euler", 2.5, 2.4, "hard"), "", 0)};
  r[0]["Jbar_fine"] = 2.0;
  EXPECT_EQ(LastCell(SummaryMarkdown("s", r), "ipopt + euler, hard, N=100"), "-");
}

TEST(SummaryMarkdown, RowsShowJbarAndTheResimulationDefect) {
  json a = MakeRecord("ipopt", "trapezoid", 3.0, 2.0);
  a["Jbar"] = 2.75;
  a["resimulation_defect"] = 4.5e-5;
  json b = a;
  b["seed"] = 2;
  b["Jbar"] = 2.25;
  b["resimulation_defect"] = 1.5e-3;
  std::vector<json> r = {a, b};
  const std::string md = SummaryMarkdown("s", r);
  EXPECT_NE(md.find("| J | Jbar | J fine | Jbar fine |"), std::string::npos);
  EXPECT_NE(md.find("| resim. defect |"), std::string::npos);
  EXPECT_NE(md.find("| 2.5 [2.25, 2.75] |"), std::string::npos);  // Jbar over the seeds
  EXPECT_NE(md.find("| 0.0015 |"), std::string::npos);            // the worst defect
}

// An Ipopt stop at its acceptable level is its own status in the table, never counted as
// converged (the case: neighbouring runs 30x more accurate), and it is not a best in
// the hard form.
TEST(SummaryMarkdown, KeepsAcceptableApartFromConverged) {
  json a = MakeRecord("ipopt", "euler", 474.3, 474.30, "hard", "converged");
  json b = a;
  b["seed"] = 2;
  b["status"] = "acceptable";
  const std::string md = SummaryMarkdown("s", {a, b});
  EXPECT_NE(md.find("| 1 acceptable, 1 converged |"), std::string::npos) << md;
  json c = b;
  c["seed"] = 1;
  c["transcription"] = "trapezoid";
  c["J_fine"] = 474.0;  // lower, but acceptable only: not the hard form's best
  const auto d = Derived({a, c});
  EXPECT_DOUBLE_EQ(d[0]["best_J"].get<double>(), 474.30);
}

TEST(SummaryMarkdown, ShowsEachRowsWarningsAndTheirFirstMessage) {
  json a = MakeRecord("indirect-newton", "", 15.8, 114.2);
  a["warnings"] = json::array({{{"code", "discretization"}, {"message", "7x off on this grid"}}});
  json b = MakeRecord("ipopt", "euler", 6.0, 6.0);
  b["warnings"] = json::array();
  const std::string md = SummaryMarkdown("s", {a, b});
  EXPECT_NE(md.find("| status | warnings |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 1 converged | 1 discretization |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 1 converged | - |"), std::string::npos) << md;
  EXPECT_NE(md.find("discretization (1 of 1 cases), for example: 7x off on this grid"),
            std::string::npos)
      << md;
}

}  // namespace
}  // namespace ocpb
