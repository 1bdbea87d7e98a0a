// Seeded pseudo-random numbers that are identical on every platform.
#pragma once

#include <cstdint>
#include <random>

namespace ocpb {

/// A std::mt19937_64 seeded explicitly from (seed, stream), so that independent ingredients of
/// one realization (shadowing, multipath, measurement positions) use independent streams of one
/// user seed: the engine's seed is SplitMix64(SplitMix64(seed) ^ stream).
///
/// Uniform, normal and bounded-integer draws are implemented here rather than with the std
/// distributions, whose algorithms are implementation-defined: with these, a (seed, stream)
/// pair gives the same numbers with any standard library (the engine itself is fully specified
/// by the standard). Normals come from the Box-Muller transform, two per pair of uniforms.
class RandomStream {
 public:
  /// Stream tags used by the channel simulator and the measurement sampler.
  enum Stream : std::uint64_t {
    kShadowing = 1,
    kMultipath = 2,
    kMeasurementPositions = 3,
  };

  RandomStream(std::uint64_t seed, std::uint64_t stream);

  /// Uniform in (0, 1]: 53 random bits, never 0.
  double Uniform();
  /// Standard normal.
  double Normal();
  /// Uniform integer in [0, n), n >= 1, without modulo bias (rejection).
  std::uint64_t Index(std::uint64_t n);

  static std::uint64_t SplitMix64(std::uint64_t x);

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace ocpb
