// The channel cache changes no record: a suite's cases run with the cache (the second case of a
// seed reuses the first's channel) and without it (every case builds its own) give records
// equal in every deterministic field.
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "bench/cli/case_runner.h"
#include "problems/comm_channel_cache.h"

namespace ocpb {
namespace {

using nlohmann::json;

// Drops the measured times (keys ending in "seconds" or "seconds_repeats"), at any depth.
json Deterministic(const json& j) {
  if (j.is_array()) {
    json out = json::array();
    for (const json& e : j) out.push_back(Deterministic(e));
    return out;
  }
  if (!j.is_object()) return j;
  json out = json::object();
  for (const auto& [key, v] : j.items()) {
    const std::string& k = key;  // clang 14 cannot capture a structured binding
    const auto ends = [&k](const std::string& tail) {
      return k.size() >= tail.size() && k.compare(k.size() - tail.size(), tail.size(), tail) == 0;
    };
    if (ends("seconds") || ends("seconds_repeats")) continue;
    out[k] = Deterministic(v);
  }
  return out;
}

std::vector<CaseSpec> SmallSuite() {
  std::vector<CaseSpec> cases;
  for (std::uint64_t seed : {1, 2}) {
    for (const char* gamma : {"gamma=0.01", "gamma=1e-4"}) {
      for (const char* solver : {"hamiltonian", "ipopt"}) {
        CaseSpec spec;
        spec.problem = "comm-path2d";
        spec.set = {"workspace=10",
                    "grid_step=0.2",
                    "base=5,5",
                    "S=8,8",
                    "D=2,3",
                    "c=10",
                    "tf=10",
                    "samples=100",
                    "min_pairs=10",
                    "bin_width=0.5",
                    gamma};
        spec.seed = seed;
        spec.solver = solver;
        if (std::string(solver) == "ipopt") spec.transcription = "euler";
        if (std::string(solver) == "hamiltonian") spec.options = {{"max_iterations", "40"}};
        spec.intervals = 40;
        spec.keep_trajectory = true;  // also compares the trajectory and the s map samples
        cases.push_back(spec);
      }
    }
  }
  return cases;
}

TEST(ChannelCache, RecordsAreTheSameWithAndWithoutIt) {
  ChannelCache& cache = ChannelCache::Global();
  cache.Clear();
  cache.SetCapacity(0);
  std::vector<json> without;
  for (const CaseSpec& spec : SmallSuite())
    without.push_back(Deterministic(RunCase(spec).ToJson()));
  EXPECT_EQ(cache.stats().hits, 0);

  cache.Clear();
  cache.SetCapacity(ChannelCache::kDefaultCapacityBytes);
  std::vector<json> with;
  for (const CaseSpec& spec : SmallSuite()) with.push_back(Deterministic(RunCase(spec).ToJson()));
  // Per seed one predicted channel and one true channel (the records' energy_true), each built
  // by the seed's first case and found by its three others.
  EXPECT_EQ(cache.stats().misses, 4);
  EXPECT_EQ(cache.stats().hits, 12);

  ASSERT_EQ(with.size(), without.size());
  for (size_t i = 0; i < with.size(); ++i) {
    // Solved (the descent stops at its 40 iterations), so the records hold real trajectories.
    EXPECT_TRUE(with[i]["status"] == "converged" || with[i]["status"] == "max_iterations")
        << with[i]["key"] << ": " << with[i]["status"];
    EXPECT_TRUE(with[i]["trajectory"].is_object());
    EXPECT_EQ(with[i], without[i])
        << "case " << with[i]["key"] << ": " << json::diff(without[i], with[i]).dump();
  }
}

}  // namespace
}  // namespace ocpb
