#include "bench/cli/case_spec.h"

#include <charconv>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "bench/cli/json_values.h"
#include "drivers/online/online_scenario.h"
#include "solvers/registry.h"

namespace ocpb {
namespace {

using nlohmann::json;

// Whether the registered solver `name` has its own option `key` (false for an unknown name:
// keys and records are also made of cases that failed to resolve).
bool SolverHasOption(const std::string& name, const std::string& key) {
  for (const SolverInfo& info : Solvers()) {
    if (info.name == name) return info.options.Contains(key);
  }
  return false;
}

// The option a case field (algorithm, degree) sets: its value resolved by the owner's
// `schema`, into the owner's resolved options, agreeing with an entry the options gave too.
void SetFromField(const char* field,
                  const OptionSchema& schema,
                  const std::string& key,
                  const OptionValue& value,
                  OptionMap* owner_options) {
  OptionValue resolved;
  try {
    resolved = schema.ResolveOne(key, value);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string(field) + ": " + e.what());
  }
  if (const OptionValue* given = owner_options->Find(key)) {
    if (!(*given == resolved)) {
      throw std::invalid_argument(std::string(field) + ": '" + resolved.ToText() +
                                  "' disagrees with options." + key + " = '" + given->ToText() +
                                  "' (give it once)");
    }
  }
  owner_options->Set(key, resolved);
}

// The transcription whose options the case may give: none for a solver that takes none.
const TranscriptionInfo* OptionTranscription(const SolverInfo& sinfo, const CaseSpec& spec) {
  if (!sinfo.uses_transcription || spec.transcription.empty()) return nullptr;
  return &FindTranscription(spec.transcription);
}

// The case's options resolved by their owners' schemas (the solver's first) and split by owner;
// then the case fields `algorithm` and `degree`, spellings of the solver's option "algorithm"
// (NLopt's) and the transcription's "degree" (LGR's), moved into `spec->options` and the
// owner's map, so that both spellings make one case; then the solver's cross-field rules. The
// errors come in that order. A solver with an option "degree" of its own keeps the
// transcription's degree in the case field (the options' "degree" is the solver's).
MethodOptions ResolveMethod(const SolverInfo& sinfo,
                            const TranscriptionInfo* tinfo,
                            CaseSpec* spec) {
  MethodOptions out;
  for (const auto& [key, value] : spec->options) {
    try {
      if (sinfo.options.Contains(key)) {
        out.solver.Set(key, sinfo.options.ResolveOne(key, value));
      } else if (tinfo != nullptr && tinfo->options.Contains(key)) {
        out.transcription.Set(key, tinfo->options.ResolveOne(key, value));
      } else {
        std::string valid = sinfo.options.Names();
        if (tinfo != nullptr)
          valid += "; transcription " + tinfo->name + ": " + tinfo->options.Names();
        throw std::invalid_argument(spec->solver + ": unknown option '" + key +
                                    "' (valid: " + valid + ")");
      }
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("options: ") + e.what());
    }
  }
  if (!spec->algorithm.empty()) {
    if (!sinfo.options.Contains("algorithm")) {
      throw std::invalid_argument("algorithm: solver '" + spec->solver +
                                  "' has no option 'algorithm' (it takes none)");
    }
    SetFromField(
        "algorithm", sinfo.options, "algorithm", OptionValue(spec->algorithm), &out.solver);
    spec->options.Set("algorithm", *out.solver.Find("algorithm"));
    spec->algorithm.clear();
  }
  if (tinfo != nullptr && tinfo->options.Contains("degree") &&
      (spec->degree_given || !out.transcription.Has("degree"))) {
    SetFromField("degree",
                 tinfo->options,
                 "degree",
                 OptionValue(static_cast<long long>(spec->degree)),
                 &out.transcription);
  }
  if (!sinfo.options.Contains("degree")) {
    if (const OptionValue* degree = out.transcription.Find("degree")) {
      spec->options.Set("degree", *degree);
    }
    spec->degree = CaseSpec::kDefaultDegree;
    spec->degree_given = false;
  }
  if (sinfo.check_options) {
    try {
      sinfo.check_options(out.solver);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("options: ") + e.what());
    }
  }
  return out;
}

// The schema's messages name the field ("online option 'estimator': ...", "online: unknown
// option ...").
OptionMap ResolveOnline(const OptionMap& settings) {
  return OnlineScenarioSchema().Resolve(settings);
}

}  // namespace

TerminalMode ParseTerminal(const std::string& s) {
  if (s == "penalty") return TerminalMode::kPenalty;
  if (s == "hard") return TerminalMode::kHard;
  throw std::invalid_argument("terminal: unknown form '" + s + "' (valid: penalty, hard)");
}

OptionMap CaseSpec::OptionsBesideCaseFields() const {
  OptionMap rest = options;
  if (SolverHasOption(solver, "algorithm")) rest.Erase("algorithm");
  if (!SolverHasOption(solver, "degree")) rest.Erase("degree");
  return rest;
}

std::string CaseSpec::Key() const {
  // NLopt's algorithm and LGR's degree in the places their case fields have had since the first
  // records (keys are how --resume, shards and compare find a case again).
  const OptionValue* algorithm_option =
      SolverHasOption(solver, "algorithm") ? options.Find("algorithm") : nullptr;
  const OptionValue* degree_option =
      SolverHasOption(solver, "degree") ? nullptr : options.Find("degree");
  std::string key = fmt::format("{}|seed={}|{}|{}|{}|N={}|deg={}|{}|{}|eval={}",
                                problem,
                                seed,
                                solver,
                                transcription,
                                !algorithm.empty() ? algorithm
                                : algorithm_option ? algorithm_option->ToText()
                                                   : std::string(),
                                intervals,
                                degree_option ? degree_option->ToText() : std::to_string(degree),
                                ToString(terminal),
                                ToString(integrator),
                                ToString(evaluate_with));
  for (const std::string& s : set) key += "|set:" + s;
  for (const auto& [k, v] : OptionsBesideCaseFields()) key += "|opt:" + k + "=" + v.ToText();
  if (!initial_guess.empty()) key += "|guess=" + initial_guess;
  if (!continuation.empty()) key += "|continuation=" + continuation;
  if (kind != "solve") {
    key += "|kind=" + kind;
    for (const auto& [k, v] : online) key += "|online:" + k + "=" + v.ToText();
    for (const auto& [k, v] : replan_options) key += "|replan:" + k + "=" + v.ToText();
  }
  return key;
}

void CaseSpec::Validate() const {
  if (problem.empty()) throw std::invalid_argument("problem: required");
  if (solver.empty()) throw std::invalid_argument("solver: required");
  if (intervals < 0) throw std::invalid_argument("N: must be >= 1 (or omitted for the default)");
  if (degree < 1) throw std::invalid_argument("degree: must be >= 1");
  if (repeats < 1 || repeats > 1000) throw std::invalid_argument("repeats: must be in 1..1000");
  if (kind != "solve" && kind != "online") {
    throw std::invalid_argument("kind: unknown '" + kind + "' (valid: solve, online)");
  }
  if (kind == "solve" && (!online.empty() || !replan_options.empty())) {
    throw std::invalid_argument("online, replan_options: only for kind \"online\"");
  }
  if (!continuation.empty()) {
    if (continuation != "penalty") {
      throw std::invalid_argument("continuation: unknown '" + continuation +
                                  "' (valid: penalty, or none)");
    }
    if (terminal != TerminalMode::kHard) {
      throw std::invalid_argument(
          "continuation: 'penalty' starts the hard form from the penalty solution, so it needs "
          "terminal = hard");
    }
    if (kind != "solve") throw std::invalid_argument("continuation: only for kind \"solve\"");
  }
}

MethodOptions ResolveMethodOptions(const CaseSpec& given) {
  const SolverInfo& sinfo = FindSolver(given.solver);
  CaseSpec spec = given;
  return ResolveMethod(sinfo, OptionTranscription(sinfo, spec), &spec);
}

CaseSpec ResolveCase(CaseSpec spec, MethodOptions* method) {
  const SolverInfo& sinfo = FindSolver(spec.solver);
  if (!spec.transcription.empty()) FindTranscription(spec.transcription);
  MethodOptions resolved = ResolveMethod(sinfo, OptionTranscription(sinfo, spec), &spec);
  // The options as the case gave them, typed.
  OptionMap options;
  for (const auto& [key, value] : spec.options) {
    const OptionValue* v = resolved.solver.Find(key);
    options.Set(key, v ? *v : *resolved.transcription.Find(key));
  }
  spec.options = std::move(options);
  if (spec.kind == "online") {
    spec.online = ResolveOnline(spec.online);
    try {
      spec.replan_options = sinfo.options.Resolve(spec.replan_options);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("replan_options: ") + e.what());
    }
  }
  if (method != nullptr) *method = std::move(resolved);
  return spec;
}

const json* CaseFields::Find(const std::string& key) const {
  if (key == "seed" && seed_ != nullptr) return seed_;
  if (key == "N" && n_ != nullptr) return n_;
  if (method_->is_object()) {
    const auto it = method_->find(key);
    if (it != method_->end()) return &*it;
  }
  if (group_ != nullptr && key != "methods" && key != "seeds" && key != "N") {
    const auto it = group_->find(key);
    if (it != group_->end()) return &*it;
  }
  return nullptr;
}

std::vector<std::string> CaseFields::Keys() const {
  std::set<std::string> keys;
  if (method_->is_object()) {
    for (const auto& [k, v] : method_->items()) keys.insert(k);
  }
  if (group_ != nullptr) {
    for (const auto& [k, v] : group_->items()) {
      if (k != "methods" && k != "seeds" && k != "N") keys.insert(k);
    }
  }
  if (seed_ != nullptr) keys.insert("seed");
  if (n_ != nullptr) keys.insert("N");
  return {keys.begin(), keys.end()};
}

namespace {

constexpr const char* kSeedRule = "must be an integer from 0 to 18446744073709551615";

}  // namespace

std::uint64_t ParseSeed(const std::string& text, const std::string& field) {
  const bool digits_only =
      !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (!digits_only || error != std::errc() || end != text.data() + text.size()) {
    throw std::invalid_argument(field + ": " + kSeedRule + " (got '" + text + "')");
  }
  return value;
}

std::uint64_t SeedFromJson(const json& value, const std::string& field) {
  if (value.is_number_unsigned()) return value.get<std::uint64_t>();
  // A negative integer, or a number written with a fraction or beyond 2^64 (a double): the
  // library's text of it (a double's shortest form), never a wrapped value.
  // (Appended, not `"'" + text + "'"`: GCC 12 reports a false -Wrestrict on that operator+.)
  std::string given = value.dump();
  if (value.is_string()) given.assign(1, '\'').append(value.get<std::string>()).append(1, '\'');
  throw std::invalid_argument(field + ": " + kSeedRule + " (got " + given + ")");
}

CaseSpec ParseCaseSpec(const json& j, const std::string& where) {
  if (!j.is_object()) throw std::invalid_argument(where + ": a case must be a JSON object");
  return ParseCaseSpec(CaseFields(j), where);
}

CaseSpec ParseCaseSpec(const CaseFields& j, const std::string& where) {
  static const std::set<std::string> kKeys = {"problem",
                                              "set",
                                              "seed",
                                              "solver",
                                              "transcription",
                                              "algorithm",
                                              "N",
                                              "degree",
                                              "terminal",
                                              "integrator",
                                              "evaluate_with",
                                              "options",
                                              "repeats",
                                              "keep_trajectory",
                                              "kind",
                                              "online",
                                              "replan_options",
                                              "continuation"};
  auto field = [&](const char* name) { return where + "." + name; };
  for (const std::string& k : j.Keys()) {
    if (!kKeys.count(k)) {
      std::string valid;
      for (const auto& key : kKeys) valid += (valid.empty() ? "" : ", ") + key;
      throw std::invalid_argument(where + ": unknown key '" + k + "' (valid: " + valid + ")");
    }
    // A null is no value: omitting the key is how a case takes the default.
    if (j.Find(k)->is_null()) {
      throw std::invalid_argument(field(k.c_str()) +
                                  ": null is not a value (omit the key for the default)");
    }
  }
  auto get_string = [&](const char* name, std::string* out) {
    const json* v = j.Find(name);
    if (v == nullptr) return;
    if (!v->is_string()) throw std::invalid_argument(field(name) + ": must be a string");
    *out = v->get<std::string>();
  };
  auto get_int = [&](const char* name, long long lo, long long hi, long long* out) {
    const json* v = j.Find(name);
    if (v == nullptr) return;
    if (!v->is_number_integer()) {
      throw std::invalid_argument(field(name) + ": must be an integer");
    }
    // Compared as given: a value beyond the 64-bit range of its sign is never wrapped.
    const bool in_range =
        v->is_number_unsigned()
            ? v->get<std::uint64_t>() <= static_cast<std::uint64_t>(hi) &&
                  (lo <= 0 || v->get<std::uint64_t>() >= static_cast<std::uint64_t>(lo))
            : v->get<std::int64_t>() >= lo && v->get<std::int64_t>() <= hi;
    if (!in_range) {
      throw std::invalid_argument(
          fmt::format("{}: {} out of range [{}, {}]", field(name), v->dump(), lo, hi));
    }
    *out = v->get<long long>();
  };
  CaseSpec spec;
  get_string("problem", &spec.problem);
  get_string("solver", &spec.solver);
  get_string("transcription", &spec.transcription);
  get_string("algorithm", &spec.algorithm);
  long long n = 0, degree = 3, repeats = 1;
  if (const json* seed = j.Find("seed")) spec.seed = SeedFromJson(*seed, field("seed"));
  get_int("N", 1, std::numeric_limits<int>::max(), &n);  // the memory check is ValidateCase's
  get_int("degree", 1, 1000, &degree);                   // the transcription's rule follows
  get_int("repeats", 1, 1000, &repeats);
  spec.intervals = static_cast<int>(n);
  spec.degree = static_cast<int>(degree);
  spec.degree_given = j.Find("degree") != nullptr;
  spec.repeats = static_cast<int>(repeats);
  std::string s;
  if (j.Find("terminal") != nullptr) {
    get_string("terminal", &s);
    try {
      spec.terminal = ParseTerminal(s);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(where + "." + e.what());
    }
  }
  for (const char* name : {"integrator", "evaluate_with"}) {
    if (j.Find(name) == nullptr) continue;
    s.clear();
    get_string(name, &s);
    try {
      (std::string(name) == "integrator" ? spec.integrator : spec.evaluate_with) =
          ParseIntegrator(s);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(field(name) + ": " + e.what());
    }
  }
  if (const json* keep = j.Find("keep_trajectory")) {
    if (!keep->is_boolean()) {
      throw std::invalid_argument(field("keep_trajectory") + ": must be true or false");
    }
    spec.keep_trajectory = keep->get<bool>();
  }
  if (const json* set = j.Find("set")) {
    if (!set->is_object()) {
      throw std::invalid_argument(field("set") +
                                  ": must be an object {\"key\": value or [values]}");
    }
    for (const auto& [k, v] : set->items()) {
      const std::string where_k = field("set") + "." + k;
      std::vector<double> values;
      auto push = [&](const json& x) {
        if (!x.is_number())
          throw std::invalid_argument(where_k + ": must be a number or a list of numbers");
        const double d = x.get<double>();
        if (!std::isfinite(d)) throw std::invalid_argument(where_k + ": must be finite");
        values.push_back(d);
      };
      if (v.is_array()) {
        if (v.empty()) throw std::invalid_argument(where_k + ": empty list");
        for (const json& x : v) push(x);
      } else {
        push(v);
      }
      spec.set.push_back(k + "=" + OptionValue(values).ToText());
    }
  }
  get_string("kind", &spec.kind);
  get_string("continuation", &spec.continuation);
  if (spec.continuation == "none") spec.continuation.clear();
  auto get_map = [&](const char* name, OptionMap* out) {
    const json* opts = j.Find(name);
    if (opts == nullptr) return;
    if (!opts->is_object()) throw std::invalid_argument(field(name) + ": must be an object");
    for (const auto& [k, v] : opts->items()) {
      out->Set(k, OptionValueFromJson(v, field(name) + "." + k));
    }
  };
  get_map("options", &spec.options);
  get_map("online", &spec.online);
  get_map("replan_options", &spec.replan_options);
  if (spec.problem.empty()) throw std::invalid_argument(field("problem") + ": required");
  if (spec.solver.empty()) throw std::invalid_argument(field("solver") + ": required");
  try {
    spec.Validate();
    return ResolveCase(spec);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(where + ": " + e.what());
  }
}

}  // namespace ocpb
