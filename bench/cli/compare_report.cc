#include "bench/cli/compare_report.h"

#include <cmath>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "bench/cli/json_values.h"

namespace ocpb {
namespace {

using nlohmann::json;

std::string ReportNumber(double v) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.4g}", v);
}

std::string PercentText(double relative) {
  if (std::isnan(relative)) return "-";
  if (relative == 0.0) return "0";
  if (std::isinf(relative)) return relative > 0 ? "+inf" : "-inf";
  return fmt::format("{:+.3g} %", 100.0 * relative);
}

// "1 case", "2 cases".
std::string Count(size_t n, const char* noun) {
  return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s");
}

std::string Arrow(const std::string& a, const std::string& b) {
  return a == b ? a : a + " -> " + b;
}

std::string P(const RankTestResult& t) {
  if (t.n_base == 0 || t.n_new == 0) return "-";
  return fmt::format("{:.2g}{}", t.p_value, t.exact ? "" : " (normal approx.)");
}

std::string CommitList(const std::vector<std::string>& commits) {
  std::string s;
  for (const std::string& c : commits) s += (s.empty() ? "" : ", ") + (c.empty() ? "?" : c);
  return s.empty() ? "-" : s;
}

std::string CaseName(const CaseComparison& c) {
  return fmt::format("{}, seed {}", c.section, c.seed);
}

std::string Findings(const std::vector<Finding>& findings, bool worse) {
  std::string s;
  for (const Finding& f : findings) {
    if (f.worse != worse) continue;
    s += (s.empty() ? "" : "; ") + f.measure + ": " + f.detail;
  }
  return s;
}

std::string StatusChanges(const MethodComparison& m) {
  std::string s;
  for (const auto& [change, n] : m.status_changes) {
    s += (s.empty() ? "" : ", ") + fmt::format("{} ({})", change, n);
  }
  return s.empty() ? "none" : s;
}

std::string Range(double median, double lo, double hi) {
  if (std::isnan(median)) return "-";
  if (lo == hi) return PercentText(median);
  return fmt::format("{} [{}, {}]", PercentText(median), PercentText(lo), PercentText(hi));
}

void Verdict(const Comparison& c, std::ostringstream& md) {
  const int cases = c.RegressedCases(), methods = c.RegressedMethods();
  if (c.HasRegression()) {
    md << fmt::format(
        "**Regression: {} of {} matched cases regressed{}{}; {} improved.** `ocpbench compare` "
        "exits 1.\n\n",
        cases,
        c.cases.size(),
        methods > 0 ? fmt::format(", {} methods' CPU time regressed", methods) : "",
        c.only_in_base.empty()
            ? ""
            : fmt::format(", {} cases of BASE are missing from NEW", c.only_in_base.size()),
        c.ImprovedCases());
  } else {
    md << fmt::format(
        "**No regression beyond the thresholds** in {}; {} improved. "
        "`ocpbench compare` exits 0.\n\n",
        Count(c.cases.size(), "matched case"),
        c.ImprovedCases());
  }
}

void Header(const Comparison& c, std::ostringstream& md) {
  md << "# `ocpbench compare`: NEW against BASE\n\n";
  md << "| | BASE | NEW |\n|---|---|---|\n";
  md << fmt::format("| path | `{}` | `{}` |\n", c.base_path, c.new_path);
  md << fmt::format("| suite | {} | {} |\n",
                    c.base_suite.empty() ? "(a records file)" : c.base_suite,
                    c.new_suite.empty() ? "(a records file)" : c.new_suite);
  md << fmt::format("| records | {} | {} |\n", c.base_records, c.new_records);
  md << fmt::format(
      "| commit | {} | {} |\n\n", CommitList(c.base_commits), CommitList(c.new_commits));
  for (const auto& [dropped, path] :
       {std::pair{c.base_dropped_partial, c.base_path}, {c.new_dropped_partial, c.new_path}}) {
    if (dropped) {
      md << "The last line of `" << path
         << "`'s records was cut short (a killed run) and is left out.\n\n";
    }
  }
  Verdict(c, md);
  if (std::isfinite(c.overall_cpu_ratio)) {
    md << fmt::format(
        "CPU over all matched cases: geometric mean of the ratios x {:.3g}. Where every method "
        "shows about this ratio, the shift is the machine's (its load, its clock), not the "
        "code's: compare CPU of runs made back to back on one machine.\n\n",
        c.overall_cpu_ratio);
  }
  const CompareThresholds& t = c.options.thresholds;
  md << fmt::format(
      "Thresholds: cost (final J fine) {:g} relative; violations +{:g} and +{:g} x base; CPU "
      "ratio {:g} (or 1/{:g}) with the Mann-Whitney U test at alpha = {:g}.",
      t.cost,
      t.violation_abs,
      t.violation_rel,
      t.cpu_ratio,
      t.cpu_ratio,
      t.alpha);
  if (!c.options.ignore_options.empty()) {
    std::string names;
    for (const std::string& n : c.options.ignore_options) names += (names.empty() ? "" : ", ") + n;
    md << " Cases are matched without the options " << names
       << " (their values on each side are in the case table).";
  }
  md << "\n\n";
}

void FindingsSection(const Comparison& c, bool worse, std::ostringstream& md) {
  std::vector<const CaseComparison*> cases;
  for (const CaseComparison& cc : c.cases) {
    if (worse ? cc.Regressed() : cc.Improved()) cases.push_back(&cc);
  }
  std::vector<const MethodComparison*> methods;
  for (const MethodComparison& m : c.methods) {
    for (const Finding& f : m.findings) {
      if (f.worse == worse) {
        methods.push_back(&m);
        break;
      }
    }
  }
  md << "## " << (worse ? "Regressions" : "Improvements") << " (" << Count(cases.size(), "case")
     << (methods.empty() ? "" : ", " + Count(methods.size(), "method")) << ")\n\n";
  if (cases.empty() && methods.empty()) {
    md << "None.\n\n";
    return;
  }
  if (!cases.empty()) {
    md << "| case | method | " << (worse ? "worse" : "better")
       << " | status |\n|---|---|---|---|\n";
    for (const CaseComparison* cc : cases) {
      md << fmt::format("| {} | {} | {} | {} |\n",
                        CaseName(*cc),
                        cc->method,
                        Findings(cc->findings, worse),
                        Arrow(cc->base.status, cc->next.status));
    }
    md << "\n";
  }
  if (!methods.empty()) {
    md << "| problem | method | " << (worse ? "worse" : "better") << " |\n|---|---|---|\n";
    for (const MethodComparison* m : methods) {
      md << fmt::format("| {} | {} | {} |\n", m->section, m->method, Findings(m->findings, worse));
    }
    md << "\n";
  }
}

void Unmatched(const Comparison& c, std::ostringstream& md) {
  md << fmt::format("## Cases in one side only ({} only in BASE, {} only in NEW)\n\n",
                    c.only_in_base.size(),
                    c.only_in_new.size());
  if (c.only_in_base.empty() && c.only_in_new.empty()) {
    md << "None: every case was matched.\n\n";
    return;
  }
  md << "A case of BASE missing from NEW counts as a regression (its result is unknown); a case "
        "only in NEW is listed.\n\n";
  md << "| side | problem | method | status | key |\n|---|---|---|---|---|\n";
  for (const auto& [side, list] :
       {std::pair{"only in BASE", &c.only_in_base}, {"only in NEW", &c.only_in_new}}) {
    for (const UnmatchedCase& u : *list) {
      md << fmt::format(
          "| {} | {} | {} | {} | `{}` |\n", side, u.section, u.method, u.status, u.key);
    }
  }
  md << "\n";
}

void Methods(const Comparison& c, std::ostringstream& md) {
  md << "## Per method and problem\n\n"
        "Changes are NEW against BASE: cost (final J fine) and Jbar fine relative, median [min, "
        "max] over the cases; violations the worst case of each side; iterations medians; CPU the "
        "geometric mean of the cases' ratios of median CPU times with the p-value of the "
        "Mann-Whitney U test stratified over the cases; time to target the median over the cases "
        "that reached it (against one target for both sides), n/m reached.\n\n";
  md << "| problem | method | cases | regressed / improved | status changes | cost | Jbar fine | "
        "terminal viol. fine | path viol. | iterations | CPU ratio | CPU p | time to target s |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const MethodComparison& m : c.methods) {
    md << fmt::format(
        "| {} | {} | {} | {} / {} | {} | {} | {} | {} | {} | {} | {} | {} | {} ({}/{}) -> {} "
        "({}/{}) |\n",
        m.section,
        m.method,
        m.cases,
        m.regressed,
        m.improved,
        StatusChanges(m),
        Range(m.cost_change_median, m.cost_change_min, m.cost_change_max),
        Range(m.Jbar_fine_change_median, m.Jbar_fine_change_min, m.Jbar_fine_change_max),
        Arrow(ReportNumber(m.terminal_violation_base), ReportNumber(m.terminal_violation_new)),
        Arrow(ReportNumber(m.path_violation_base), ReportNumber(m.path_violation_new)),
        Arrow(ReportNumber(m.iterations_base), ReportNumber(m.iterations_new)),
        ReportNumber(m.cpu_ratio),
        P(m.cpu_test),
        ReportNumber(m.time_to_target_base),
        m.reached_base,
        m.cases,
        ReportNumber(m.time_to_target_new),
        m.reached_new,
        m.cases);
  }
  md << "\n";
}

void WriteProfiles(const Comparison& c, std::ostringstream& md) {
  md << "## Time to target: performance profiles\n\n"
        "Dolan-More profile of the CPU time to target over the matched cases' target groups "
        "(problem, seed, parameters, terminal form), every method on each side one solver of a "
        "single profile, so that both sides are measured against the same best time: rho(tau) "
        "is the fraction of the method's groups where its time is within tau times the best "
        "(times below 1e-6 s count as 1e-6 s, as in results/plot.py); ever = reached at all. Two "
        "runs of an unchanged method split the wins at tau = 1 by timing noise alone: read tau "
        ">= 2 for speed.\n\n";
  if (c.profiles.empty()) {
    md << "No group has a time to target.\n\n";
    return;
  }
  md << "| method | groups | rho(1) | rho(2) | rho(4) | rho(10) | ever |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const ProfileComparison& p : c.profiles) {
    md << "| " << p.method << " | " << p.instances << " |";
    for (size_t i = 0; i < kProfileTaus.size(); ++i) {
      md << " " << Arrow(fmt::format("{:.2f}", p.base[i]), fmt::format("{:.2f}", p.next[i]))
         << " |";
    }
    md << "\n";
  }
  md << "\n";
}

void Cases(const Comparison& c, std::ostringstream& md) {
  const bool ignored = !c.options.ignore_options.empty();
  md << "## Every matched case\n\n";
  md << "| case | method |" << (ignored ? " ignored options |" : "")
     << " status | cost | cost change | Jbar fine change | terminal viol. fine | path viol. | "
        "iterations | CPU s | CPU ratio | CPU p | time to target s |\n|---|---|"
     << (ignored ? "---|" : "") << "---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const CaseComparison& cc : c.cases) {
    md << "| " << CaseName(cc) << " | " << cc.method << " |";
    if (ignored) {
      std::string o;
      for (const auto& [name, value] : cc.base.ignored_options) {
        o += (o.empty() ? "" : ", ") + name + " " + Arrow(value, cc.next.ignored_options.at(name));
      }
      md << " " << o << " |";
    }
    md << fmt::format(
        " {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
        Arrow(cc.base.status, cc.next.status),
        Arrow(ReportNumber(cc.base.cost), ReportNumber(cc.next.cost)),
        PercentText(cc.cost_change),
        PercentText(cc.Jbar_fine_change),
        Arrow(ReportNumber(cc.base.terminal_violation), ReportNumber(cc.next.terminal_violation)),
        Arrow(ReportNumber(cc.base.path_violation), ReportNumber(cc.next.path_violation)),
        Arrow(cc.base.iterations >= 0 ? std::to_string(cc.base.iterations) : "-",
              cc.next.iterations >= 0 ? std::to_string(cc.next.iterations) : "-"),
        Arrow(ReportNumber(cc.base.cpu_seconds), ReportNumber(cc.next.cpu_seconds)),
        ReportNumber(cc.cpu_ratio),
        P(cc.cpu_test),
        Arrow(ReportNumber(cc.base.time_to_target), ReportNumber(cc.next.time_to_target)));
  }
  md << "\n";
}

void HowToRead(const Comparison& c, std::ostringstream& md) {
  std::set<std::pair<int, int>> sizes;
  for (const CaseComparison& cc : c.cases) {
    if (cc.cpu_test.n_base > 0) sizes.insert({cc.cpu_test.n_base, cc.cpu_test.n_new});
  }
  std::string smallest;
  for (const auto& [b, n] : sizes) {
    smallest += (smallest.empty() ? "" : ", ") +
                fmt::format("{} vs {} repeats: {:.2g}", b, n, SmallestTwoSidedP(b, n));
  }
  md << "## How to read this\n\n"
        "- Cases are matched by their key (every field that changes a result); a case found on "
        "one side only is listed above, never dropped.\n"
        "- A case regressed when any measure moved beyond its threshold the wrong way: its status "
        "fell to a worse tier (converged < acceptable < limits such as max_iterations < "
        "not_applicable < failures: converged -> max_iterations is a regression whatever the "
        "cost), its cost (final J fine; in the hard terminal form only when both sides "
        "converged) rose by more than the cost threshold, a violation rose by more than both "
        "violation thresholds, or its CPU ratio passed the CPU threshold with a significant rank "
        "test. Jbar fine, iterations and time to target are reported, not judged.\n"
        "- CPU: the two-sided Mann-Whitney U test over the per-repeat CPU times (exact "
        "permutation distribution, ties included, up to 60 repeats in all; normal approximation "
        "beyond). A rank test because timing noise on a shared machine is one-sided and heavy-"
        "tailed (a repeat that meets a busy moment is much slower, never much faster), which "
        "pulls means and t intervals but not ranks. Per method, the test is stratified over the "
        "cases (each case's repeats permuted within the case). It cannot tell a slower method "
        "from a busier machine: runs compared for CPU should be made on the same machine under "
        "similar load.\n"
        "- What the repeats allow: with 1 repeat per side no single case can show anything "
        "(p = 1), and the per-method test is a sign test over the cases (5 cases all slower: "
        "p = 0.0625); with 3 vs 3 the smallest p of a case is 0.1, so at alpha = 0.05 only the "
        "per-method test can find a CPU change; 4 vs 4 repeats reach 0.029, 5 vs 5 0.0079.";
  if (!smallest.empty()) md << " Here, the smallest p of a case: " << smallest << ".";
  md << "\n\n";
}

json Side(const CaseSide& s) {
  json ignored = json::object();
  for (const auto& [k, v] : s.ignored_options) ignored[k] = v;
  return json{{"status", s.status},
              {"solver_status", s.solver_status},
              {"cost", JsonNumber(s.cost)},
              {"Jbar_fine", JsonNumber(s.Jbar_fine)},
              {"terminal_violation_fine", JsonNumber(s.terminal_violation)},
              {"path_violation", JsonNumber(s.path_violation)},
              {"iterations", s.iterations},
              {"cpu_seconds", JsonNumber(s.cpu_seconds)},
              {"cpu_seconds_repeats", s.cpu_repeats},
              {"time_to_target", JsonNumber(s.time_to_target)},
              {"ignored_options", ignored},
              {"commit", s.commit}};
}

json Test(const RankTestResult& t) {
  return json{{"u", t.u},
              {"mean_u", t.mean_u},
              {"p_value", t.p_value},
              {"exact", t.exact},
              {"n_base", t.n_base},
              {"n_new", t.n_new}};
}

json FindingsJson(const std::vector<Finding>& findings) {
  json a = json::array();
  for (const Finding& f : findings) {
    a.push_back({{"measure", f.measure}, {"worse", f.worse}, {"detail", f.detail}});
  }
  return a;
}

std::string Verdict(const CaseComparison& c) {
  if (c.Regressed()) return "regressed";
  if (c.Improved()) return "improved";
  return "unchanged";
}

json UnmatchedJson(const std::vector<UnmatchedCase>& list) {
  json a = json::array();
  for (const UnmatchedCase& u : list) {
    a.push_back(
        {{"key", u.key}, {"section", u.section}, {"method", u.method}, {"status", u.status}});
  }
  return a;
}

}  // namespace

std::string CompareMarkdown(const Comparison& c) {
  std::ostringstream md;
  Header(c, md);
  FindingsSection(c, /*worse=*/true, md);
  Unmatched(c, md);
  FindingsSection(c, /*worse=*/false, md);
  Methods(c, md);
  WriteProfiles(c, md);
  Cases(c, md);
  HowToRead(c, md);
  return md.str();
}

namespace {

// Written key by key rather than as nested initializer lists: the same document (nlohmann
// sorts object keys), but a sanitizer build spent about 18 s compiling the list form.
json CompareCaseJson(const CaseComparison& cc) {
  json j;
  j["key"] = cc.key;
  j["section"] = cc.section;
  j["method"] = cc.method;
  j["group"] = cc.group;
  j["seed"] = cc.seed;
  j["verdict"] = Verdict(cc);
  j["findings"] = FindingsJson(cc.findings);
  j["base"] = Side(cc.base);
  j["new"] = Side(cc.next);
  j["cost_change"] = JsonNumber(cc.cost_change);
  j["Jbar_fine_change"] = JsonNumber(cc.Jbar_fine_change);
  j["terminal_violation_change"] = JsonNumber(cc.terminal_violation_change);
  j["path_violation_change"] = JsonNumber(cc.path_violation_change);
  j["cpu_ratio"] = JsonNumber(cc.cpu_ratio);
  j["cpu_test"] = Test(cc.cpu_test);
  return j;
}

// {"base": base, "new": next} of two numbers, the shape of every before/after pair.
json CompareBaseNew(double base, double next) {
  json j;
  j["base"] = JsonNumber(base);
  j["new"] = JsonNumber(next);
  return j;
}

json CompareMedianMinMax(double median, double min, double max) {
  json j;
  j["median"] = JsonNumber(median);
  j["min"] = JsonNumber(min);
  j["max"] = JsonNumber(max);
  return j;
}

json CompareMethodJson(const MethodComparison& m) {
  json changes = json::object();
  for (const auto& [k, n] : m.status_changes) changes[k] = n;
  json j;
  j["section"] = m.section;
  j["method"] = m.method;
  j["cases"] = m.cases;
  j["regressed"] = m.regressed;
  j["improved"] = m.improved;
  j["status_changes"] = changes;
  j["cost_change"] =
      CompareMedianMinMax(m.cost_change_median, m.cost_change_min, m.cost_change_max);
  j["Jbar_fine_change"] = CompareMedianMinMax(
      m.Jbar_fine_change_median, m.Jbar_fine_change_min, m.Jbar_fine_change_max);
  j["terminal_violation_fine"] =
      CompareBaseNew(m.terminal_violation_base, m.terminal_violation_new);
  j["path_violation"] = CompareBaseNew(m.path_violation_base, m.path_violation_new);
  j["iterations"] = CompareBaseNew(m.iterations_base, m.iterations_new);
  j["cpu_ratio"] = JsonNumber(m.cpu_ratio);
  j["cpu_test"] = Test(m.cpu_test);
  json time_to_target = CompareBaseNew(m.time_to_target_base, m.time_to_target_new);
  time_to_target["reached_base"] = m.reached_base;
  time_to_target["reached_new"] = m.reached_new;
  j["time_to_target"] = time_to_target;
  j["findings"] = FindingsJson(m.findings);
  return j;
}

json CompareProfileJson(const ProfileComparison& p) {
  json taus = json::array(), base = json::array(), next = json::array();
  for (size_t i = 0; i < kProfileTaus.size(); ++i) {
    taus.push_back(std::isinf(kProfileTaus[i]) ? json("inf") : json(kProfileTaus[i]));
    base.push_back(p.base[i]);
    next.push_back(p.next[i]);
  }
  json j;
  j["method"] = p.method;
  j["groups"] = p.instances;
  j["tau"] = taus;
  j["base"] = base;
  j["new"] = next;
  return j;
}

json CompareRunJson(const std::string& path,
                    const std::string& suite,
                    size_t records,
                    const std::vector<std::string>& commits,
                    bool dropped_partial) {
  json j;
  j["path"] = path;
  j["suite"] = suite;
  j["records"] = records;
  j["commits"] = commits;
  j["dropped_partial"] = dropped_partial;
  return j;
}

}  // namespace

json CompareJson(const Comparison& c) {
  const CompareThresholds& t = c.options.thresholds;
  json cases = json::array();
  for (const CaseComparison& cc : c.cases) cases.push_back(CompareCaseJson(cc));
  json methods = json::array();
  for (const MethodComparison& m : c.methods) methods.push_back(CompareMethodJson(m));
  json profiles = json::array();
  for (const ProfileComparison& p : c.profiles) profiles.push_back(CompareProfileJson(p));
  json thresholds;
  thresholds["cost"] = t.cost;
  thresholds["violation_abs"] = t.violation_abs;
  thresholds["violation_rel"] = t.violation_rel;
  thresholds["cpu_ratio"] = t.cpu_ratio;
  thresholds["alpha"] = t.alpha;
  json verdict;
  verdict["regression"] = c.HasRegression();
  verdict["regressed_cases"] = c.RegressedCases();
  verdict["improved_cases"] = c.ImprovedCases();
  verdict["regressed_methods"] = c.RegressedMethods();
  verdict["matched_cases"] = c.cases.size();
  verdict["only_in_base"] = c.only_in_base.size();
  verdict["only_in_new"] = c.only_in_new.size();
  verdict["overall_cpu_ratio"] = JsonNumber(c.overall_cpu_ratio);
  json j;
  j["base"] = CompareRunJson(
      c.base_path, c.base_suite, c.base_records, c.base_commits, c.base_dropped_partial);
  j["new"] =
      CompareRunJson(c.new_path, c.new_suite, c.new_records, c.new_commits, c.new_dropped_partial);
  j["thresholds"] = thresholds;
  j["ignore_options"] = c.options.ignore_options;
  j["verdict"] = verdict;
  j["cases"] = cases;
  j["only_in_base"] = UnmatchedJson(c.only_in_base);
  j["only_in_new"] = UnmatchedJson(c.only_in_new);
  j["methods"] = methods;
  j["profiles"] = profiles;
  return j;
}

}  // namespace ocpb
