#include "bench/cli/compare.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "bench/cli/case_runner.h"
#include "bench/cli/io.h"
#include "bench/cli/json_input.h"
#include "bench/cli/json_values.h"
#include "bench/cli/performance_profile.h"
#include "bench/cli/records_file.h"
#include "bench/cli/summary.h"
#include "core/option_binding.h"
#include "core/solve_result.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// results/plot.py's floor for times to target: a first iterate on target would otherwise make
// every other ratio infinite.
constexpr double kTimeFloor = 1e-6;

// Every threshold is a number: one table states each once, for the schema and for resolving.
struct ThresholdField {
  const char* name;
  double CompareThresholds::*field;
  const char* doc;
  OptionBounds bounds;
};

const std::vector<ThresholdField>& ThresholdFields() {
  using T = CompareThresholds;
  static const std::vector<ThresholdField> fields = {
      {"cost",
       &T::cost,
       "a case's cost (final J fine) is worse when it rises by more than this fraction of |base| "
       "(hard terminal form: only when both sides converged)",
       OptionBounds::AtLeast(0)},
      {"violation_abs",
       &T::violation_abs,
       "a violation (terminal fine, path) is worse when it rises by more than this and by more "
       "than violation_rel times its base value",
       OptionBounds::AtLeast(0)},
      {"violation_rel",
       &T::violation_rel,
       "the relative part of the violation rule (see violation_abs)",
       OptionBounds::AtLeast(0)},
      {"cpu_ratio",
       &T::cpu_ratio,
       "CPU is worse when new / base median CPU exceeds this and the rank test of the repeats is "
       "significant at alpha (better: below 1 / cpu_ratio)",
       OptionBounds::AtLeast(1)},
      {"alpha",
       &T::alpha,
       "significance level of the two-sided Mann-Whitney U test of the timing repeats",
       OptionBounds::Open(0, 1)},
  };
  return fields;
}

// The schema through OptionBinding (defaults read from the struct). Values are written by the
// table rather than OptionBinding::Apply: GCC 12 at -O2 reports a false -Warray-bounds in
// Apply's nested-option branch for an options struct smaller than an OptionMap.
const OptionBinding<CompareThresholds>& Binding() {
  static const OptionBinding<CompareThresholds> table = [] {
    OptionBinding<CompareThresholds> t("compare");
    for (const ThresholdField& f : ThresholdFields()) t.Number(f.name, f.field, f.doc, f.bounds);
    return t;
  }();
  return table;
}

// ---- reading one side ------------------------------------------------------------------------

// The suite's name from a result folder's suite.json ({"suite": NAME, "records": n}); empty
// when the folder has none.
std::string SuiteName(const std::string& dir) {
  const std::string path = (fs::path(dir) / "suite.json").string();
  if (!fs::exists(path)) return "";
  // Size and nesting limits, errors "PATH:LINE: ..." (bench/cli/json_input.h).
  const json meta = LoadJsonFile(path, kMaxSuiteFileBytes, "suite.json");
  if (!meta.is_object()) throw std::invalid_argument(path + ": not a JSON object");
  if (!meta.contains("suite") || !meta["suite"].is_string()) {
    throw std::invalid_argument(path + ": suite: must be a string (the suite's name)");
  }
  return meta["suite"].get<std::string>();
}

// ---- comparing numbers -----------------------------------------------------------------------

double RelativeChange(double base, double next) {
  if (!std::isfinite(base) || !std::isfinite(next)) return NAN;
  if (next == base) return 0.0;
  if (base == 0.0) return next > base ? INFINITY : -INFINITY;
  return (next - base) / std::abs(base);
}

// The violation rule of CompareThresholds: `to` is worse than `from`.
bool ViolationWorse(double from, double to, const CompareThresholds& t) {
  const double rise = to - from;
  return rise > t.violation_abs && rise > t.violation_rel * from;
}

std::string G(double v) {
  if (std::isnan(v)) return "none";
  return fmt::format("{:.6g}", v);
}

std::string Percent(double relative) { return fmt::format("{:+.3g} %", 100.0 * relative); }

std::string CpuDetail(double ratio, const RankTestResult& test) {
  return fmt::format(
      "x {:.3g} (p = {:.2g}, {} vs {} repeats)", ratio, test.p_value, test.n_base, test.n_new);
}

double GeometricMean(const std::vector<double>& v) {
  double log_sum = 0.0;
  for (double x : v) log_sum += std::log(x);
  return v.empty() ? NAN : std::exp(log_sum / v.size());
}

void MinMedianMax(std::vector<double> v, double* median, double* lo, double* hi) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return;
  *median = Median(v);
  const auto [a, b] = std::minmax_element(v.begin(), v.end());
  *lo = *a;
  *hi = *b;
}

double Worst(double a, double b) {
  if (std::isnan(a)) return b;
  if (std::isnan(b)) return a;
  return std::max(a, b);
}

// ---- one case --------------------------------------------------------------------------------

CaseSide SideOf(const Record& r, const DerivedFields& d, const std::vector<std::string>& ignore) {
  CaseSide s;
  s.status = r.status;
  s.solver_status = r.solver_status;
  s.cost = d.final_J;
  s.Jbar_fine = r.Jbar_fine;
  s.terminal_violation =
      std::isnan(r.terminal_violation_fine) ? r.terminal_violation : r.terminal_violation_fine;
  s.path_violation = r.path_violation;
  s.iterations = r.iterations;
  s.cpu_seconds = r.cpu_seconds;
  s.cpu_repeats = r.cpu_seconds_repeats;
  if (s.cpu_repeats.empty() && std::isfinite(r.cpu_seconds)) s.cpu_repeats = {r.cpu_seconds};
  s.time_to_target = d.time_to_target;
  for (const std::string& name : ignore) {
    const auto it = r.options.find(name);
    s.ignored_options[name] = it == r.options.end() ? "(default)" : it->second;
  }
  s.commit = r.versions.commit;
  return s;
}

void CompareCase(const CompareThresholds& t, CaseComparison* c) {
  const CaseSide& b = c->base;
  const CaseSide& n = c->next;
  const int from = StatusTier(b.status), to = StatusTier(n.status);
  if (from != to) {
    c->findings.push_back({"status", to > from, b.status + " -> " + n.status});
  }

  c->cost_change = RelativeChange(b.cost, n.cost);
  c->Jbar_fine_change = RelativeChange(b.Jbar_fine, n.Jbar_fine);
  // In the hard form a result that did not converge may sit below every feasible cost.
  const bool costs_comparable = c->terminal != "hard" || (from <= 1 && to <= 1);
  if (costs_comparable) {
    const std::string values = fmt::format("{} -> {}", G(b.cost), G(n.cost));
    if (std::isfinite(b.cost) && !std::isfinite(n.cost)) {
      c->findings.push_back({"cost", true, values});
    } else if (!std::isfinite(b.cost) && std::isfinite(n.cost)) {
      c->findings.push_back({"cost", false, values});
    } else if (std::abs(c->cost_change) > t.cost) {
      c->findings.push_back(
          {"cost", c->cost_change > 0, Percent(c->cost_change) + " (" + values + ")"});
    }
  }

  auto violation = [&](const char* measure, double from_v, double to_v, double* change) {
    if (!std::isfinite(from_v) || !std::isfinite(to_v)) return;
    *change = to_v - from_v;
    const std::string detail = fmt::format("{:+.3g} ({} -> {})", *change, G(from_v), G(to_v));
    if (ViolationWorse(from_v, to_v, t)) c->findings.push_back({measure, true, detail});
    if (ViolationWorse(to_v, from_v, t)) c->findings.push_back({measure, false, detail});
  };
  violation("terminal viol. fine",
            b.terminal_violation,
            n.terminal_violation,
            &c->terminal_violation_change);
  violation("path viol.", b.path_violation, n.path_violation, &c->path_violation_change);

  if (b.cpu_seconds > 0 && n.cpu_seconds > 0 && std::isfinite(b.cpu_seconds) &&
      std::isfinite(n.cpu_seconds)) {
    c->cpu_ratio = n.cpu_seconds / b.cpu_seconds;
    c->cpu_test = MannWhitneyU(b.cpu_repeats, n.cpu_repeats);
    if (c->cpu_test.p_value < t.alpha) {
      if (c->cpu_ratio > t.cpu_ratio) {
        c->findings.push_back({"CPU", true, CpuDetail(c->cpu_ratio, c->cpu_test)});
      } else if (c->cpu_ratio < 1.0 / t.cpu_ratio) {
        c->findings.push_back({"CPU", false, CpuDetail(c->cpu_ratio, c->cpu_test)});
      }
    }
  }
}

// ---- matching --------------------------------------------------------------------------------

// The record's key with the ignored options' "|opt:NAME=VALUE" parts left out (CaseSpec::Key
// writes each option as that part, with the record's canonical option text as VALUE).
std::string MatchKey(const Record& r,
                     const std::vector<std::string>& ignore,
                     const std::string& where) {
  std::string key = r.key;
  for (const std::string& name : ignore) {
    const auto it = r.options.find(name);
    if (it == r.options.end()) continue;
    const std::string part = "|opt:" + name + "=" + it->second;
    size_t pos = key.find(part);
    while (pos != std::string::npos && pos + part.size() < key.size() &&
           key[pos + part.size()] != '|') {
      pos = key.find(part, pos + 1);
    }
    if (pos == std::string::npos) {
      throw std::invalid_argument(fmt::format(
          "{}: key: does not carry option '{}' that the record's options list", where, name));
    }
    key.erase(pos, part.size());
  }
  return key;
}

std::vector<std::string> Commits(const std::vector<Record>& records) {
  std::vector<std::string> out;
  for (const Record& r : records) {
    if (std::find(out.begin(), out.end(), r.versions.commit) == out.end()) {
      out.push_back(r.versions.commit);
    }
  }
  return out;
}

// ---- aggregation -----------------------------------------------------------------------------

MethodComparison Aggregate(const std::vector<const CaseComparison*>& cases,
                           const CompareThresholds& t) {
  MethodComparison m;
  m.section = cases.front()->section;
  m.method = cases.front()->method;
  std::vector<double> cost, jbar, it_base, it_new, ratios, ttt_base, ttt_new;
  std::vector<std::pair<std::vector<double>, std::vector<double>>> strata;
  for (const CaseComparison* c : cases) {
    ++m.cases;
    m.regressed += c->Regressed() ? 1 : 0;
    m.improved += c->Improved() ? 1 : 0;
    if (c->base.status != c->next.status) {
      m.status_changes[c->base.status + " -> " + c->next.status]++;
    }
    cost.push_back(c->cost_change);
    jbar.push_back(c->Jbar_fine_change);
    m.terminal_violation_base = Worst(m.terminal_violation_base, c->base.terminal_violation);
    m.terminal_violation_new = Worst(m.terminal_violation_new, c->next.terminal_violation);
    m.path_violation_base = Worst(m.path_violation_base, c->base.path_violation);
    m.path_violation_new = Worst(m.path_violation_new, c->next.path_violation);
    it_base.push_back(c->base.iterations >= 0 ? c->base.iterations : NAN);
    it_new.push_back(c->next.iterations >= 0 ? c->next.iterations : NAN);
    if (std::isfinite(c->cpu_ratio)) {
      ratios.push_back(c->cpu_ratio);
      strata.push_back({c->base.cpu_repeats, c->next.cpu_repeats});
    }
    if (std::isfinite(c->base.time_to_target)) {
      ttt_base.push_back(c->base.time_to_target);
      ++m.reached_base;
    }
    if (std::isfinite(c->next.time_to_target)) {
      ttt_new.push_back(c->next.time_to_target);
      ++m.reached_new;
    }
  }
  MinMedianMax(cost, &m.cost_change_median, &m.cost_change_min, &m.cost_change_max);
  MinMedianMax(jbar, &m.Jbar_fine_change_median, &m.Jbar_fine_change_min, &m.Jbar_fine_change_max);
  m.iterations_base = Median(it_base);
  m.iterations_new = Median(it_new);
  m.time_to_target_base = Median(ttt_base);
  m.time_to_target_new = Median(ttt_new);
  if (!ratios.empty()) {
    m.cpu_ratio = GeometricMean(ratios);
    m.cpu_test = StratifiedMannWhitneyU(strata);
    if (m.cpu_test.p_value < t.alpha) {
      const std::string detail = fmt::format("geometric mean x {:.3g} over {} cases (p = {:.2g})",
                                             m.cpu_ratio,
                                             ratios.size(),
                                             m.cpu_test.p_value);
      if (m.cpu_ratio > t.cpu_ratio) m.findings.push_back({"CPU", true, detail});
      if (m.cpu_ratio < 1.0 / t.cpu_ratio) m.findings.push_back({"CPU", false, detail});
    }
  }
  return m;
}

std::vector<ProfileComparison> Profiles(const std::vector<CaseComparison>& cases) {
  std::vector<ProfileEntry> entries;
  std::vector<std::string> methods;
  auto time = [](double t) { return std::isfinite(t) ? std::max(t, kTimeFloor) : INFINITY; };
  for (const CaseComparison& c : cases) {
    if (c.kind != "solve") continue;  // as results/plot.py's profiles
    if (std::find(methods.begin(), methods.end(), c.method) == methods.end()) {
      methods.push_back(c.method);
    }
    entries.push_back({c.group,
                       c.method + "\x1f"
                                  "base",
                       time(c.base.time_to_target)});
    entries.push_back({c.group,
                       c.method + "\x1f"
                                  "new",
                       time(c.next.time_to_target)});
  }
  const auto ratios = PerformanceRatios(entries);
  std::vector<ProfileComparison> out;
  for (const std::string& m : methods) {
    const auto b = ratios.find(m +
                               "\x1f"
                               "base");
    const auto n = ratios.find(m +
                               "\x1f"
                               "new");
    if (b == ratios.end() || n == ratios.end()) continue;  // no instance with a finite best
    ProfileComparison p;
    p.method = m;
    p.instances = static_cast<int>(b->second.size());
    for (size_t i = 0; i < kProfileTaus.size(); ++i) {
      p.base[i] = ProfileFraction(b->second, kProfileTaus[i]);
      p.next[i] = ProfileFraction(n->second, kProfileTaus[i]);
    }
    out.push_back(p);
  }
  return out;
}

}  // namespace

const OptionSchema& CompareThresholdSchema() { return Binding().schema(); }

CompareThresholds ResolveCompareThresholds(const OptionMap& given) {
  CompareThresholds t;
  for (const auto& [name, value] : Binding().schema().Resolve(given)) {
    for (const ThresholdField& f : ThresholdFields()) {
      if (name == f.name && !value.empty()) t.*(f.field) = value.number();
    }
  }
  return t;
}

int StatusTier(const std::string& status) {
  if (status == ToString(SolveStatus::kConverged)) return 0;
  if (status == ToString(SolveStatus::kAcceptable)) return 1;
  if (status == ToString(SolveStatus::kNotApplicable)) return 3;
  if (status.empty() || IsFailure(status)) return 4;
  return 2;
}

bool CaseComparison::Regressed() const {
  return std::any_of(findings.begin(), findings.end(), [](const Finding& f) { return f.worse; });
}

bool CaseComparison::Improved() const { return !Regressed() && !findings.empty(); }

int Comparison::RegressedCases() const {
  return static_cast<int>(std::count_if(
      cases.begin(), cases.end(), [](const CaseComparison& c) { return c.Regressed(); }));
}

int Comparison::ImprovedCases() const {
  return static_cast<int>(std::count_if(
      cases.begin(), cases.end(), [](const CaseComparison& c) { return c.Improved(); }));
}

int Comparison::RegressedMethods() const {
  return static_cast<int>(std::count_if(methods.begin(), methods.end(), [](const auto& m) {
    return std::any_of(
        m.findings.begin(), m.findings.end(), [](const Finding& f) { return f.worse; });
  }));
}

bool Comparison::HasRegression() const {
  return RegressedCases() > 0 || RegressedMethods() > 0 || !only_in_base.empty();
}

CompareSide LoadCompareSide(const std::string& path) {
  CompareSide side;
  side.path = path;
  if (!fs::exists(path))
    throw std::invalid_argument("compare: " + path + ": no such file or folder");
  if (fs::is_directory(path)) {
    side.records_path = (fs::path(path) / "records.jsonl").string();
    if (!fs::exists(side.records_path)) {
      throw std::invalid_argument(side.records_path +
                                  ": no such file (not a result folder of ocpbench run)");
    }
    side.suite = SuiteName(path);
  } else {
    side.records_path = path;
  }
  RecordFile file = ReadRecords(side.records_path);
  return CompareSideOfRecords(std::move(side), std::move(file));
}

CompareSide CompareSideOfRecords(CompareSide side, RecordFile file) {
  side.dropped_partial = file.dropped_partial;
  side.records = std::move(file.records);
  // Errors name the record's line in the file, as the records reader does ("FILE:LINE: ...").
  const std::vector<int>& line = file.line_numbers;
  if (side.records.empty()) throw std::invalid_argument(side.records_path + ": no records");
  std::map<std::string, size_t> seen;
  for (size_t i = 0; i < side.records.size(); ++i) {
    const std::string& key = side.records[i].key;
    if (key.empty()) {
      throw std::invalid_argument(
          fmt::format("{}:{}: key: missing (a record without a case key cannot be matched)",
                      side.records_path,
                      line[i]));
    }
    const auto [it, inserted] = seen.emplace(key, i);
    if (!inserted) {
      throw std::invalid_argument(
          fmt::format("{}:{}: key: the case of line {} again "
                      "(a case recorded twice)",
                      side.records_path,
                      line[i],
                      line[it->second]));
    }
  }
  return side;
}

Comparison Compare(const CompareSide& base,
                   const CompareSide& next,
                   const CompareOptions& options) {
  if (!base.suite.empty() && !next.suite.empty() && base.suite != next.suite) {
    throw std::invalid_argument(fmt::format(
        "compare: {} is a run of suite '{}', {} of suite '{}': not two runs of one suite",
        base.path,
        base.suite,
        next.path,
        next.suite));
  }
  const std::vector<std::string>& ignore = options.ignore_options;
  for (const std::string& name : ignore) {
    auto sets = [&name](const std::vector<Record>& rs) {
      return std::any_of(
          rs.begin(), rs.end(), [&name](const Record& r) { return r.options.count(name) > 0; });
    };
    if (!sets(base.records) && !sets(next.records)) {
      throw std::invalid_argument("--ignore-option '" + name + "': no case of " + base.path +
                                  " or " + next.path + " sets this option");
    }
  }

  // Matching keys, and a check that ignoring options merges no two cases of one side.
  auto keys_of = [&ignore](const CompareSide& side) {
    std::vector<std::string> keys;
    std::map<std::string, size_t> seen;
    for (size_t i = 0; i < side.records.size(); ++i) {
      const std::string where = fmt::format("{}: line {}", side.records_path, i + 1);
      keys.push_back(MatchKey(side.records[i], ignore, where));
      const auto [it, inserted] = seen.emplace(keys.back(), i);
      if (!inserted) {
        throw std::invalid_argument(
            fmt::format("--ignore-option: {}: lines {} and {} differ only in the ignored "
                        "options, so they cannot be told apart",
                        side.records_path,
                        it->second + 1,
                        i + 1));
      }
    }
    return keys;
  };
  const std::vector<std::string> base_keys = keys_of(base), new_keys = keys_of(next);
  std::map<std::string, size_t> new_index;
  for (size_t i = 0; i < new_keys.size(); ++i) new_index[new_keys[i]] = i;

  // Labels and targets from both sides at once: one row label per method for both sides, and
  // one target (the best J fine of the group over BASE and NEW) for both sides' times.
  std::vector<Record> all;
  all.reserve(base.records.size() + next.records.size());
  for (const CompareSide* side : {&base, &next}) {
    for (const Record& original : side->records) {
      Record r = original;
      for (const std::string& name : ignore) r.options.erase(name);
      // The bulky parts the target rule never reads: a suite of large grids is not held twice.
      r.trajectory.reset();
      r.s_map = nullptr;
      r.online.reset();
      all.push_back(std::move(r));
    }
  }
  const std::vector<DerivedFields> derived = DeriveTargets(all);
  const size_t offset = base.records.size();

  Comparison out;
  out.options = options;
  out.base_path = base.path;
  out.new_path = next.path;
  out.base_suite = base.suite;
  out.new_suite = next.suite;
  out.base_records = base.records.size();
  out.new_records = next.records.size();
  out.base_commits = Commits(base.records);
  out.new_commits = Commits(next.records);
  out.base_dropped_partial = base.dropped_partial;
  out.new_dropped_partial = next.dropped_partial;
  std::set<size_t> matched_new;
  for (size_t i = 0; i < base.records.size(); ++i) {
    const Record& b = base.records[i];
    const DerivedFields& db = derived[i];
    const auto it = new_index.find(base_keys[i]);
    if (it == new_index.end()) {
      out.only_in_base.push_back({b.key, db.section, db.method_label, b.status});
      continue;
    }
    matched_new.insert(it->second);
    CaseComparison c;
    c.key = base_keys[i];
    c.section = db.section;
    c.method = db.method_label;
    c.group = db.group;
    c.seed = b.seed;
    c.kind = b.kind;
    c.terminal = b.terminal;
    c.base = SideOf(b, db, ignore);
    c.next = SideOf(next.records[it->second], derived[offset + it->second], ignore);
    CompareCase(options.thresholds, &c);
    out.cases.push_back(std::move(c));
  }
  for (size_t i = 0; i < next.records.size(); ++i) {
    if (matched_new.count(i)) continue;
    const DerivedFields& d = derived[offset + i];
    out.only_in_new.push_back(
        {next.records[i].key, d.section, d.method_label, next.records[i].status});
  }
  if (out.cases.empty()) {
    throw std::invalid_argument(
        fmt::format("compare: {} and {} have no case in common: not two runs of one suite",
                    base.path,
                    next.path));
  }

  std::vector<std::pair<std::string, std::string>> rows;  // (section, method), in order
  std::map<std::pair<std::string, std::string>, std::vector<const CaseComparison*>> by_row;
  for (const CaseComparison& c : out.cases) {
    const auto row = std::make_pair(c.section, c.method);
    if (!by_row.count(row)) rows.push_back(row);
    by_row[row].push_back(&c);
  }
  for (const auto& row : rows) out.methods.push_back(Aggregate(by_row[row], options.thresholds));
  out.profiles = Profiles(out.cases);
  std::vector<double> ratios;
  for (const CaseComparison& c : out.cases) {
    if (std::isfinite(c.cpu_ratio)) ratios.push_back(c.cpu_ratio);
  }
  out.overall_cpu_ratio = GeometricMean(ratios);
  return out;
}

}  // namespace ocpb
