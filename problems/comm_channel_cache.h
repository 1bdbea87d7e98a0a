// Channels of the comm problems, built once per process for every case that shares one.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <mutex>
#include <string>

#include "problems/channel/channel_quality.h"

namespace ocpb {

/// A bounded least-recently-used store of built channels (ChannelQuality), by a key that names
/// everything that defines the channel.
///
/// Why: building the paper's channel (simulate, measure, estimate, predict on the grid, spline)
/// is about half of the instructions of a comm-path2d solve, and a suite solves the same seed
/// and channel parameters with every method and weight: `ocpbench run bench/suites/paper.json`
/// builds 5 distinct channels for its 96 cases. The registry's `make` of comm-path2d and
/// comm-fixed-path asks this cache (MakeCommChannel), so every caller of the registry benefits
/// without knowing the problems.
///
/// Sharing is safe because a ChannelQuality is immutable after construction (const Evaluate, no
/// mutable state) and MakePaperChannel is deterministic (the grid prediction does not depend on
/// the thread count): a hit returns the very object a rebuild would reproduce bit for bit
/// (tests/problems/comm_channel_cache_test.cc, tests/cli/channel_cache_records_test.cc).
///
/// Bounds: at most `capacity_bytes` of estimated channel memory (the caller's estimate of the
/// object's size) and `max_entries` channels; the least recently used go first. A channel
/// larger than the capacity is built and returned but not kept. Capacity 0 disables the cache.
/// Thread-safe; two threads missing the same key at once both build it and one copy is kept.
class ChannelCache {
 public:
  struct Stats {
    long hits = 0;
    long misses = 0;
    long evictions = 0;
    std::size_t entries = 0;
    std::size_t bytes = 0;  ///< estimated bytes held
  };

  /// Default bound: 256 MB (the paper's 0.1 m map is about 2 MB, its exact predictor 2-4 MB).
  static constexpr std::size_t kDefaultCapacityBytes = std::size_t{256} << 20;
  static constexpr std::size_t kDefaultMaxEntries = 64;

  /// The process-wide cache the comm problems use.
  static ChannelCache& Global();

  /// The channel stored under `key`, or build() (outside the lock) stored under it when its
  /// estimated size `bytes` fits. Exceptions from build() propagate and nothing is stored.
  std::shared_ptr<const ChannelQuality> GetOrBuild(
      const std::string& key,
      std::size_t bytes,
      const std::function<std::shared_ptr<const ChannelQuality>()>& build);

  /// New bounds (evicting as needed); capacity_bytes = 0 disables and empties the cache.
  void SetCapacity(std::size_t capacity_bytes, std::size_t max_entries = kDefaultMaxEntries);
  std::size_t capacity_bytes() const;
  /// Drops every channel and zeroes the statistics.
  void Clear();
  Stats stats() const;

 private:
  struct Entry {
    std::string key;
    std::size_t bytes;
    std::shared_ptr<const ChannelQuality> channel;
  };
  void EvictLocked();

  mutable std::mutex mutex_;
  std::list<Entry> entries_;  // most recently used first; a suite holds a handful
  std::size_t capacity_bytes_ = kDefaultCapacityBytes;
  std::size_t max_entries_ = kDefaultMaxEntries;
  Stats stats_;
};

}  // namespace ocpb
