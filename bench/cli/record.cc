#include "bench/cli/record.h"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "bench/cli/json_values.h"
#include "bench/cli/version.h"

namespace ocpb {
namespace {

using nlohmann::json;

json NumbersJson(const std::vector<double>& v) {
  json a = json::array();
  for (double x : v) a.push_back(JsonNumber(x));
  return a;
}

// Reads the known fields of one JSON object with their types; "FIELD: must be ..." otherwise.
class Reader {
 public:
  /// `movable`: the same object as `j`, when its bulky parts may be moved out (each is read
  /// once), so that reading a record copies no sub-document.
  Reader(const json& j, std::string prefix, json* movable = nullptr)
      : j_(j), prefix_(std::move(prefix)), movable_(movable) {}

  bool Has(const char* key) const { return j_.contains(key) && !j_[key].is_null(); }
  [[noreturn]] void Fail(const std::string& key, const char* rule) const {
    throw std::invalid_argument(prefix_ + key + ": must be " + rule);
  }
  void Text(const char* key, std::string* out) const {
    if (!Has(key)) return;
    if (!j_[key].is_string()) Fail(key, "a string");
    *out = j_[key].get<std::string>();
  }
  void Number(const char* key, double* out) const {
    if (!j_.contains(key)) return;
    *out = NumberAt(j_[key], key);
  }
  void Integer(const char* key, int* out) const {
    if (!Has(key)) return;
    const json& v = j_[key];
    // An unsigned beyond INT64_MAX would read as a negative long long: compared as given.
    const bool fits = v.is_number_unsigned()
                          ? v.get<std::uint64_t>() <= std::numeric_limits<int>::max()
                          : v.is_number_integer() &&
                                v.get<long long>() >= std::numeric_limits<int>::min() &&
                                v.get<long long>() <= std::numeric_limits<int>::max();
    if (!fits) Fail(key, "an integer");
    *out = static_cast<int>(v.get<long long>());
  }
  void Bool(const char* key, bool* out) const {
    if (!Has(key)) return;
    if (!j_[key].is_boolean()) Fail(key, "true or false");
    *out = j_[key].get<bool>();
  }
  void Numbers(const char* key, std::vector<double>* out) const {
    if (!Has(key)) return;
    if (!j_[key].is_array()) Fail(key, "an array of numbers");
    out->clear();
    for (const json& x : j_[key]) out->push_back(NumberAt(x, key));
  }
  void Integers(const char* key, int min, std::vector<int>* out) const {
    if (!Has(key)) return;
    if (!j_[key].is_array()) Fail(key, "an array of integers");
    out->clear();
    for (const json& x : j_[key]) {
      if (!x.is_number_integer() || x.get<long long>() < min ||
          x.get<long long>() > std::numeric_limits<int>::max()) {
        Fail(key, min == 1 ? "an array of integers >= 1" : "an array of integers");
      }
      out->push_back(static_cast<int>(x.get<long long>()));
    }
  }
  void Object(const char* key, json* out) const {
    if (!Has(key)) return;
    if (!j_[key].is_object()) Fail(key, "an object");
    Take(key, out);
  }
  void Any(const char* key, json* out) const {
    if (j_.contains(key)) Take(key, out);
  }
  void TextMap(const char* key, std::map<std::string, std::string>* out) const {
    if (!Has(key)) return;
    if (!j_[key].is_object()) Fail(key, "an object");
    for (const auto& [k, v] : j_[key].items()) {
      // Records store option values as text; a typed value (hand-written records) is read as
      // its text too.
      (*out)[k] = v.is_string() ? v.get<std::string>() : v.dump();
    }
  }
  void NumberMap(const char* key, std::map<std::string, double>* out) const {
    if (!Has(key)) return;
    if (!j_[key].is_object()) Fail(key, "an object");
    for (const auto& [k, v] : j_[key].items()) (*out)[k] = NumberAt(v, key);
  }
  Mat Rows(const json& rows, const std::string& key) const {
    if (!rows.is_array()) Fail(key, "an array of rows");
    Mat m;
    for (size_t i = 0; i < rows.size(); ++i) {
      if (!rows[i].is_array()) Fail(key, "an array of rows");
      if (i == 0) m.resize(static_cast<Eigen::Index>(rows.size()), rows[0].size());
      if (static_cast<Eigen::Index>(rows[i].size()) != m.cols()) Fail(key, "rows of one length");
      for (size_t k = 0; k < rows[i].size(); ++k) m(i, k) = NumberAt(rows[i][k], key);
    }
    return m;
  }
  const json& j() const { return j_; }
  const std::string& prefix() const { return prefix_; }
  /// The value at `key` (present), moved out when the document may be taken apart.
  void Take(const char* key, json* out) const {
    if (movable_ != nullptr) {
      *out = std::move((*movable_)[key]);
    } else {
      *out = j_[key];
    }
  }

 private:
  double NumberAt(const json& v, const std::string& key) const {
    if (v.is_null()) return NAN;
    if (!v.is_number()) Fail(key, "a number or null");
    return v.get<double>();
  }
  const json& j_;
  std::string prefix_;
  json* movable_;
};

json HistoryJson(const std::vector<IterationRecord>& history) {
  json hist = json::array();
  for (const IterationRecord& h : history) {
    hist.push_back(json{{"iteration", h.iteration},
                        {"J", JsonNumber(h.J)},
                        {"theta", JsonNumber(h.theta)},
                        {"armijo_j", h.armijo_j},
                        {"primal_inf", JsonNumber(h.primal_inf)},
                        {"dual_inf", JsonNumber(h.dual_inf)},
                        {"cpu_seconds", JsonNumber(h.cpu_seconds)}});
    if (h.intervals > 0) hist.back()["intervals"] = h.intervals;
  }
  return hist;
}

// The SolveStatus whose ToString is `name`.
std::optional<SolveStatus> ParseSolveStatus(const std::string& name) {
  for (int i = 0; i <= static_cast<int>(SolveStatus::kError); ++i) {
    const auto status = static_cast<SolveStatus>(i);
    if (name == ToString(status)) return status;
  }
  return std::nullopt;
}

constexpr const char* kStatusRule =
    "one of converged, acceptable, max_iterations, max_time, step_too_small, "
    "roundoff_limited, infeasible, numerical_failure, invalid_input, not_applicable, error";

json MeshJson(const RecordMesh& m) {
  json rows = json::array();
  for (const MeshIterationRecord& row : m.history) {
    rows.push_back(json{{"intervals", row.intervals},
                        {"nlp_variables", row.nlp_variables},
                        {"nlp_constraints", row.nlp_constraints},
                        {"max_error", JsonNumber(row.max_error)},
                        {"iterations", row.iterations},
                        {"cpu_seconds", JsonNumber(row.cpu_seconds)},
                        {"status", ToString(row.status)},
                        {"solver_status", row.solver_status}});
    if (!row.degrees.empty()) rows.back()["degrees"] = row.degrees;
  }
  return json{{"stop_reason", m.stop_reason}, {"nodes", m.nodes}, {"history", rows}};
}

RecordMesh MeshFrom(const Reader& r) {
  const json& m = r.j()["mesh"];
  if (!m.is_object()) r.Fail("mesh", "an object");
  const Reader mr(m, "mesh.");
  RecordMesh out;
  mr.Text("stop_reason", &out.stop_reason);
  mr.Numbers("nodes", &out.nodes);
  if (!mr.Has("history")) return out;
  if (!m["history"].is_array()) mr.Fail("history", "an array");
  size_t i = 0;
  for (const json& h : m["history"]) {
    const std::string where = "mesh.history[" + std::to_string(i++) + "]";
    if (!h.is_object()) r.Fail(where, "an object");
    const Reader row(h, where + ".");
    MeshIterationRecord rec;
    row.Integer("intervals", &rec.intervals);
    row.Integer("nlp_variables", &rec.nlp_variables);
    row.Integer("nlp_constraints", &rec.nlp_constraints);
    row.Number("max_error", &rec.max_error);
    row.Integer("iterations", &rec.iterations);
    row.Number("cpu_seconds", &rec.cpu_seconds);
    std::string status;
    row.Text("status", &status);
    if (!status.empty()) {
      const std::optional<SolveStatus> parsed = ParseSolveStatus(status);
      if (!parsed) row.Fail("status", "a status name");
      rec.status = *parsed;
    }
    row.Text("solver_status", &rec.solver_status);
    row.Integers("degrees", 1, &rec.degrees);
    out.history.push_back(rec);
  }
  return out;
}

std::vector<IterationRecord> HistoryFrom(const Reader& r) {
  std::vector<IterationRecord> out;
  if (!r.Has("history")) return out;
  if (!r.j()["history"].is_array()) r.Fail("history", "an array");
  size_t i = 0;
  for (const json& h : r.j()["history"]) {
    if (!h.is_object()) r.Fail("history", "an array of objects");
    const Reader row(h, r.prefix() + "history[" + std::to_string(i++) + "].");
    IterationRecord rec;
    row.Integer("iteration", &rec.iteration);
    row.Number("J", &rec.J);
    row.Number("theta", &rec.theta);
    row.Integer("armijo_j", &rec.armijo_j);
    row.Number("primal_inf", &rec.primal_inf);
    row.Number("dual_inf", &rec.dual_inf);
    row.Number("cpu_seconds", &rec.cpu_seconds);
    row.Integer("intervals", &rec.intervals);
    if (row.Has("intervals") && rec.intervals < 1) row.Fail("intervals", "an integer >= 1");
    out.push_back(rec);
  }
  return out;
}

void OnlineToJson(const OnlineOutcome& o, json* rec) {
  json& r = *rec;
  r["online"] = o.settings;
  json replan = json::object();
  for (const auto& [k, v] : o.replan_options) replan[k] = v;
  r["replan_options"] = replan;
  r["cycles"] = o.cycles;
  r["energy_true"] = JsonNumber(o.energy_true);
  r["energy_predicted"] = JsonNumber(o.energy_predicted);
  r["J_true"] = JsonNumber(o.J_true);
  r["transmit_energy_true"] = JsonNumber(o.transmit_energy_true);
  r["offline_transmit_energy_true"] = JsonNumber(o.offline_transmit_energy_true);
  r["transmit_energy_ratio"] = JsonNumber(o.transmit_energy_ratio);
  r["energy_ratio"] = JsonNumber(o.energy_ratio);
  r["offline_energy_true"] = JsonNumber(o.offline_energy_true);
  r["offline_energy_predicted"] = JsonNumber(o.offline_energy_predicted);
  r["offline_J_true"] = JsonNumber(o.offline_J_true);
  r["offline_terminal_violation"] = JsonNumber(o.offline_terminal_violation);
  r["offline_terminal_residual"] = NumbersJson(o.offline_terminal_residual);
  r["offline_solve_seconds"] = JsonNumber(o.offline_solve_seconds);
  if (!o.executed.is_null()) r["executed"] = o.executed;
  if (!o.offline.is_null()) r["offline"] = o.offline;
  if (!o.measurements.is_null()) r["measurements"] = o.measurements;
}

OnlineOutcome OnlineFrom(const Reader& r) {
  OnlineOutcome o;
  r.Object("online", &o.settings);
  r.TextMap("replan_options", &o.replan_options);
  if (r.Has("cycles")) {
    if (!r.j()["cycles"].is_array()) r.Fail("cycles", "an array");
    r.Take("cycles", &o.cycles);
  }
  r.Number("energy_true", &o.energy_true);
  r.Number("energy_predicted", &o.energy_predicted);
  r.Number("J_true", &o.J_true);
  r.Number("transmit_energy_true", &o.transmit_energy_true);
  r.Number("offline_transmit_energy_true", &o.offline_transmit_energy_true);
  r.Number("transmit_energy_ratio", &o.transmit_energy_ratio);
  r.Number("energy_ratio", &o.energy_ratio);
  r.Number("offline_energy_true", &o.offline_energy_true);
  r.Number("offline_energy_predicted", &o.offline_energy_predicted);
  r.Number("offline_J_true", &o.offline_J_true);
  r.Number("offline_terminal_violation", &o.offline_terminal_violation);
  r.Numbers("offline_terminal_residual", &o.offline_terminal_residual);
  r.Number("offline_solve_seconds", &o.offline_solve_seconds);
  r.Any("executed", &o.executed);
  r.Any("offline", &o.offline);
  r.Any("measurements", &o.measurements);
  return o;
}

}  // namespace

RecordVersions CurrentVersions() {
  return RecordVersions{
      OCPB_VERSION, GitCommit(), CompilerVersion(), IpoptVersion(), NloptVersion()};
}

json Record::ToJson() const {
  json r;
  r["schema_version"] = schema_version;
  if (kind != "solve") r["kind"] = kind;
  r["key"] = key;
  r["problem"] = problem;
  json params = json::object();
  for (const auto& [k, v] : parameters) params[k] = v.size() == 1 ? json(v[0]) : json(v);
  r["parameters"] = params;
  r["seed"] = seed;
  r["uses_seed"] = uses_seed;
  r["solver"] = solver;
  r["transcription"] = transcription;
  r["algorithm"] = algorithm;
  r["N"] = N;
  if (degree) r["degree"] = *degree;
  r["terminal"] = terminal;
  r["integrator"] = integrator;
  r["evaluated_with"] = evaluated_with;
  json opts = json::object();
  for (const auto& [k, v] : options) opts[k] = v;
  r["options"] = opts;
  r["solver_options"] = solver_options;
  r["transcription_options"] = transcription_options;
  if (initial_guess) r["initial_guess"] = *initial_guess;
  r["repeats"] = repeats;

  // Every record OCPBench makes has a status; one read without it (the reader tolerates that)
  // is written back without it, not with an empty text, which is no status name.
  if (!status.empty()) r["status"] = status;
  r["solver_status"] = solver_status;
  r["message"] = message;
  r["objective"] = JsonNumber(objective);
  r["iterations"] = iterations;
  r["cpu_seconds"] = JsonNumber(cpu_seconds);
  r["cpu_seconds_repeats"] = NumbersJson(cpu_seconds_repeats);
  r["wall_seconds"] = JsonNumber(wall_seconds);
  json stats = json::object();
  for (const auto& [k, v] : solver_stats) stats[k] = JsonNumber(v);
  r["solver_stats"] = stats;
  r["history"] = HistoryJson(history);

  r["J"] = JsonNumber(J);
  r["Jbar"] = JsonNumber(Jbar);
  r["terminal_violation"] = JsonNumber(terminal_violation);
  r["control_violation"] = JsonNumber(control_violation);
  r["path_violation"] = JsonNumber(path_violation);
  r["terminal_residual"] = NumbersJson(terminal_residual);
  r["final_state"] = NumbersJson(final_state);
  r["J_fine"] = JsonNumber(J_fine);
  r["Jbar_fine"] = JsonNumber(Jbar_fine);
  r["terminal_violation_fine"] = JsonNumber(terminal_violation_fine);
  r["resimulation_defect"] = JsonNumber(resimulation_defect);
  r["final_time"] = JsonNumber(final_time);
  r["final_time_free"] = final_time_free;
  if (!initial_state.empty()) r["initial_state"] = NumbersJson(initial_state);
  if (!static_parameters.empty()) r["static_parameters"] = NumbersJson(static_parameters);
  if (state_bound_violation) r["state_bound_violation"] = JsonNumber(*state_bound_violation);
  if (boundary_violation) {
    r["boundary_residual"] = NumbersJson(boundary_residual);
    r["boundary_violation"] = JsonNumber(*boundary_violation);
  }
  r["discretization_gap"] = JsonNumber(discretization_gap);
  json warn = json::array();
  for (const RecordWarning& w : warnings)
    warn.push_back({{"code", w.code}, {"message", w.message}});
  r["warnings"] = warn;
  if (stopping_tolerance) {
    r["stopping_tolerance"] = json{{"option", stopping_tolerance->option},
                                   {"value", JsonNumber(stopping_tolerance->value)},
                                   {"note", stopping_tolerance->note}};
  }
  if (continuation) {
    r["continuation"] = json{{"from", continuation->from},
                             {"status", continuation->status},
                             {"solver_status", continuation->solver_status},
                             {"message", continuation->message},
                             {"iterations", continuation->iterations},
                             {"cpu_seconds", JsonNumber(continuation->cpu_seconds)}};
    if (continuation->status.empty()) r["continuation"].erase("status");  // as for the status
  }
  if (mesh) r["mesh"] = MeshJson(*mesh);
  if (trajectory) {
    json t{{"t", trajectory->t},
           {"x", JsonRows(trajectory->x)},
           {"u", JsonRows(trajectory->u)},
           {"u_rule", trajectory->u_rule}};
    if (!trajectory->own_t.empty()) {
      json own{{"t", trajectory->own_t}, {"x", JsonRows(trajectory->own_x)}};
      if (trajectory->own_p.size() > 0) own["p"] = JsonRows(trajectory->own_p);
      t["own"] = own;
    }
    r["trajectory"] = t;
  }
  if (!costate_source.empty()) r["costate_source"] = costate_source;
  if (std::isfinite(costate_error)) r["costate_error"] = costate_error;
  if (costates) r["costates"] = json{{"t", costates->t}, {"p", JsonRows(costates->p)}};
  if (!s_map.is_null()) r["s_map"] = s_map;
  const auto reference_json = [](const RecordReference& reference) {
    json ref{{"value", JsonNumber(reference.value)},
             {"quantity", reference.quantity},
             {"source", reference.source},
             {"scheme", reference.scheme}};
    if (reference.scheme != "continuous") ref["N"] = reference.N;
    return ref;
  };
  if (reference) r["reference"] = reference_json(*reference);
  if (nlp_reference) r["nlp_reference"] = reference_json(*nlp_reference);
  if (online) OnlineToJson(*online, &r);
  if (truth && !online) {
    r["truth_model"] = truth->model;
    r["energy_true"] = JsonNumber(truth->energy_true);
    r["transmit_energy_true"] = JsonNumber(truth->transmit_energy_true);
    r["J_true"] = JsonNumber(truth->J_true);
    r["max_distance_from_segment"] = JsonNumber(truth->max_distance_from_segment);
    r["min_distance_to_base"] = JsonNumber(truth->min_distance_to_base);
  }
  r["versions"] = json{{"ocpbench", versions.ocpbench},
                       {"commit", versions.commit},
                       {"compiler", versions.compiler},
                       {"ipopt", versions.ipopt},
                       {"nlopt", versions.nlopt}};
  return r;
}

Record Record::FromJson(const json& j) { return Read(j, nullptr); }

Record Record::FromJson(json&& j) { return Read(j, &j); }

Record Record::Read(const json& j, json* movable) {
  if (!j.is_object()) throw std::invalid_argument("a record must be a JSON object");
  const Reader r(j, "", movable);
  Record rec;
  rec.schema_version = 1;  // records before the typed record carry none
  r.Integer("schema_version", &rec.schema_version);
  if (rec.schema_version < 1 || rec.schema_version > kRecordSchemaVersion) {
    throw std::invalid_argument("schema_version: " + std::to_string(rec.schema_version) +
                                " is not one this build reads (1 to " +
                                std::to_string(kRecordSchemaVersion) + ")");
  }
  r.Text("kind", &rec.kind);
  if (rec.kind != "solve" && rec.kind != "online") r.Fail("kind", "\"solve\" or \"online\"");
  r.Text("key", &rec.key);
  r.Text("problem", &rec.problem);
  if (r.Has("parameters")) {
    if (!j["parameters"].is_object()) r.Fail("parameters", "an object");
    for (const auto& [k, v] : j["parameters"].items()) {
      const Reader p(j["parameters"], "parameters.");
      std::vector<double> values;
      if (v.is_array()) {
        p.Numbers(k.c_str(), &values);
      } else {
        double x = NAN;
        p.Number(k.c_str(), &x);
        values = {x};
      }
      rec.parameters[k] = values;
    }
  }
  if (r.Has("seed")) {
    if (!j["seed"].is_number_integer() ||
        (!j["seed"].is_number_unsigned() && j["seed"].get<std::int64_t>() < 0)) {
      r.Fail("seed", "an integer >= 0");
    }
    rec.seed = j["seed"].get<std::uint64_t>();
  }
  r.Bool("uses_seed", &rec.uses_seed);
  r.Text("solver", &rec.solver);
  r.Text("transcription", &rec.transcription);
  r.Text("algorithm", &rec.algorithm);
  r.Integer("N", &rec.N);
  if (r.Has("degree")) {
    int d = 0;
    r.Integer("degree", &d);
    rec.degree = d;
  }
  r.Text("terminal", &rec.terminal);
  r.Text("integrator", &rec.integrator);
  r.Text("evaluated_with", &rec.evaluated_with);
  r.TextMap("options", &rec.options);
  r.Object("solver_options", &rec.solver_options);
  r.Object("transcription_options", &rec.transcription_options);
  if (r.Has("initial_guess")) {
    std::string path;
    r.Text("initial_guess", &path);
    rec.initial_guess = path;
  }
  r.Integer("repeats", &rec.repeats);

  r.Text("status", &rec.status);
  // The schema's list (results/record.schema.json, $defs.status), not any text: compare and
  // the summaries count statuses by name.
  if (r.Has("status") && !ParseSolveStatus(rec.status)) r.Fail("status", kStatusRule);
  r.Text("solver_status", &rec.solver_status);
  r.Text("message", &rec.message);
  r.Number("objective", &rec.objective);
  r.Integer("iterations", &rec.iterations);
  r.Number("cpu_seconds", &rec.cpu_seconds);
  r.Numbers("cpu_seconds_repeats", &rec.cpu_seconds_repeats);
  r.Number("wall_seconds", &rec.wall_seconds);
  r.NumberMap("solver_stats", &rec.solver_stats);
  rec.history = HistoryFrom(r);

  r.Number("J", &rec.J);
  r.Number("Jbar", &rec.Jbar);
  r.Number("terminal_violation", &rec.terminal_violation);
  r.Number("control_violation", &rec.control_violation);
  r.Number("path_violation", &rec.path_violation);
  r.Numbers("terminal_residual", &rec.terminal_residual);
  r.Numbers("final_state", &rec.final_state);
  r.Number("J_fine", &rec.J_fine);
  r.Number("Jbar_fine", &rec.Jbar_fine);
  r.Number("terminal_violation_fine", &rec.terminal_violation_fine);
  r.Number("resimulation_defect", &rec.resimulation_defect);
  r.Number("final_time", &rec.final_time);
  r.Bool("final_time_free", &rec.final_time_free);
  r.Numbers("initial_state", &rec.initial_state);
  r.Numbers("static_parameters", &rec.static_parameters);
  if (j.contains("state_bound_violation")) {
    double v = NAN;
    r.Number("state_bound_violation", &v);
    rec.state_bound_violation = v;
  }
  r.Numbers("boundary_residual", &rec.boundary_residual);
  if (j.contains("boundary_violation")) {
    double v = NAN;
    r.Number("boundary_violation", &v);
    rec.boundary_violation = v;
  }
  r.Number("discretization_gap", &rec.discretization_gap);
  if (r.Has("warnings")) {
    if (!j["warnings"].is_array()) r.Fail("warnings", "an array");
    size_t i = 0;
    for (const json& w : j["warnings"]) {
      const std::string where = "warnings[" + std::to_string(i++) + "]";
      if (!w.is_object()) r.Fail(where, "an object");
      const Reader wr(w, where + ".");
      RecordWarning out;
      wr.Text("code", &out.code);
      wr.Text("message", &out.message);
      rec.warnings.push_back(out);
    }
  }
  if (r.Has("stopping_tolerance")) {
    if (!j["stopping_tolerance"].is_object()) r.Fail("stopping_tolerance", "an object");
    const Reader st(j["stopping_tolerance"], "stopping_tolerance.");
    RecordStoppingTolerance out;
    st.Text("option", &out.option);
    st.Number("value", &out.value);
    st.Text("note", &out.note);
    rec.stopping_tolerance = out;
  }
  if (r.Has("continuation")) {
    if (!j["continuation"].is_object()) r.Fail("continuation", "an object");
    const Reader c(j["continuation"], "continuation.");
    RecordContinuation out;
    c.Text("from", &out.from);
    c.Text("status", &out.status);
    if (c.Has("status") && !ParseSolveStatus(out.status)) c.Fail("status", kStatusRule);
    c.Text("solver_status", &out.solver_status);
    c.Text("message", &out.message);
    c.Integer("iterations", &out.iterations);
    c.Number("cpu_seconds", &out.cpu_seconds);
    rec.continuation = out;
  }
  if (r.Has("mesh")) rec.mesh = MeshFrom(r);
  if (r.Has("trajectory")) {
    const json& t = j["trajectory"];
    if (!t.is_object()) r.Fail("trajectory", "an object");
    const Reader tr(t, "trajectory.");
    RecordTrajectory traj;
    tr.Numbers("t", &traj.t);
    if (tr.Has("x")) traj.x = tr.Rows(t["x"], "x");
    if (tr.Has("u")) traj.u = tr.Rows(t["u"], "u");
    tr.Text("u_rule", &traj.u_rule);
    if (tr.Has("own")) {
      const json& o = t["own"];
      if (!o.is_object()) tr.Fail("own", "an object");
      const Reader own(o, "trajectory.own.");
      own.Numbers("t", &traj.own_t);
      if (own.Has("x")) traj.own_x = own.Rows(o["x"], "x");
      if (own.Has("p")) traj.own_p = own.Rows(o["p"], "p");
    }
    rec.trajectory = std::move(traj);
  }
  r.Text("costate_source", &rec.costate_source);
  r.Number("costate_error", &rec.costate_error);
  if (r.Has("costates")) {
    const json& c = j["costates"];
    if (!c.is_object()) r.Fail("costates", "an object");
    const Reader cr(c, "costates.");
    RecordCostates out;
    cr.Numbers("t", &out.t);
    if (cr.Has("p")) out.p = cr.Rows(c["p"], "p");
    if (out.p.size() > 0 && static_cast<size_t>(out.p.cols()) != out.t.size()) {
      cr.Fail("p", "rows of as many values as t");
    }
    rec.costates = std::move(out);
  }
  r.Any("s_map", &rec.s_map);
  const auto read_reference = [&](const std::string& field) {
    if (!j[field].is_object()) r.Fail(field, "an object");
    const Reader ref(j[field], field + ".");
    RecordReference out;
    ref.Number("value", &out.value);
    ref.Text("quantity", &out.quantity);
    ref.Text("source", &out.source);
    // Records from before the reference named its scheme: the comparison is then undefined.
    out.scheme.clear();
    ref.Text("scheme", &out.scheme);
    ref.Integer("N", &out.N);
    return out;
  };
  if (r.Has("reference")) rec.reference = read_reference("reference");
  if (r.Has("nlp_reference")) rec.nlp_reference = read_reference("nlp_reference");
  if (rec.kind == "online") {
    rec.online = OnlineFrom(r);
  } else if (r.Has("truth_model") || r.Has("energy_true")) {
    RecordTruth t;
    r.Text("truth_model", &t.model);
    r.Number("energy_true", &t.energy_true);
    r.Number("transmit_energy_true", &t.transmit_energy_true);
    r.Number("J_true", &t.J_true);
    r.Number("max_distance_from_segment", &t.max_distance_from_segment);
    r.Number("min_distance_to_base", &t.min_distance_to_base);
    rec.truth = t;
  }
  if (r.Has("versions")) {
    if (!j["versions"].is_object()) r.Fail("versions", "an object");
    const Reader v(j["versions"], "versions.");
    v.Text("ocpbench", &rec.versions.ocpbench);
    v.Text("commit", &rec.versions.commit);
    v.Text("compiler", &rec.versions.compiler);
    v.Text("ipopt", &rec.versions.ipopt);
    v.Text("nlopt", &rec.versions.nlopt);
  }
  return rec;
}

}  // namespace ocpb
