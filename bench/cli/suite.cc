#include "bench/cli/suite.h"

#include <cctype>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "core/memory_budget.h"

namespace ocpb {

using nlohmann::json;

namespace {

// The errors of one suite document: "SOURCE:LINE: rule", with the line where the value the
// rule is about starts (when the document's text is known: LoadSuite).
class SuiteErrors {
 public:
  SuiteErrors(const std::string& source, const JsonLines* lines) : source_(source), lines_(lines) {}

  [[noreturn]] void Fail(const json& at, const std::string& rule) const {
    const int line = lines_ != nullptr ? lines_->LineOf(at) : 0;
    throw std::invalid_argument(source_ + (line > 0 ? ":" + std::to_string(line) : "") + ": " +
                                rule);
  }

  // A case's error ("groups[0].methods[1].FIELD...: rule", "groups[0].methods[1]: FIELD:
  // rule" or "groups[0].methods[1]: rule"), placed at the field's value when the message names
  // one the case gives, else at `method`.
  [[noreturn]] void FailInCase(const std::string& message,
                               const std::string& where,
                               const CaseFields& fields,
                               const json& method) const {
    const json* at = &method;
    for (const std::string& lead : {where + ".", where + ": "}) {
      if (message.rfind(lead, 0) != 0) continue;
      const std::string rest = message.substr(lead.size());
      const json* field = fields.Find(rest.substr(0, rest.find_first_of(".[: ")));
      if (field != nullptr) at = field;
    }
    Fail(*at, message);
  }

 private:
  const std::string& source_;
  const JsonLines* lines_;
};

}  // namespace

Suite ParseSuite(const json& j, const std::string& source, const JsonLines* lines) {
  const SuiteErrors errors(source, lines);
  if (!j.is_object()) errors.Fail(j, "a suite must be a JSON object");
  static const std::set<std::string> kTop = {"name", "description", "groups"};
  for (const auto& [k, v] : j.items()) {
    if (!kTop.count(k))
      errors.Fail(v, "unknown key '" + k + "' (valid: description, groups, name)");
  }
  Suite suite;
  suite.document = j;
  if (!j.contains("name") || !j["name"].is_string() || j["name"].get<std::string>().empty()) {
    errors.Fail(j.contains("name") ? j["name"] : j, "name: required non-empty string");
  }
  suite.name = j["name"].get<std::string>();
  for (char c : suite.name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) {
      errors.Fail(j["name"], "name: only letters, digits, '-' and '_' allowed");
    }
  }
  if (j.contains("description")) {
    if (!j["description"].is_string())
      errors.Fail(j["description"], "description: must be a string");
    suite.description = j["description"].get<std::string>();
  }
  if (!j.contains("groups") || !j["groups"].is_array() || j["groups"].empty()) {
    errors.Fail(j.contains("groups") ? j["groups"] : j, "groups: required non-empty list");
  }
  const json& groups = j["groups"];
  // The number of cases, counted before any is built: a few short lists can ask for billions.
  double total = 0.0;
  for (const json& group : groups) {
    if (!group.is_object()) continue;  // refused below, with its place
    auto count = [&](const char* name) {
      const auto it = group.find(name);
      return it == group.end() || !it->is_array() ? 1.0 : static_cast<double>(it->size());
    };
    total += count("seeds") * count("N") * count("methods");
  }
  if (total > static_cast<double>(kMaxSuiteCases)) {
    errors.Fail(groups,
                fmt::format("groups: {:.0f} cases (seeds x N x methods over the groups); a suite "
                            "may hold at most {} (split it into several suite files)",
                            total,
                            kMaxSuiteCases));
  }
  std::set<std::string> keys;
  double record_bytes = 0.0;
  for (size_t g = 0; g < groups.size(); ++g) {
    const json& group = groups[g];
    const std::string where = "groups[" + std::to_string(g) + "]";
    if (!group.is_object()) errors.Fail(group, where + ": must be an object");
    if (!group.contains("methods") || !group["methods"].is_array() || group["methods"].empty()) {
      errors.Fail(group.contains("methods") ? group["methods"] : group,
                  where + ".methods: required non-empty list");
    }
    // The cases take their seed and N from these lists (pointers into the document: nothing is
    // copied out of it); nullptr: the case's own field, or the default.
    std::vector<const json*> seeds = {nullptr}, grids = {nullptr};
    auto list_of = [&](const char* name, std::vector<const json*>* out) {
      if (!group.contains(name)) return;
      const json& v = group[name];
      const std::string field = where + "." + name;
      if (v.is_null())
        errors.Fail(v, field + ": null is not a value (omit the key for the default)");
      if (!v.is_array()) {
        out->assign(1, &v);
        return;
      }
      if (v.empty()) errors.Fail(v, field + ": empty list");
      out->clear();
      for (size_t i = 0; i < v.size(); ++i) {
        if (v[i].is_null()) errors.Fail(v[i], fmt::format("{}[{}]: null is not a value", field, i));
        out->push_back(&v[i]);
      }
    };
    list_of("seeds", &seeds);
    list_of("N", &grids);
    for (size_t m = 0; m < group["methods"].size(); ++m) {
      const json& method = group["methods"][m];
      const std::string where_m = where + ".methods[" + std::to_string(m) + "]";
      if (!method.is_object()) errors.Fail(method, where_m + ": must be an object");
      for (const json* seed : seeds) {
        for (const json* n : grids) {
          const CaseFields fields(method, group, seed, n);
          CaseSpec spec;
          try {
            spec = ParseCaseSpec(fields, where_m);
          } catch (const std::invalid_argument& e) {
            errors.FailInCase(e.what(), where_m, fields, method);
          }
          // Everything that can be checked without solving is checked now (names, parameters,
          // the problem's own rules, solver options, memory), so a typo fails the whole suite
          // before anything runs.
          try {
            record_bytes += ValidateCase(spec).record_bytes;
          } catch (const std::invalid_argument& e) {
            errors.FailInCase(where_m + ": " + e.what(), where_m, fields, method);
          }
          if (!keys.insert(spec.Key()).second) {
            errors.Fail(method, where + ": duplicate case " + spec.Key());
          }
          suite.cases.push_back(std::move(spec));
        }
      }
    }
  }
  // `ocpbench run` keeps every record of the suite for its summary.
  try {
    CheckMemoryEstimate(record_bytes,
                        "groups",
                        std::to_string(suite.cases.size()) +
                            " records held for the summary (their fields and iteration histories)");
  } catch (const std::invalid_argument& e) {
    errors.Fail(groups, e.what());
  }
  return suite;
}

Suite LoadSuite(const std::string& path) {
  const JsonInputFile in(path, kMaxSuiteFileBytes, "suite file", OneLine(path));
  const JsonLines& lines = in.lines();
  return ParseSuite(in.document(), in.source(), &lines);
}

}  // namespace ocpb
