// Shards of a suite: shard i of n (1-based, 1 <= i <= n, as Slurm's --array=1-n and GNU
// parallel's `::: $(seq n)` number them) runs the suite's cases i, i + n, i + 2n, ... (1-based
// case numbers, round robin, so every shard gets its share of each group).
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace ocpb {

/// The most shards a suite is split into (`--shard i/n`, shards.json, records file names), so
/// that status and merge, which keep a line per shard, stay small whatever a file name claims.
/// Lower than kMaxSuiteCases: a suite of more than 100000 cases is split into shards of several
/// cases each (a shard per case of such a suite would be a scheduler's burden anyway).
inline constexpr int kMaxShards = 100000;

struct Shard {
  int index = 1;  ///< 1 <= index <= count
  int count = 1;

  /// Whether the suite's case at 0-based position `case_position` belongs to this shard.
  bool Owns(size_t case_position) const {
    return static_cast<int>(case_position % static_cast<size_t>(count)) == index - 1;
  }
  /// The number of the suite's `cases` this shard owns.
  size_t CaseCount(size_t cases) const;
  /// "records.shard-I-of-N.jsonl": the shard's records file in the output folder.
  std::string RecordsFileName() const;
  /// "I/N".
  std::string Text() const;
};

/// Parses `--shard i/n`. Throws std::invalid_argument naming the flag and the rule: a
/// malformed value, n < 1 or above kMaxShards, and i outside 1..n; "0/n" is refused with a hint
/// that shards are numbered from 1 (the 0-based numbering of earlier versions).
Shard ParseShard(const std::string& text);

/// The shard of a records file name "records.shard-I-of-N.jsonl"; nullopt for any other name.
/// Throws std::invalid_argument for a shard file whose numbers break the 1-based rule (a folder
/// written by an earlier, 0-based version: "records.shard-0-of-N.jsonl").
std::optional<Shard> ShardOfRecordsFileName(const std::string& file_name);

}  // namespace ocpb
