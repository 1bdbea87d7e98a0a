#include "bench/cli/shard_manifest.h"

#include <filesystem>
#include <stdexcept>

#include <fmt/format.h>

#include "bench/cli/io.h"
#include "bench/cli/json_input.h"
#include "bench/cli/shard.h"

namespace ocpb {

using nlohmann::json;

std::string ShardManifestPath(const std::string& dir) { return dir + "/shards.json"; }

std::optional<ShardManifest> ReadShardManifest(const std::string& dir) {
  const std::string path = ShardManifestPath(dir);
  if (!std::filesystem::exists(path)) return std::nullopt;
  // Size and nesting limits, errors "PATH:LINE: ..." (bench/cli/json_input.h); the manifest
  // holds the suite document.
  const json j = LoadJsonFile(path, 2 * kMaxSuiteFileBytes, "shard manifest");
  auto field = [&](const char* name, bool (json::*is)() const noexcept) -> const json& {
    if (!j.is_object() || !j.contains(name) || !(j[name].*is)()) {
      throw std::invalid_argument(fmt::format("{}: {}: missing or of the wrong type", path, name));
    }
    return j[name];
  };
  ShardManifest m;
  const json& shards = field("shards", &json::is_number_integer);
  if (!shards.is_number_unsigned() || shards.get<unsigned long long>() < 1 ||
      shards.get<unsigned long long>() > static_cast<unsigned long long>(kMaxShards)) {
    throw std::invalid_argument(
        fmt::format("{}: shards: must be an integer from 1 to {}", path, kMaxShards));
  }
  m.shards = shards.get<int>();
  m.cases = field("cases", &json::is_number_unsigned).get<size_t>();
  m.suite_name = field("suite_name", &json::is_string).get<std::string>();
  m.suite_source = field("suite_source", &json::is_string).get<std::string>();
  m.suite = field("suite", &json::is_object);
  return m;
}

void CheckShardManifest(const std::string& dir, const Suite& suite, int count) {
  const std::optional<ShardManifest> m = ReadShardManifest(dir);
  if (!m) return;
  if (m->suite != suite.document) {
    throw std::invalid_argument(
        fmt::format("{}: the folder holds shards of another suite document ('{}' from {}, {} "
                    "cases): its records would not merge with these; use another --out (or "
                    "remove the folder)",
                    ShardManifestPath(dir),
                    m->suite_name,
                    m->suite_source,
                    m->cases));
  }
  if (m->shards != count) {
    throw std::invalid_argument(fmt::format(
        "{}: the folder holds a sweep of {} shards, not {}: run --shard i/{} (or use another "
        "--out)",
        ShardManifestPath(dir),
        m->shards,
        count,
        m->shards));
  }
}

void WriteShardManifestIfAbsent(const std::string& dir,
                                const Suite& suite,
                                const std::string& suite_source,
                                int count) {
  if (std::filesystem::exists(ShardManifestPath(dir))) return;
  const json j{{"shards", count},
               {"cases", suite.cases.size()},
               {"suite_name", suite.name},
               {"suite_source", suite_source},
               {"suite", suite.document}};
  WriteFileAtomically(ShardManifestPath(dir), j.dump(1) + "\n");
}

}  // namespace ocpb
