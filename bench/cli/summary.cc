#include "bench/cli/summary.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include <fmt/format.h>

#include "bench/cli/json_values.h"
#include "bench/cli/summary_overview.h"

namespace ocpb {

using nlohmann::json;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTargetTolerance = 0.01;  // "within 1% of the best"
constexpr double kFeasibleHistory = 1e-6;  // primal_inf of a history entry that may count

// A method's row label. The integrator names a row only where it is not the default Euler: for
// every method that uses one (the descent, single shooting), which the solver options cannot
// tell apart otherwise.
std::string RowMethodLabel(const Record& r) {
  std::string label = r.solver;
  if (!r.transcription.empty()) label += " + " + r.transcription;
  if (!r.algorithm.empty()) label += " (" + r.algorithm + ")";
  if (r.degree) label += fmt::format(" deg {}", *r.degree);
  label += ", " + r.terminal;
  if (r.transcription.empty() && r.integrator != "euler") label += ", " + r.integrator;
  if (!r.evaluated_with.empty() && r.evaluated_with != "euler") {
    label += ", judged with " + r.evaluated_with;
  }
  return label + fmt::format(", N={}", r.N);
}

std::string OptionsText(const Record& r) {
  std::string text;
  for (const auto& [key, value] : r.options) text += (text.empty() ? "" : ", ") + key + "=" + value;
  return text;
}

std::string ParameterText(const std::vector<double>& v) {
  return v.size() == 1 ? json(v[0]).dump() : json(v).dump();
}

std::string ParametersText(const Record& r) {
  json p = json::object();
  for (const auto& [k, v] : r.parameters) p[k] = v.size() == 1 ? json(v[0]) : json(v);
  return p.dump();
}

// The section (table) and row label of every record. A problem's table splits by the
// parameters that differ between its records (for example the penalty weights C), so no row
// averages two different problems. Options name a row only where they tell two rows of the same
// method apart somewhere in the suite, so one method has one label in every table and figure.
struct Labels {
  std::vector<std::string> section, row;
};

Labels LabelRecords(const std::vector<Record>& records) {
  std::map<std::string, std::map<std::string, std::set<std::string>>> values;
  std::map<std::string, std::set<std::string>> options_of;
  for (const Record& r : records) {
    options_of[RowMethodLabel(r)].insert(OptionsText(r));
    for (const auto& [key, value] : r.parameters)
      values[r.problem][key].insert(ParameterText(value));
  }
  std::map<std::string, std::set<std::string>> varying;  // problem -> parameters that vary
  for (const auto& [problem, keys] : values) {
    for (const auto& [key, seen] : keys) {
      if (seen.size() > 1) varying[problem].insert(key);
    }
  }
  Labels labels;
  for (const Record& r : records) {
    std::string setting;
    for (const std::string& key : varying[r.problem]) {
      const auto it = r.parameters.find(key);
      const std::string v = it != r.parameters.end() ? ParameterText(it->second) : "default";
      setting += (setting.empty() ? "" : ", ") + key + " = " + v;
    }
    labels.section.push_back(setting.empty() ? r.problem : r.problem + " (" + setting + ")");
    std::string row = RowMethodLabel(r);
    if (options_of[row].size() > 1) {
      const std::string o = OptionsText(r);
      row += o.empty() ? ", default options" : ", " + o;
    }
    labels.row.push_back(row);
  }
  return labels;
}

double FinalValue(const Record& r) {
  if (std::isfinite(r.J_fine)) return r.J_fine;
  return std::isfinite(r.J) ? r.J : kNaN;
}

bool WithinTarget(double value, double best) {
  return std::isfinite(value) && std::abs(value - best) <= kTargetTolerance * std::abs(best);
}

std::string SummaryNumber(double v) {
  if (std::isnan(v)) return "-";
  if (std::isinf(v)) return "inf";
  return fmt::format("{:.6g}", v);
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
  if (f.size() == 1) return SummaryNumber(mean);
  const auto [lo, hi] = std::minmax_element(f.begin(), f.end());
  return fmt::format("{} [{}, {}]", SummaryNumber(mean), SummaryNumber(*lo), SummaryNumber(*hi));
}

// The worst case of a row (NaN where no case has a value, e.g. not applicable).
double WorstOf(const std::vector<double>& v) {
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
bool IsContinuous(const RecordReference& ref) { return ref.scheme == "continuous"; }

std::string ReferenceNote(const RecordReference& ref) {
  const std::string head = fmt::format("Reference {} = {} ({}).",
                                       ref.quantity,
                                       SummaryNumber(ref.value),
                                       ref.source.empty() ? "no source given" : ref.source);
  if (IsContinuous(ref)) {
    return head +
           " A continuous optimum: rel. error = |Jbar fine - reference| / |reference| for every "
           "row (the continuous-time cost of the method's controls; see terminal viol. fine for "
           "how well they meet the terminal conditions).";
  }
  if (!ref.scheme.empty()) {
    return head + fmt::format(
                      " An optimum of the discrete NLP of the {} scheme at N = {}: rel. error = "
                      "|objective - reference| / |reference| (the NLP's own objective) only for "
                      "rows that solve that NLP (that transcription and N, hard terminal form).",
                      ref.scheme,
                      ref.N);
  }
  return head +
         " The records do not say which problem the value is an optimum of (continuous or "
         "a scheme and grid): the error column stays empty.";
}

}  // namespace

std::string GroupKey(const Record& r) {
  return fmt::format("{}|seed={}|{}|{}", r.problem, r.seed, ParametersText(r), r.terminal);
}

double ReferenceError(const Record& r, const RecordReference& ref) {
  const double value = ref.value;
  if (!std::isfinite(value) || value == 0.0) return kNaN;
  if (IsContinuous(ref)) return std::abs(r.Jbar_fine - value) / std::abs(value);
  if (ref.scheme.empty() || r.transcription != ref.scheme || r.terminal != "hard" || r.N != ref.N) {
    return kNaN;
  }
  return std::abs(r.objective - value) / std::abs(value);
}

std::vector<DerivedFields> DeriveTargets(const std::vector<Record>& records) {
  const Labels labels = LabelRecords(records);
  std::vector<DerivedFields> derived(records.size());
  std::map<std::string, double> best;
  for (size_t i = 0; i < records.size(); ++i) {
    const Record& r = records[i];
    DerivedFields& d = derived[i];
    d.group = GroupKey(r);
    d.section = labels.section[i];
    d.method_label = labels.row[i];
    d.final_J = FinalValue(r);
    if (!std::isfinite(d.final_J)) continue;
    // A hard-form record that did not converge may sit below every feasible answer.
    if (r.terminal == "hard" && r.status != "converged") continue;
    if (!best.count(d.group) || d.final_J < best[d.group]) best[d.group] = d.final_J;
  }
  for (size_t i = 0; i < records.size(); ++i) {
    const Record& r = records[i];
    DerivedFields& d = derived[i];
    const auto it = best.find(d.group);
    if (it == best.end()) continue;
    d.best_J = it->second;
    d.reached_target = WithinTarget(d.final_J, d.best_J);
    if (!d.reached_target) continue;
    for (const IterationRecord& h : r.history) {
      // An iterate of a coarser grid (grid sequencing) has that grid's J: not the request's.
      if (h.intervals >= 0) continue;
      if (WithinTarget(h.J, d.best_J) && !(h.primal_inf > kFeasibleHistory)) {
        d.time_to_target = h.cpu_seconds;
        break;
      }
    }
    // The final answer reached it although no recorded iterate did (the history holds the
    // method's own objective, which differs from J_fine by its discretization error).
    if (std::isnan(d.time_to_target)) d.time_to_target = r.cpu_seconds;
  }
  return derived;
}

std::vector<json> DerivedRecordsJson(const std::vector<Record>& records) {
  const std::vector<DerivedFields> derived = DeriveTargets(records);
  std::vector<json> out;
  out.reserve(records.size());
  for (size_t i = 0; i < records.size(); ++i) {
    json j = records[i].ToJson();
    const DerivedFields& d = derived[i];
    j["group"] = d.group;
    j["section"] = d.section;
    j["method_label"] = d.method_label;
    j["final_J"] = JsonNumber(d.final_J);
    j["best_J"] = JsonNumber(d.best_J);
    j["reached_target"] = d.reached_target;
    j["time_to_target"] = JsonNumber(d.time_to_target);
    out.push_back(std::move(j));
  }
  return out;
}

std::string SummaryMarkdown(const std::string& suite_name,
                            const std::vector<Record>& records,
                            size_t expected_cases) {
  std::ostringstream md;
  md << "# Suite `" << suite_name << "`\n\n";
  if (expected_cases > 0 && records.size() < expected_cases) {
    md << fmt::format(
        "**Partial: {} of the suite's {} cases are recorded** (the others are missing: a run "
        "or shard that has not finished, or was not merged). Every mean, median and best below "
        "covers the recorded cases only.\n\n",
        records.size(),
        expected_cases);
  }
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
        "never. n/m = reached in n of m cases.\n\n"
        "Status is OCPBench's grouping of each solver's own code (an Ipopt stop at its acceptable "
        "level stays `acceptable`, never `converged`). Warnings say what a status does not: "
        "`discretization` when a method's own objective and the fine re-simulation of its "
        "controls differ by more than 1% (the grid, not the method, limits the answer), "
        "`terminal_weights_default` for the penalty form of a problem that never chose its "
        "terminal weights, `infeasible` when the controls re-simulated on the fine grid violate "
        "U, a path constraint or (hard form) the terminal constraints by more than 1e-3, "
        "`not_finite` when the re-simulation on the method's grid (J) is not finite (with the "
        "status numerical_failure unless the fine one is finite and the method's scheme is "
        "not the judge's integrator), `reformulated` when the method solved the problem's "
        "Hamiltonian reformulation (penalties for path constraints, a regularized H) rather than "
        "the problem. Each "
        "record's `stopping_tolerance` names the option that bounds its "
        "accuracy (Ipopt: `tol`).\n\n";
  md << OverviewMarkdown(records);
  const Labels labels = LabelRecords(records);
  const std::vector<DerivedFields> derived = DeriveTargets(records);
  std::vector<std::string> sections;
  for (const std::string& s : labels.section) {
    if (std::find(sections.begin(), sections.end(), s) == sections.end()) sections.push_back(s);
  }
  for (const std::string& section : sections) {
    md << "## " << section << "\n\n";
    std::vector<std::string> methods;
    std::map<std::string, std::vector<size_t>> by_method;
    const RecordReference* reference = nullptr;
    bool free_time = false;  // a free final time: the table says each method's T
    bool costates = false;   // some record has a costate error against a known p*
    // State bounds or a free initial state: the table says how far outside them the fine
    // re-simulation goes, and where a free x(t0) was put.
    bool bounds = false;
    bool free_start = false;
    bool boundary = false;
    bool peer = false;  // some record solved an NLP whose optimum a peer published
    for (size_t i = 0; i < records.size(); ++i) {
      if (labels.section[i] != section) continue;
      const Record& r = records[i];
      free_time = free_time || r.final_time_free;
      costates = costates || std::isfinite(r.costate_error);
      bounds = bounds || r.state_bound_violation.has_value();
      free_start = free_start || !r.initial_state.empty();
      boundary = boundary || r.boundary_violation.has_value();
      peer = peer || r.nlp_reference.has_value();
      if (!by_method.count(labels.row[i])) methods.push_back(labels.row[i]);
      by_method[labels.row[i]].push_back(i);
      if (!reference && r.reference && std::isfinite(r.reference->value)) {
        reference = &*r.reference;
      }
    }
    if (reference) md << ReferenceNote(*reference) << "\n\n";
    if (costates) {
      md << "Costate error: the worst over a row's cases of max |p - p*| / max |p*| on the "
            "method's own costate grid, against the problem's known optimal costate (record "
            "field costate_error; empty where a method has no costates or the case is not the "
            "problem as posed).\n\n";
    }
    if (peer) {
      md << "NLP vs peer: |objective - value| / |value| against a peer's published optimum of "
            "the same NLP (the row's transcription and N; record field nlp_reference, e.g. "
            "CTBenchmarks' trapezoid values), the worst over the row's cases that have one: a "
            "check that the transcription is the peer's NLP, not an accuracy.\n\n";
    }
    if (bounds || free_start || boundary) {
      md << "State bounds, a free initial state, boundary constraints: state bound viol. fine is "
            "the worst over a row's cases of how far the fine re-simulation leaves the state "
            "bounds (and x(t0) its bounds; record field state_bound_violation); x(t0) is where "
            "the row's first case started (record field initial_state); boundary viol. fine how "
            "far b(x(t0), x(tf)) lies outside its bounds (record field boundary_violation).\n\n";
    }
    md << "| method | cases | status | warnings | J | Jbar | J fine | Jbar fine | terminal viol. | "
          "terminal viol. fine | U viol. | path viol. | resim. defect | iterations | CPU s | "
          "time to target s |"
       << (free_time ? " final time T |" : "") << (reference ? " rel. error vs reference |" : "")
       << (costates ? " costate error |" : "") << (bounds ? " state bound viol. fine |" : "")
       << (free_start ? " x(t0) |" : "") << (boundary ? " boundary viol. fine |" : "")
       << (peer ? " NLP vs peer |" : "") << "\n";
    md << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
       << (free_time ? "---|" : "") << (reference ? "---|" : "") << (costates ? "---|" : "")
       << (bounds ? "---|" : "") << (free_start ? "---|" : "") << (boundary ? "---|" : "")
       << (peer ? "---|" : "") << "\n";
    std::vector<std::string> notes;  // one line per row and warning code: its first message
    for (const std::string& m : methods) {
      const auto& rs = by_method[m];
      std::map<std::string, int> statuses;
      std::map<std::string, int> warnings;
      std::map<std::string, std::string> first_message;
      std::vector<double> J, Jbar, Jf, Jbarf, tv, tvf, cv, pv, defect, it, cpu, ttt, rel, T, pe;
      std::vector<double> sbv, bv, nlp;
      std::string starts;  // the x(t0) of the row's first case that has one
      int reached = 0;
      for (const size_t i : rs) {
        const Record& r = records[i];
        statuses[r.status]++;
        for (const RecordWarning& w : r.warnings) {
          if (warnings[w.code]++ == 0) first_message[w.code] = w.message;
        }
        J.push_back(r.J);
        Jbar.push_back(r.Jbar);
        Jf.push_back(r.J_fine);
        Jbarf.push_back(r.Jbar_fine);
        tv.push_back(r.terminal_violation);
        tvf.push_back(r.terminal_violation_fine);
        cv.push_back(r.control_violation);
        pv.push_back(r.path_violation);
        defect.push_back(r.resimulation_defect);
        it.push_back(r.iterations >= 0 ? r.iterations : kNaN);
        cpu.push_back(r.cpu_seconds);
        T.push_back(r.final_time);
        pe.push_back(r.costate_error);
        sbv.push_back(r.state_bound_violation.value_or(kNaN));
        bv.push_back(r.boundary_violation.value_or(kNaN));
        if (starts.empty() && !r.initial_state.empty()) {
          for (const double x : r.initial_state) {
            starts += (starts.empty() ? "" : ", ") + SummaryNumber(x);
          }
        }
        const double t = derived[i].time_to_target;
        if (std::isfinite(t)) {
          ttt.push_back(t);
          ++reached;
        }
        if (reference) rel.push_back(ReferenceError(r, *reference));
        if (r.nlp_reference) nlp.push_back(ReferenceError(r, *r.nlp_reference));
      }
      std::string st;
      for (const auto& [s, n] : statuses)
        st += (st.empty() ? "" : ", ") + fmt::format("{} {}", n, s);
      std::string wt;
      for (const auto& [code, n] : warnings) {
        wt += (wt.empty() ? "" : ", ") + fmt::format("{} {}", n, code);
        notes.push_back(fmt::format("- {}: {} ({} of {} cases), for example: {}",
                                    m,
                                    code,
                                    n,
                                    rs.size(),
                                    first_message[code]));
      }
      md << fmt::format(
          "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} ({}/{}) "
          "|",
          m,
          rs.size(),
          st,
          wt.empty() ? "-" : wt,
          Spread(J),
          Spread(Jbar),
          Spread(Jf),
          Spread(Jbarf),
          SummaryNumber(WorstOf(tv)),
          SummaryNumber(WorstOf(tvf)),
          SummaryNumber(WorstOf(cv)),
          SummaryNumber(WorstOf(pv)),
          SummaryNumber(WorstOf(defect)),
          SummaryNumber(Median(it)),
          SummaryNumber(Median(cpu)),
          SummaryNumber(Median(ttt)),
          reached,
          rs.size());
      if (free_time) md << " " << Spread(T) << " |";
      if (reference) md << " " << Spread(rel) << " |";
      if (costates) md << " " << SummaryNumber(WorstOf(pe)) << " |";
      if (bounds) md << " " << SummaryNumber(WorstOf(sbv)) << " |";
      if (free_start) md << " " << (starts.empty() ? "-" : "(" + starts + ")") << " |";
      if (boundary) md << " " << SummaryNumber(WorstOf(bv)) << " |";
      if (peer) md << " " << SummaryNumber(WorstOf(nlp)) << " |";
      md << "\n";
    }
    md << "\n";
    if (!notes.empty()) {
      md << "Warnings (the records' `warnings`):\n\n";
      for (const std::string& n : notes) md << n << "\n";
      md << "\n";
    }
  }
  return md.str();
}

std::string RecordsCsv(const std::vector<Record>& records) {
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
                                   "final_time",
                                   "discretization_gap",
                                   "costate_error"};
  std::ostringstream csv;
  bool first = true;
  for (const char* c : kColumns) {
    csv << (first ? "" : ",") << c;
    first = false;
  }
  csv << "\n";
  for (const json& r : DerivedRecordsJson(records)) {
    first = true;
    for (const char* c : kColumns) {
      csv << (first ? "" : ",");
      first = false;
      if (!r.contains(c) || r[c].is_null()) continue;
      if (r[c].is_string()) {
        std::string q = "\"";
        for (char ch : r[c].get<std::string>())
          q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
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
