// The data behind `ocpbench report`'s pages (report_model.h).
#include "bench/cli/report_model.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <map>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "bench/cli/compare.h"
#include "bench/cli/performance_profile.h"
#include "bench/cli/shard_manifest.h"
#include "bench/cli/summary.h"
#include "problems/registry.h"

namespace ocpb {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Numbers that were not computed are null in the data (JSON has no NaN), as in the records.
json Num(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
json Count(int v) { return v >= 0 ? json(v) : json(nullptr); }

// The rule of summary.md's "rel. error vs reference" column (one rule: summary.h).
double ReferenceError(const Record& r) {
  return r.reference ? ocpb::ReferenceError(r, *r.reference) : NAN;
}

// The registry's entry, or null for a problem this build does not know (records of a user's own
// problem read by the stock ocpbench): the pages then show what the records say.
const ProblemInfo* KnownProblem(const std::string& name) {
  for (const ProblemInfo& info : Problems()) {
    if (info.name == name) return &info;
  }
  return nullptr;
}

std::vector<std::string> Tags(const std::string& problem) {
  const ProblemInfo* info = KnownProblem(problem);
  return info ? info->tags : std::vector<std::string>{};
}

// The worst violation the common evaluator found (fine re-simulation where there is one): the
// table's one "violation" column; the problem page lists each.
double WorstViolation(const Record& r) {
  double worst = NAN;
  auto take = [&worst](double v) {
    if (std::isfinite(v)) worst = std::isfinite(worst) ? std::max(worst, v) : v;
  };
  take(std::isfinite(r.terminal_violation_fine) ? r.terminal_violation_fine : r.terminal_violation);
  take(r.control_violation);
  take(r.path_violation);
  if (r.state_bound_violation) take(*r.state_bound_violation);
  if (r.boundary_violation) take(*r.boundary_violation);
  return worst;
}

// A file's modification time in UTC (stat: GCC 12's <chrono> has no clock_cast to turn a
// file_time_type into a calendar time); empty when it cannot be read.
std::string ModifiedUtc(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return "";
  std::tm tm{};
  gmtime_r(&st.st_mtime, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &tm);
  return text;
}

// The values of one field over the records, distinct, in order of appearance ("" left out).
template <typename F>
json Distinct(const std::vector<Record>& records, F field) {
  std::vector<std::string> seen;
  for (const Record& r : records) {
    const std::string v = field(r);
    if (!v.empty() && std::find(seen.begin(), seen.end(), v) == seen.end()) seen.push_back(v);
  }
  return seen;
}

// A problem's bounds as drawn on its page: the control set's bounding box and the state bounds,
// from the problem built with the records' parameters (the cheap builder where there is one:
// comm-path2d's full builder simulates a channel). Null where the registry does not know the
// problem or building it fails: the page then draws no bounds, and says so.
json Bounds(const Record& r) {
  const ProblemInfo* info = KnownProblem(r.problem);
  if (!info) return nullptr;
  try {
    Parameters params(info->parameters);
    for (const auto& [key, value] : r.parameters) {
      if (params.Has(key)) params.Set(key, value);
    }
    const auto& make = info->make_for_checks ? info->make_for_checks : info->make;
    const std::unique_ptr<Ocp> ocp = make(params, r.seed);
    Vec lower, upper;
    ocp->control_set().BoundingBox(&lower, &upper);
    json out{{"u_lower", json::array()}, {"u_upper", json::array()}};
    for (int i = 0; i < lower.size(); ++i) {
      out["u_lower"].push_back(Num(lower[i]));
      out["u_upper"].push_back(Num(upper[i]));
    }
    if (ocp->state_bounds()) {
      const VectorBounds& sb = *ocp->state_bounds();
      out["x_lower"] = json::array();
      out["x_upper"] = json::array();
      for (int i = 0; i < sb.lower.size(); ++i) {
        out["x_lower"].push_back(Num(sb.lower[i]));
        out["x_upper"].push_back(Num(sb.upper[i]));
      }
    }
    return out;
  } catch (const std::exception&) {
    return nullptr;  // a problem the records were made with but this build cannot rebuild
  }
}

// The pages' numbers carry 9 significant digits, not a double's 17: the data files of a suite
// with trajectories shrink by about half, and a gap of 1e-8 to the best J stays visible.
void Compact(json& j) {
  if (j.is_number_float()) {
    const double v = j.get<double>();
    if (std::isfinite(v)) j = std::stod(fmt::format("{:.9g}", v));
  } else if (j.is_structured()) {
    for (json& item : j) Compact(item);
  }
}

// A history thinned to at most kHistoryPoints rows, evenly by index, the last row kept: a
// descent's 8000 iterations draw no better than 500 on a 560-pixel plot.
constexpr size_t kHistoryPoints = 500;
// Of each row only what the page draws: iteration, J, CPU seconds and the grid (a row of a
// coarser grid is left out of the gap plots).
json DrawnRow(const json& row) {
  json out = json::object();
  for (const char* k : {"iteration", "J", "cpu_seconds", "intervals"}) {
    if (row.is_object() && row.contains(k) && !row[k].is_null()) out[k] = row[k];
  }
  return out;
}

json Thinned(const json& history) {
  if (!history.is_array()) return history;
  json out = json::array();
  const size_t n = history.size();
  if (n <= kHistoryPoints) {
    for (const json& row : history) out.push_back(DrawnRow(row));
    return out;
  }
  for (size_t k = 0; k < kHistoryPoints; ++k)
    out.push_back(DrawnRow(history[k * (n - 1) / (kHistoryPoints - 1)]));
  return out;
}

// One table row of a record, with its derived fields (summary.md's target rule).
json CaseRow(const Record& r, const DerivedFields& d) {
  json warnings = json::array();
  for (const RecordWarning& w : r.warnings) warnings.push_back(w.code);
  return {
      {"key", r.key},
      {"kind", r.kind},
      {"problem", r.problem},
      {"page", ProblemPageName(r.problem)},
      {"section", d.section},
      {"method", d.method_label},
      {"solver", r.solver},
      {"seed", r.seed},
      {"N", r.N},
      {"terminal", r.terminal},
      {"status", r.status},
      {"warnings", warnings},
      {"tags", Tags(r.problem)},
      {"J_fine", Num(r.J_fine)},
      {"Jbar_fine", Num(r.Jbar_fine)},
      {"ref_error", Num(ReferenceError(r))},
      {"violation", Num(WorstViolation(r))},
      {"iterations", Count(r.iterations)},
      {"cpu", Num(r.cpu_seconds)},
      {"time_to_target", Num(d.time_to_target)},
      {"best_J", Num(d.best_J)},
      {"reached_target", d.reached_target},
      {"energy_true",
       r.online ? Num(r.online->energy_true) : Num(r.truth ? r.truth->energy_true : NAN)},
      {"offline_energy_true", r.online ? Num(r.online->offline_energy_true) : json(nullptr)},
      {"cycles", r.online ? json(r.online->cycles.size()) : json(nullptr)},
      {"energy_ratio", r.online ? Num(r.online->energy_ratio) : json(nullptr)},
      {"transmit_energy_ratio", r.online ? Num(r.online->transmit_energy_ratio) : json(nullptr)}};
}

// Dolan-More profiles of CPU time to target, one instance per target group (a problem, seed,
// parameters and terminal form): each method's performance ratios, which the page draws as
// rho(tau). A method that never reached the target has infinite ratios (drawn as never solved).
json Profiles(const std::vector<Record>& records, const std::vector<DerivedFields>& derived) {
  std::vector<ProfileEntry> entries;
  for (size_t i = 0; i < records.size(); ++i) {
    if (records[i].kind != "solve") continue;
    const double t = derived[i].reached_target ? derived[i].time_to_target : INFINITY;
    entries.push_back({derived[i].group, derived[i].method_label, t});
  }
  json out = json::array();
  for (const auto& [method, ratios] : PerformanceRatios(entries)) {
    json r = json::array();
    for (double v : ratios) r.push_back(Num(v));  // infinity (never reached): null
    out.push_back({{"method", method}, {"ratios", r}});
  }
  return out;
}

}  // namespace

std::string ProblemPageName(const std::string& problem) {
  std::string name = problem;
  bool replaced = false;
  for (char& c : name) {
    const bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
    if (!ok) {
      c = '_';
      replaced = true;
    }
  }
  if (replaced) {
    // "a.b" and "a_b" must not share a page: a name that needed replacing gets its own hash.
    std::uint64_t hash = 1469598103934665603ull;  // FNV-1a
    for (const char c : problem) hash = (hash ^ static_cast<unsigned char>(c)) * 1099511628211ull;
    name += fmt::format("-{:08x}", static_cast<std::uint32_t>(hash));
  }
  return "problem-" + name + ".html";
}

ReportInput LoadReportInput(const std::string& path) {
  ReportInput in;
  in.path = path;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    throw std::invalid_argument("report: DIR " + path + ": no such file or folder");
  }
  const bool folder = fs::is_directory(path, ec);
  if (folder) {
    const std::string records = (fs::path(path) / "records.jsonl").string();
    const std::optional<ShardManifest> manifest = ReadShardManifest(path);
    if (!fs::exists(records, ec)) {
      if (manifest) {
        throw std::invalid_argument("report: DIR " + path +
                                    ": holds shards not merged yet (no records.jsonl); run "
                                    "`ocpbench merge " +
                                    path + "` first");
      }
      throw std::invalid_argument("report: DIR " + records +
                                  ": no such file (not a result folder of ocpbench run)");
    }
    if (manifest) {
      in.shards = manifest->shards;
      in.expected_cases = manifest->cases;
    }
  }
  // The records with the checks `compare` makes of each side: keys present, no case twice.
  const CompareSide side = LoadCompareSide(path);
  in.records_path = side.records_path;
  in.suite_named = !side.suite.empty();
  in.suite =
      side.suite.empty() ? fs::path(path).lexically_normal().filename().string() : side.suite;
  if (in.suite.empty()) in.suite = fs::path(path).stem().string();
  in.records = side.records;
  in.dropped_partial = side.dropped_partial;
  in.recorded_at = ModifiedUtc(in.records_path);
  if (folder) {
    const fs::path figures = fs::path(path) / "figures";
    if (fs::is_directory(figures, ec)) {
      for (const auto& entry : fs::directory_iterator(figures)) {
        const std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".png" || ext == ".svg")) {
          in.figures.push_back(entry.path().filename().string());
        }
      }
      std::sort(in.figures.begin(), in.figures.end());
    }
  }
  return in;
}

std::vector<std::string> ReportProblems(const ReportInput& input) {
  std::vector<std::string> out;
  for (const Record& r : input.records) {
    if (std::find(out.begin(), out.end(), r.problem) == out.end()) out.push_back(r.problem);
  }
  return out;
}

json SuiteIndexData(const ReportInput& input) {
  const std::vector<Record>& records = input.records;
  const std::vector<DerivedFields> derived = DeriveTargets(records);
  std::map<std::string, int> by_status, by_warning;
  json cases = json::array();
  for (size_t i = 0; i < records.size(); ++i) {
    ++by_status[records[i].status];
    for (const RecordWarning& w : records[i].warnings) ++by_warning[w.code];
    cases.push_back(CaseRow(records[i], derived[i]));
  }
  json problems = json::array();
  for (const std::string& p : ReportProblems(input)) {
    const ProblemInfo* info = KnownProblem(p);
    problems.push_back({{"name", p},
                        {"page", ProblemPageName(p)},
                        {"description", info ? info->description : ""},
                        {"tags", Tags(p)}});
  }
  const json meta{{"suite", input.suite},
                  {"source", input.path},
                  {"records", records.size()},
                  {"commits", Distinct(records, [](const Record& r) { return r.versions.commit; })},
                  {"versions",
                   Distinct(records,
                            [](const Record& r) {
                              const RecordVersions& v = r.versions;
                              return fmt::format("ocpbench {}, {}, Ipopt {}, NLopt {}",
                                                 v.ocpbench,
                                                 v.compiler,
                                                 v.ipopt,
                                                 v.nlopt);
                            })},
                  {"recorded_at", input.recorded_at},
                  {"shards", input.shards},
                  {"expected_cases", input.expected_cases},
                  {"dropped_partial", input.dropped_partial},
                  {"online", std::any_of(records.begin(), records.end(), [](const Record& r) {
                     return r.kind == "online";
                   })}};
  return {{"meta", meta},
          {"counts", {{"status", by_status}, {"warning", by_warning}}},
          {"profiles", Profiles(records, derived)},
          {"problems", problems},
          {"figures", input.figures},
          {"cases", cases}};
}

json ProblemPageData(const ReportInput& input, const std::string& problem) {
  const std::vector<DerivedFields> derived = DeriveTargets(input.records);
  const ProblemInfo* info = KnownProblem(problem);
  json references = json::array();
  if (info && info->reference_value) {
    references.push_back({{"value", *info->reference_value},
                          {"quantity", info->reference_quantity},
                          {"scheme", info->reference_scheme},
                          {"N", info->reference_intervals},
                          {"source", info->reference_source}});
  }
  if (info) {
    for (const ProblemReference& ref : info->additional_references) {
      references.push_back({{"value", Num(ref.value)},
                            {"quantity", ref.quantity},
                            {"scheme", ref.scheme},
                            {"N", ref.intervals},
                            {"source", ref.source}});
    }
  }
  json runs = json::array();
  json bounds = nullptr;
  for (size_t i = 0; i < input.records.size(); ++i) {
    const Record& r = input.records[i];
    if (r.problem != problem) continue;
    if (bounds.is_null()) bounds = Bounds(r);
    // The record's own JSON form (Record::ToJson, the schema's names) for its bulky parts: the
    // page's script reads them as results/record.schema.json describes them.
    const json full = r.ToJson();
    json run = CaseRow(r, derived[i]);
    run["solver_status"] = r.solver_status;
    run["message"] = r.message;
    run["terminal_violation_fine"] = Num(r.terminal_violation_fine);
    run["control_violation"] = Num(r.control_violation);
    run["path_violation"] = Num(r.path_violation);
    run["discretization_gap"] = Num(r.discretization_gap);
    run["costate_error"] = Num(r.costate_error);
    run["costate_source"] = r.costate_source;
    run["final_time"] = Num(r.final_time);
    run["options"] = r.options;
    run["warning_messages"] = json::array();
    for (const RecordWarning& w : r.warnings) {
      run["warning_messages"].push_back({{"code", w.code}, {"message", w.message}});
    }
    for (const char* part :
         {"trajectory", "costates", "history", "mesh", "continuation", "stopping_tolerance"}) {
      run[part] = full.contains(part) ? full[part] : json(nullptr);
    }
    // The method's own states and costates (a warm start's source) are not drawn: the
    // evaluator's trajectory and the costates are. They were half of the paper suite's page.
    if (run["trajectory"].is_object()) run["trajectory"].erase("own");
    run["history_rows"] = r.history.size();
    run["history"] = Thinned(run["history"]);
    if (r.online) {
      run["online_executed"] = r.online->executed;
      run["online_offline"] = r.online->offline;
      // Of each cycle only what the page draws (a cycle also keeps its plan and measurements).
      json cycles = json::array();
      for (const json& c : r.online->cycles) {
        json kept = json::object();
        for (const char* k : {"t0", "solve_seconds", "predict_seconds", "iterations", "status"}) {
          if (c.is_object() && c.contains(k)) kept[k] = c[k];
        }
        cycles.push_back(std::move(kept));
      }
      run["online_cycles"] = std::move(cycles);
    }
    Compact(run);
    runs.push_back(std::move(run));
  }
  return {{"suite", input.suite},
          {"problem", problem},
          {"description", info ? info->description : "(not a problem this ocpbench registers)"},
          {"origin", info ? info->origin : ""},
          {"tags", Tags(problem)},
          {"hamiltonian_note", info ? info->hamiltonian_note : ""},
          {"references", references},
          {"bounds", bounds},
          {"runs", runs}};
}

}  // namespace ocpb
