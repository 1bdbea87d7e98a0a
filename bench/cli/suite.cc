#include "bench/cli/suite.h"

#include <cctype>
#include <set>
#include <stdexcept>

#include "bench/cli/io.h"

namespace ocpb {

using nlohmann::json;

Suite ParseSuite(const json& j, const std::string& source) {
  if (!j.is_object()) throw std::invalid_argument(source + ": a suite must be a JSON object");
  static const std::set<std::string> kTop = {"name", "description", "groups"};
  for (const auto& [k, v] : j.items()) {
    if (!kTop.count(k)) {
      throw std::invalid_argument(source + ": unknown key '" + k +
                                  "' (valid: description, groups, name)");
    }
  }
  Suite suite;
  suite.document = j;
  if (!j.contains("name") || !j["name"].is_string() || j["name"].get<std::string>().empty()) {
    throw std::invalid_argument(source + ": name: required non-empty string");
  }
  suite.name = j["name"].get<std::string>();
  for (char c : suite.name) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_')) {
      throw std::invalid_argument(source + ": name: only letters, digits, '-' and '_' allowed");
    }
  }
  if (j.contains("description")) {
    if (!j["description"].is_string())
      throw std::invalid_argument(source + ": description: must be a string");
    suite.description = j["description"].get<std::string>();
  }
  if (!j.contains("groups") || !j["groups"].is_array() || j["groups"].empty()) {
    throw std::invalid_argument(source + ": groups: required non-empty list");
  }
  std::set<std::string> keys;
  for (size_t g = 0; g < j["groups"].size(); ++g) {
    const json& group = j["groups"][g];
    const std::string where = source + ": groups[" + std::to_string(g) + "]";
    if (!group.is_object()) throw std::invalid_argument(where + ": must be an object");
    if (!group.contains("methods") || !group["methods"].is_array() || group["methods"].empty()) {
      throw std::invalid_argument(where + ".methods: required non-empty list");
    }
    std::vector<json> seeds = {json(nullptr)}, grids = {json(nullptr)};
    auto list_of = [&](const char* name, std::vector<json>* out) {
      if (!group.contains(name)) return;
      const json& v = group[name];
      if (v.is_array()) {
        if (v.empty()) throw std::invalid_argument(where + "." + name + ": empty list");
        out->assign(v.begin(), v.end());
      } else {
        out->assign(1, v);
      }
    };
    list_of("seeds", &seeds);
    list_of("N", &grids);
    json base = group;
    base.erase("methods");
    base.erase("seeds");
    base.erase("N");
    for (size_t m = 0; m < group["methods"].size(); ++m) {
      const json& method = group["methods"][m];
      if (!method.is_object()) {
        throw std::invalid_argument(where + ".methods[" + std::to_string(m) +
                                    "]: must be an object");
      }
      for (const json& seed : seeds) {
        for (const json& n : grids) {
          json c = base;
          for (const auto& [k, v] : method.items()) c[k] = v;
          if (!seed.is_null()) c["seed"] = seed;
          if (!n.is_null()) c["N"] = n;
          CaseSpec spec = ParseCaseSpec(c, where + ".methods[" + std::to_string(m) + "]");
          // Everything that can be checked without solving is checked now (names, parameters,
          // the problem's own rules, solver options, memory), so a typo fails the whole suite
          // before anything runs.
          try {
            ValidateCase(spec);
          } catch (const std::invalid_argument& e) {
            throw std::invalid_argument(where + ".methods[" + std::to_string(m) + "]: " + e.what());
          }
          if (!keys.insert(spec.Key()).second) {
            throw std::invalid_argument(where + ": duplicate case " + spec.Key());
          }
          suite.cases.push_back(std::move(spec));
        }
      }
    }
  }
  return suite;
}

Suite LoadSuite(const std::string& path) {
  const std::string text = ReadFile(path);
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {
    // parse_error, and out_of_range for a number beyond double (1e999): both are the file's.
    throw std::invalid_argument(path + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  return ParseSuite(j, path);
}

}  // namespace ocpb
