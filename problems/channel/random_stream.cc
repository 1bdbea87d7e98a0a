#include "problems/channel/random_stream.h"

#include <cmath>
#include <numbers>

namespace ocpb {

std::uint64_t RandomStream::SplitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

RandomStream::RandomStream(std::uint64_t seed, std::uint64_t stream)
    : engine_(SplitMix64(SplitMix64(seed) ^ stream)) {}

double RandomStream::Uniform() {
  // (k + 1) / 2^53 for k uniform in [0, 2^53): in (0, 1].
  return static_cast<double>((engine_() >> 11) + 1) * 0x1.0p-53;
}

double RandomStream::Normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double r = std::sqrt(-2.0 * std::log(Uniform()));
  const double t = 2.0 * std::numbers::pi * Uniform();
  spare_ = r * std::sin(t);
  has_spare_ = true;
  return r * std::cos(t);
}

std::uint64_t RandomStream::Index(std::uint64_t n) {
  // Accept x below the largest multiple of n that fits in 2^64.
  const std::uint64_t limit = (~std::uint64_t{0}) - ((~std::uint64_t{0}) % n + 1) % n;
  for (;;) {
    const std::uint64_t x = engine_();
    if (x <= limit) return x % n;
  }
}

}  // namespace ocpb
