// The sharded sweep an output folder holds (shards.json): written by the first `ocpbench run
// --shard` into the folder, checked by every later one, read by `merge` and `status` so that
// they know the suite's cases and the shard count without being told.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "bench/cli/suite.h"

namespace ocpb {

struct ShardManifest {
  int shards = 0;            ///< n of every shard i/n run into the folder
  size_t cases = 0;          ///< the suite's case count
  std::string suite_name;    ///< Suite::name
  std::string suite_source;  ///< the suite file as given to the first run (information only)
  nlohmann::json suite;      ///< the suite document (Suite::document)
};

/// DIR/shards.json.
std::string ShardManifestPath(const std::string& dir);

/// Reads DIR/shards.json; nullopt when there is none. Throws std::invalid_argument naming the
/// file and the field when it is not a manifest.
std::optional<ShardManifest> ReadShardManifest(const std::string& dir);

/// Checks that a shard of `count` shards of `suite` may run into `dir`: throws
/// std::invalid_argument when the folder's manifest names another suite document or another
/// shard count (its other shards' records would not merge with this one's). Writes nothing.
void CheckShardManifest(const std::string& dir, const Suite& suite, int count);

/// Writes DIR/shards.json (atomically) when it does not exist yet. Concurrent first shards write
/// the same content, so whichever rename lands last is right.
void WriteShardManifestIfAbsent(const std::string& dir,
                                const Suite& suite,
                                const std::string& suite_source,
                                int count);

}  // namespace ocpb
