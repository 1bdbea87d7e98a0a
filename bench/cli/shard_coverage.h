// Which of a suite's cases the records of a sharded run hold: per shard, the cases missing and
// duplicated by key. `merge` refuses to call an incomplete sweep complete; `status` reports
// progress while the shards run.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace ocpb {

struct ShardProgress {
  int index = 0;  ///< 1-based shard number
  bool file_present = false;
  size_t expected = 0;  ///< cases of the suite the shard owns
  size_t recorded = 0;  ///< of them, how many have a record (in any shard file)
};

struct ShardCoverage {
  int shards = 0;
  size_t expected = 0;                  ///< the suite's cases
  size_t recorded = 0;                  ///< the suite's cases with at least one record
  std::vector<ShardProgress> progress;  ///< shard 1 .. n
  std::vector<std::string> missing;     ///< cases without a record, in suite order
  /// Cases with more than one record (each key once, in suite order).
  std::vector<std::string> duplicated;
  /// Record keys that are no case of the suite (each once, in file order).
  std::vector<std::string> foreign;

  bool Complete() const { return missing.empty() && duplicated.empty() && foreign.empty(); }
  /// The shards that own a missing case, as a Slurm --array list ("2,5-7"); empty when none.
  std::string IncompleteShardList() const;
};

/// The coverage of `suite_keys` (the suite's case keys, in suite order) in `shards` shards by
/// the record keys found in each shard's records file (`keys_by_shard`: shard number -> keys in
/// file order; a shard without a file is absent).
ShardCoverage ComputeShardCoverage(const std::vector<std::string>& suite_keys,
                                   int shards,
                                   const std::map<int, std::vector<std::string>>& keys_by_shard);

/// Human-readable lines: the totals, every incomplete shard, and up to `max_keys` keys of each
/// kind (missing, duplicated, not in the suite) with the count of the rest.
std::vector<std::string> DescribeShardCoverage(const ShardCoverage& coverage, size_t max_keys);

}  // namespace ocpb
