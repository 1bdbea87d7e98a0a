#include "bench/cli/shard_coverage.h"

#include <set>
#include <unordered_map>

#include <fmt/format.h>

#include "bench/cli/shard.h"

namespace ocpb {

std::string ShardCoverage::IncompleteShardList() const {
  std::vector<int> incomplete;
  for (const ShardProgress& p : progress) {
    if (p.recorded < p.expected) incomplete.push_back(p.index);
  }
  std::string out;
  for (size_t a = 0; a < incomplete.size();) {
    size_t b = a;
    while (b + 1 < incomplete.size() && incomplete[b + 1] == incomplete[b] + 1) ++b;
    // Appended piecewise: GCC 12 -O2 reports a false -Wrestrict on `"," + text`.
    if (!out.empty()) out += ',';
    out += std::to_string(incomplete[a]);
    if (b > a) {
      out += '-';
      out += std::to_string(incomplete[b]);
    }
    a = b + 1;
  }
  return out;
}

ShardCoverage ComputeShardCoverage(const std::vector<std::string>& suite_keys,
                                   int shards,
                                   const std::map<int, std::vector<std::string>>& keys_by_shard) {
  ShardCoverage c;
  c.shards = shards;
  c.expected = suite_keys.size();
  std::unordered_map<std::string, size_t> position;
  for (size_t i = 0; i < suite_keys.size(); ++i) position.emplace(suite_keys[i], i);
  std::vector<int> count(suite_keys.size(), 0);
  std::set<std::string> foreign_seen;
  for (const auto& [shard, keys] : keys_by_shard) {
    for (const std::string& key : keys) {
      const auto it = position.find(key);
      if (it == position.end()) {
        if (foreign_seen.insert(key).second) c.foreign.push_back(key);
        continue;
      }
      ++count[it->second];
    }
  }
  for (int s = 1; s <= shards; ++s) {
    ShardProgress p;
    p.index = s;
    p.file_present = keys_by_shard.count(s) > 0;
    c.progress.push_back(p);
  }
  for (size_t i = 0; i < suite_keys.size(); ++i) {
    ShardProgress& p = c.progress[i % static_cast<size_t>(shards)];
    ++p.expected;
    if (count[i] > 0) {
      ++p.recorded;
      ++c.recorded;
    } else {
      c.missing.push_back(suite_keys[i]);
    }
    if (count[i] > 1) c.duplicated.push_back(suite_keys[i]);
  }
  return c;
}

std::vector<std::string> DescribeShardCoverage(const ShardCoverage& c, size_t max_keys) {
  std::vector<std::string> lines;
  lines.push_back(fmt::format("{} of {} cases recorded in {} shards{}",
                              c.recorded,
                              c.expected,
                              c.shards,
                              c.Complete() ? "" : ": incomplete"));
  for (const ShardProgress& p : c.progress) {
    if (p.recorded == p.expected) continue;
    const std::string file = Shard{p.index, c.shards}.RecordsFileName();
    lines.push_back(p.file_present ? fmt::format("shard {} of {}: {} of {} cases recorded ({})",
                                                 p.index,
                                                 c.shards,
                                                 p.recorded,
                                                 p.expected,
                                                 file)
                                   : fmt::format("shard {} of {}: missing (no {}; {} cases)",
                                                 p.index,
                                                 c.shards,
                                                 file,
                                                 p.expected));
  }
  auto list = [&](const std::vector<std::string>& keys, const char* what) {
    for (size_t i = 0; i < keys.size() && i < max_keys; ++i) {
      lines.push_back(fmt::format("{}: {}", what, keys[i]));
    }
    if (keys.size() > max_keys) {
      lines.push_back(fmt::format("{}: ... and {} more", what, keys.size() - max_keys));
    }
  };
  list(c.missing, "missing case");
  list(c.duplicated, "duplicated case");
  list(c.foreign, "not a case of the suite");
  if (!c.missing.empty()) {
    lines.push_back("shards to run again: " + c.IncompleteShardList());
  }
  return lines;
}

}  // namespace ocpb
