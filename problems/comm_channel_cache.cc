#include "problems/comm_channel_cache.h"

namespace ocpb {

ChannelCache& ChannelCache::Global() {
  static ChannelCache cache;
  return cache;
}

std::shared_ptr<const ChannelQuality> ChannelCache::GetOrBuild(
    const std::string& key,
    std::size_t bytes,
    const std::function<std::shared_ptr<const ChannelQuality>()>& build) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      if (it->key != key) continue;
      entries_.splice(entries_.begin(), entries_, it);
      ++stats_.hits;
      return entries_.front().channel;
    }
    ++stats_.misses;
  }
  // Built without the lock: a channel takes a fraction of a second to a few seconds.
  std::shared_ptr<const ChannelQuality> channel = build();
  const std::lock_guard<std::mutex> lock(mutex_);
  if (bytes > capacity_bytes_ || max_entries_ == 0) return channel;
  for (const Entry& e : entries_) {
    if (e.key == key) return channel;  // another thread stored it meanwhile
  }
  entries_.push_front(Entry{key, bytes, channel});
  stats_.bytes += bytes;
  EvictLocked();
  return channel;
}

void ChannelCache::EvictLocked() {
  while (!entries_.empty() && (stats_.bytes > capacity_bytes_ || entries_.size() > max_entries_)) {
    stats_.bytes -= entries_.back().bytes;
    entries_.pop_back();
    ++stats_.evictions;
  }
  stats_.entries = entries_.size();
}

void ChannelCache::SetCapacity(std::size_t capacity_bytes, std::size_t max_entries) {
  const std::lock_guard<std::mutex> lock(mutex_);
  capacity_bytes_ = capacity_bytes;
  max_entries_ = capacity_bytes == 0 ? 0 : max_entries;
  EvictLocked();
}

std::size_t ChannelCache::capacity_bytes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return capacity_bytes_;
}

void ChannelCache::Clear() {
  const std::lock_guard<std::mutex> lock(mutex_);
  entries_.clear();
  stats_ = Stats();
}

ChannelCache::Stats ChannelCache::stats() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

}  // namespace ocpb
