#include "bench/cli/shard.h"

#include <stdexcept>

#include <fmt/format.h>

namespace ocpb {
namespace {

// A decimal number of at most 9 digits (no sign, no spaces); nullopt otherwise.
std::optional<int> ParseCount(const std::string& text) {
  if (text.empty() || text.size() > 9) return std::nullopt;
  int value = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return std::nullopt;
    value = value * 10 + (c - '0');
  }
  return value;
}

}  // namespace

size_t Shard::CaseCount(size_t cases) const {
  const size_t n = static_cast<size_t>(count), i = static_cast<size_t>(index);
  return cases / n + (cases % n >= i ? 1 : 0);
}

std::string Shard::RecordsFileName() const {
  return fmt::format("records.shard-{}-of-{}.jsonl", index, count);
}

std::string Shard::Text() const { return fmt::format("{}/{}", index, count); }

Shard ParseShard(const std::string& text) {
  const auto slash = text.find('/');
  std::optional<int> i, n;
  if (slash != std::string::npos) {
    i = ParseCount(text.substr(0, slash));
    n = ParseCount(text.substr(slash + 1));
  }
  if (!i || !n || *n < 1) {
    throw std::invalid_argument("--shard '" + text +
                                "': expected i/n with 1 <= i <= n (shard i of n, numbered from 1)");
  }
  if (*n > kMaxShards) {
    throw std::invalid_argument(fmt::format(
        "--shard '{}': at most {} shards (n); a suite split further has only empty shards",
        text,
        kMaxShards));
  }
  if (*i == 0) {
    throw std::invalid_argument(fmt::format(
        "--shard '{0}': shards are numbered from 1, 1 <= i <= n (as Slurm's --array=1-{1} and "
        "`parallel ... ::: $(seq {1})` number them); 0 was the first shard of earlier, 0-based "
        "versions: use 1/{1} ... {1}/{1}",
        text,
        *n));
  }
  if (*i > *n) {
    throw std::invalid_argument(
        fmt::format("--shard '{}': expected i/n with 1 <= i <= n (shard {} of {} does not exist)",
                    text,
                    *i,
                    *n));
  }
  return Shard{*i, *n};
}

std::optional<Shard> ShardOfRecordsFileName(const std::string& file_name) {
  static const std::string kPrefix = "records.shard-", kSuffix = ".jsonl";
  if (file_name.size() <= kPrefix.size() + kSuffix.size() || file_name.rfind(kPrefix, 0) != 0 ||
      file_name.compare(file_name.size() - kSuffix.size(), kSuffix.size(), kSuffix) != 0) {
    return std::nullopt;
  }
  const std::string middle =
      file_name.substr(kPrefix.size(), file_name.size() - kPrefix.size() - kSuffix.size());
  const auto of = middle.find("-of-");
  if (of == std::string::npos) return std::nullopt;
  const std::optional<int> i = ParseCount(middle.substr(0, of));
  const std::optional<int> n = ParseCount(middle.substr(of + 4));
  if (!i || !n) return std::nullopt;
  if (*n > kMaxShards) {
    throw std::invalid_argument(fmt::format(
        "{}: a sweep of {} shards; OCPBench writes at most {} (remove or rename the file)",
        file_name,
        *n,
        kMaxShards));
  }
  if (*n < 1 || *i < 1 || *i > *n) {
    throw std::invalid_argument(
        fmt::format("{}: not a shard of the 1-based numbering (1 <= i <= n); a folder written by "
                    "an earlier version numbered shards from 0: rename its files to "
                    "records.shard-(i+1)-of-{}.jsonl, or run the suite again",
                    file_name,
                    *n));
  }
  return Shard{*i, *n};
}

}  // namespace ocpb
