#include "bench/cli/summary.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

namespace ocpb {

using nlohmann::json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTargetTolerance = 0.01;  // "within 1% of the best"
constexpr double kFeasibleHistory = 1e-6;  // primal_inf of a history entry that may count

double Num(const json& r, const char* key) {
  if (!r.contains(key) || !r[key].is_number()) return kNaN;
  return r[key].get<double>();
}

std::string Str(const json& r, const char* key) {
  return r.contains(key) && r[key].is_string() ? r[key].get<std::string>() : std::string();
}

std::string MethodLabel(const json& r) {
  std::string label = Str(r, "solver");
  if (!Str(r, "transcription").empty()) label += " + " + Str(r, "transcription");
  if (!Str(r, "algorithm").empty()) label += " (" + Str(r, "algorithm") + ")";
  if (r.contains("degree")) label += fmt::format(" deg {}", r["degree"].get<int>());
  label += ", " + Str(r, "terminal");
  if (Str(r, "solver") == "hamiltonian" && Str(r, "integrator") != "euler") {
    label += ", " + Str(r, "integrator");
  }
  const std::string evaluated = Str(r, "evaluated_with");
  if (!evaluated.empty() && evaluated != "euler") label += ", judged with " + evaluated;
  return label + fmt::format(", N={}", r.value("N", 0));
}

std::string OptionsText(const json& r) {
  std::string text;
  if (r.contains("options") && r["options"].is_object()) {
    for (const auto& [key, value] : r["options"].items()) {
      text += (text.empty() ? "" : ", ") + key + "=" +
              (value.is_string() ? value.get<std::string>() : value.dump());
    }
  }
  return text;
}

std::string GroupKey(const json& r) {
  return fmt::format("{}|seed={}|{}|{}",
                     Str(r, "problem"),
                     r.value("seed", 0),
                     r.contains("parameters") ? r["parameters"].dump() : "",
                     Str(r, "terminal"));
}

// The section (table) and row label of every record. A problem's table splits by the
// parameters that differ between its records (for example the penalty weights C), so no row
// averages two different problems. Options name a row only where they tell two rows of the same
// method apart somewhere in the suite, so one method has one label in every table and figure.
struct Labels {
  std::vector<std::string> section, row;
};

Labels LabelRecords(const std::vector<json>& records) {
  std::map<std::string, std::map<std::string, std::set<std::string>>> values;
  std::map<std::string, std::set<std::string>> options_of;
  for (const json& r : records) {
    options_of[MethodLabel(r)].insert(OptionsText(r));
    if (!r.contains("parameters") || !r["parameters"].is_object()) continue;
    for (const auto& [key, value] : r["parameters"].items()) {
      values[Str(r, "problem")][key].insert(value.dump());
    }
  }
  std::map<std::string, std::set<std::string>> varying;  // problem -> parameters that vary
  for (const auto& [problem, keys] : values) {
    for (const auto& [key, seen] : keys) {
      if (seen.size() > 1) varying[problem].insert(key);
    }
  }
  Labels labels;
  for (const json& r : records) {
    std::string setting;
    for (const std::string& key : varying[Str(r, "problem")]) {
      const std::string v = r.contains("parameters") && r["parameters"].contains(key)
                                ? r["parameters"][key].dump()
                                : std::string("default");
      setting += (setting.empty() ? "" : ", ") + key + " = " + v;
    }
    labels.section.push_back(setting.empty() ? Str(r, "problem")
                                             : Str(r, "problem") + " (" + setting + ")");
    std::string row = MethodLabel(r);
    if (options_of[row].size() > 1) {
      const std::string o = OptionsText(r);
      row += o.empty() ? ", default options" : ", " + o;
    }
    labels.row.push_back(row);
  }
  return labels;
}

double FinalValue(const json& r) {
  const double fine = Num(r, "J_fine");
  if (std::isfinite(fine)) return fine;
  const double J = Num(r, "J");
  return std::isfinite(J) ? J : kNaN;
}

bool WithinTarget(double value, double best) {
  return std::isfinite(value) && std::abs(value - best) <= kTargetTolerance * std::abs(best);
}

std::string G(double v) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return "inf";
  return fmt::format("{:.6g}", v);
}

double Median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return std::isnan(x); }), v.end());
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string Spread(const std::vector<double>& v) {
  std::vector<double> f;
  for (double x : v) {
    if (std::isfinite(x)) f.push_back(x);
  }
  if (f.empty()) return "-";
  double mean = 0.0;
  for (double x : f) mean += x;
  mean /= f.size();
  if (f.size() == 1) return G(mean);
  const auto [lo, hi] = std::minmax_element(f.begin(), f.end());
  return fmt::format("{} [{}, {}]", G(mean), G(*lo), G(*hi));
}

// The worst case of a row (NaN where no case has a value, e.g. not applicable).
double Worst(const std::vector<double>& v) {
  double w = kNaN;
  for (double x : v) {
    if (!std::isnan(x)) w = std::isnan(w) ? x : std::max(w, x);
  }
  return w;
}

// A reference value is either a continuous optimum (scheme "continuous"), comparable with the
// continuous-time cost of any method's controls, or an optimum of one discrete NLP (COPS: a scheme
// at a grid), comparable only with a record that solved that very NLP. Records written before the
// reference carried its scheme are compared with nothing.
bool IsContinuous(const json& ref) { return Str(ref, "scheme") == "continuous"; }

std::string ReferenceNote(const json& ref) {
  const std::string head = fmt::format("Reference {} = {} ({}).",
                                       ref.value("quantity", std::string("J")),
                                       G(Num(ref, "value")),
                                       ref.value("source", std::string("no source given")));
  if (IsContinuous(ref)) {
    return head +
           " A continuous optimum: rel. error = |Jbar fine - reference| / |reference| for every "
           "row (the continuous-time cost of the method's controls; see terminal viol. fine for "
           "how well they meet the terminal conditions).";
  }
  if (!Str(ref, "scheme").empty()) {
    return head + fmt::format(
                      " An optimum of the discrete NLP of the {} scheme at N = {}: rel. error = "
                      "|objective - reference| / |reference| (the NLP's own objective) only for "
                      "rows that solve that NLP (that transcription and N, hard terminal form).",
                      Str(ref, "scheme"),
                      ref.value("N", 0));
  }
  return head +
         " The records do not say which problem the value is an optimum of (continuous or "
         "a scheme and grid): the error column stays empty.";
}

double ReferenceError(const json& r, const json& ref) {
  const double value = Num(ref, "value");
  if (!std::isfinite(value) || value == 0.0) return kNaN;
  if (IsContinuous(ref)) return std::abs(Num(r, "Jbar_fine") - value) / std::abs(value);
  const std::string scheme = Str(ref, "scheme");
  if (scheme.empty() || Str(r, "transcription") != scheme || Str(r, "terminal") != "hard" ||
      r.value("N", -1) != ref.value("N", -2)) {
    return kNaN;
  }
  return std::abs(Num(r, "objective") - value) / std::abs(value);
}

}  // namespace

void DeriveTargets(std::vector<json>* records) {
  const Labels labels = LabelRecords(*records);
  std::map<std::string, double> best;
  for (size_t i = 0; i < records->size(); ++i) {
    json& r = (*records)[i];
    r["group"] = GroupKey(r);
    r["section"] = labels.section[i];
    r["method_label"] = labels.row[i];
    const double v = FinalValue(r);
    r["final_J"] = std::isfinite(v) ? json(v) : json(nullptr);
    if (!std::isfinite(v)) continue;
    // A hard-form record that did not converge may sit below every feasible answer.
    if (Str(r, "terminal") == "hard" && Str(r, "status") != "converged") continue;
    const std::string g = r["group"];
    if (!best.count(g) || v < best[g]) best[g] = v;
  }
  for (json& r : *records) {
    const auto it = best.find(r["group"].get<std::string>());
    r["best_J"] = it == best.end() ? json(nullptr) : json(it->second);
    r["reached_target"] = it != best.end() && WithinTarget(FinalValue(r), it->second);
    r["time_to_target"] = nullptr;
    if (!r["reached_target"].get<bool>()) continue;
    const double b = it->second;
    if (r.contains("history") && r["history"].is_array()) {
      for (const json& h : r["history"]) {
        const double primal = Num(h, "primal_inf");
        if (WithinTarget(Num(h, "J"), b) && !(primal > kFeasibleHistory)) {
          r["time_to_target"] = Num(h, "cpu_seconds");
          break;
        }
      }
    }
    // The final answer reached it although no recorded iterate did (the history holds the
    // method's own objective, which differs from J_fine by its discretization error).
    if (r["time_to_target"].is_null()) r["time_to_target"] = Num(r, "cpu_seconds");
  }
}

std::string SummaryMarkdown(const std::string& suite_name, const std::vector<json>& records) {
  std::ostringstream md;
  md << "# Suite `" << suite_name << "`\n\n";
  md << "Generated by `ocpbench run` from `records.jsonl`; do not edit. J, Jbar and violations "
        "come from the common evaluator on each method's grid (forward Euler unless the row says "
        "otherwise; J is penalized, Jbar is not); \"fine\" is RK4 on a 10x finer grid, the "
        "continuous-time judge for every method; resim. defect is the largest gap between a "
        "method's own states and its controls re-simulated (methods that carry states). Numbers "
        "are mean [min, max] over seeds, violations and defects the worst case of the row; CPU "
        "(each case: the median of its repeats) and time to target are medians over the row.\n\n"
        "Time to target: the target is the best J fine (J where J fine is missing) of any method "
        "on the same problem, seed, parameters and terminal form; in the hard form only converged "
        "cases count for the best. A case reaches the target when its own final J fine is within "
        "1% of it; its time to target is then the CPU seconds at its first iterate whose own "
        "objective is within 1% of the target with primal infeasibility (where the solver "
        "reports one) at most 1e-6, or its total CPU time if no iterate qualifies; otherwise "
        "never. n/m = reached in n of m cases.\n\n";
  const Labels labels = LabelRecords(records);
  std::vector<std::string> sections;
  for (const std::string& s : labels.section) {
    if (std::find(sections.begin(), sections.end(), s) == sections.end()) sections.push_back(s);
  }
  for (const std::string& section : sections) {
    md << "## " << section << "\n\n";
    std::vector<std::string> methods;
    std::map<std::string, std::vector<const json*>> by_method;
    const json* reference = nullptr;
    bool free_time = false;  // a free final time: the table says each method's T
    for (size_t i = 0; i < records.size(); ++i) {
      if (labels.section[i] != section) continue;
      const json& r = records[i];
      free_time = free_time || r.value("final_time_free", false);
      if (!by_method.count(labels.row[i])) methods.push_back(labels.row[i]);
      by_method[labels.row[i]].push_back(&r);
      if (!reference && r.contains("reference") && r["reference"].is_object() &&
          std::isfinite(Num(r["reference"], "value"))) {
        reference = &r["reference"];
      }
    }
    if (reference) md << ReferenceNote(*reference) << "\n\n";
    md << "| method | cases | status | J | Jbar | J fine | Jbar fine | terminal viol. | "
          "terminal viol. fine | U viol. | path viol. | resim. defect | iterations | CPU s | "
          "time to target s |"
       << (free_time ? " final time T |" : "") << (reference ? " rel. error vs reference |" : "")
       << "\n";
    md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
       << (free_time ? "---|" : "") << (reference ? "---|" : "") << "\n";
    for (const std::string& m : methods) {
      const auto& rs = by_method[m];
      std::map<std::string, int> statuses;
      std::vector<double> J, Jbar, Jf, Jbarf, tv, tvf, cv, pv, defect, it, cpu, ttt, rel, T;
      int reached = 0;
      for (const json* r : rs) {
        statuses[Str(*r, "status")]++;
        J.push_back(Num(*r, "J"));
        Jbar.push_back(Num(*r, "Jbar"));
        Jf.push_back(Num(*r, "J_fine"));
        Jbarf.push_back(Num(*r, "Jbar_fine"));
        tv.push_back(Num(*r, "terminal_violation"));
        tvf.push_back(Num(*r, "terminal_violation_fine"));
        cv.push_back(Num(*r, "control_violation"));
        pv.push_back(Num(*r, "path_violation"));
        defect.push_back(Num(*r, "resimulation_defect"));
        it.push_back(Num(*r, "iterations"));
        cpu.push_back(Num(*r, "cpu_seconds"));
        T.push_back(Num(*r, "final_time"));
        const double t = Num(*r, "time_to_target");
        if (std::isfinite(t)) {
          ttt.push_back(t);
          ++reached;
        }
        if (reference) rel.push_back(ReferenceError(*r, *reference));
      }
      std::string st;
      for (const auto& [s, n] : statuses)
        st += (st.empty() ? "" : ", ") + fmt::format("{} {}", n, s);
      md << fmt::format(
          "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} ({}/{}) |",
          m,
          rs.size(),
          st,
          Spread(J),
          Spread(Jbar),
          Spread(Jf),
          Spread(Jbarf),
          G(Worst(tv)),
          G(Worst(tvf)),
          G(Worst(cv)),
          G(Worst(pv)),
          G(Worst(defect)),
          G(Median(it)),
          G(Median(cpu)),
          G(Median(ttt)),
          reached,
          rs.size());
      if (free_time) md << " " << Spread(T) << " |";
      if (reference) md << " " << Spread(rel) << " |";
      md << "\n";
    }
    md << "\n";
  }
  return md.str();
}

std::string RecordsCsv(const std::vector<json>& records) {
  static const char* kColumns[] = {"problem",
                                   "seed",
                                   "solver",
                                   "transcription",
                                   "algorithm",
                                   "N",
                                   "terminal",
                                   "integrator",
                                   "status",
                                   "solver_status",
                                   "J",
                                   "Jbar",
                                   "terminal_violation",
                                   "control_violation",
                                   "path_violation",
                                   "J_fine",
                                   "Jbar_fine",
                                   "terminal_violation_fine",
                                   "resimulation_defect",
                                   "iterations",
                                   "cpu_seconds",
                                   "wall_seconds",
                                   "final_J",
                                   "best_J",
                                   "reached_target",
                                   "time_to_target",
                                   "final_time"};
  std::ostringstream csv;
  bool first = true;
  for (const char* c : kColumns) {
    csv << (first ? "" : ",") << c;
    first = false;
  }
  csv << "\n";
  for (const json& r : records) {
    first = true;
    for (const char* c : kColumns) {
      csv << (first ? "" : ",");
      first = false;
      if (!r.contains(c) || r[c].is_null()) continue;
      if (r[c].is_string()) {
        std::string s = r[c].get<std::string>();
        std::string q = "\"";
        for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
        csv << q << "\"";
      } else {
        csv << r[c].dump();
      }
    }
    csv << "\n";
  }
  return csv.str();
}

}  // namespace ocpb
