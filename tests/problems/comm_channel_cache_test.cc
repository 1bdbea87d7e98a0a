// The comm problems' channel cache: one build per key, the key complete, the bounds kept, and a
// cached channel identical to a rebuilt one.
#include "problems/comm_channel_cache.h"

#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "problems/comm_path2d.h"
#include "problems/registry.h"

namespace ocpb {
namespace {

// A 10 m workspace at 0.2 m (50 x 50 cells) keeps each channel build in milliseconds.
std::vector<std::string> Small(std::vector<std::string> more = {}) {
  std::vector<std::string> a = {"workspace=10",
                                "grid_step=0.2",
                                "base=5,5",
                                "S=8,8",
                                "D=2,3",
                                "c=10",
                                "samples=100",
                                "min_pairs=10",
                                "bin_width=0.5"};
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// The problem keeps its channel alive; ChannelOf(...).get() identifies the channel object.
struct Built {
  std::unique_ptr<Ocp> ocp;
  const ChannelQuality* get() const { return &dynamic_cast<const CommPath2d&>(*ocp).channel(); }
  const ChannelQuality* operator->() const { return get(); }
};

Built ChannelOf(const std::vector<std::string>& set, std::uint64_t seed) {
  return Built{MakeProblem("comm-path2d", set, seed)};
}

// `p` with parameter `name` changed to another admissible value (+-1, halved or doubled).
Parameters Changed(const Parameters& p, const ParameterSpec& spec) {
  for (double delta : {1.0, -1.0}) {
    for (double factor : {1.0, 0.5, 2.0}) {
      std::vector<double> v = p.Raw(spec.name);
      v[0] = factor == 1.0 ? v[0] + delta : v[0] * factor;
      if (v[0] == p.Raw(spec.name)[0]) continue;
      Parameters changed = p;
      try {
        changed.Set(spec.name, v);
        return changed;
      } catch (const std::invalid_argument&) {
      }
    }
  }
  ADD_FAILURE() << "no other admissible value for " << spec.name;
  return p;
}

class ChannelCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ChannelCache::Global().Clear();
    ChannelCache::Global().SetCapacity(ChannelCache::kDefaultCapacityBytes);
  }
  void TearDown() override { SetUp(); }
};

TEST_F(ChannelCacheTest, CasesThatShareTheChannelBuildItOnce) {
  const Built a = ChannelOf(Small({"gamma=0.01"}), 1);
  const Built b = ChannelOf(Small({"gamma=1e-4", "C=500,500,500", "tf=30"}), 1);
  EXPECT_EQ(a.get(), b.get());
  const auto fixed =
      MakeProblem("comm-fixed-path", Small({"fillet=0.5"}), 1);  // shares MakeCommChannel
  EXPECT_EQ(ChannelCache::Global().stats().misses, 1);
  EXPECT_EQ(ChannelCache::Global().stats().hits, 2);
  EXPECT_NE(ChannelOf(Small(), 2).get(), a.get());               // another seed
  EXPECT_NE(ChannelOf(Small({"xi=3"}), 1).get(), a.get());       // another channel
  EXPECT_NE(ChannelOf(Small({"channel=1"}), 1).get(), a.get());  // exact, not the map
  EXPECT_EQ(ChannelCache::Global().stats().misses, 4);
  // The path-loss channel costs nothing to build and is never stored.
  ChannelOf(Small({"channel=0"}), 1);
  EXPECT_EQ(ChannelCache::Global().stats().entries, 4u);
}

TEST_F(ChannelCacheTest, ACachedChannelEqualsARebuiltOne) {
  for (const char* model : {"channel=1", "channel=2"}) {
    const Built cached = ChannelOf(Small({model}), 3);
    ChannelCache::Global().SetCapacity(0);  // disabled: every make builds
    const Built rebuilt = ChannelOf(Small({model}), 3);
    ChannelCache::Global().SetCapacity(ChannelCache::kDefaultCapacityBytes);
    ASSERT_NE(cached.get(), rebuilt.get());
    EXPECT_EQ(cached->Describe(), rebuilt->Describe());
    for (double x = -0.5; x <= 10.5; x += 0.37) {
      for (double y = -0.5; y <= 10.5; y += 0.41) {
        double s1, s2;
        Eigen::Vector2d g1, g2;
        Eigen::Matrix2d h1, h2;
        cached->Evaluate(Eigen::Vector2d(x, y), &s1, &g1, &h1);
        rebuilt->Evaluate(Eigen::Vector2d(x, y), &s2, &g2, &h2);
        ASSERT_EQ(s1, s2) << model << " at " << x << ", " << y;
        ASSERT_EQ(g1, g2);
        ASSERT_EQ(h1, h2);
      }
    }
  }
}

TEST_F(ChannelCacheTest, KeyNamesEveryChannelParameterAndNoTaskParameter) {
  const ProblemInfo& info = FindProblem("comm-path2d");
  const Parameters base(info.parameters);
  const std::string key = CommChannelKey(base, 1);
  EXPECT_NE(key, CommChannelKey(base, 2));
  const std::set<std::string> task = {
      "S", "D", "c", "tf", "umax", "Rmax", "gamma", "C", "k", "eps", "pb"};
  int channel_parameters = 0;
  for (const ParameterSpec& spec : CommParameterSpecs()) {
    const std::string changed = CommChannelKey(Changed(base, spec), 1);
    if (task.count(spec.name)) {
      EXPECT_EQ(changed, key) << spec.name;
    } else {
      EXPECT_NE(changed, key) << spec.name;
      ++channel_parameters;
    }
  }
  EXPECT_GE(channel_parameters, 17);  // the 17 of today
}

TEST_F(ChannelCacheTest, KeepsItsBoundsLeastRecentlyUsedFirst) {
  ChannelCache cache;
  auto make = [] { return std::shared_ptr<const ChannelQuality>(new PathLossChannel()); };
  cache.SetCapacity(300, 2);
  const auto a = cache.GetOrBuild("a", 100, make);
  const auto b = cache.GetOrBuild("b", 100, make);
  EXPECT_EQ(cache.GetOrBuild("a", 100, make), a);  // a is now the most recent
  cache.GetOrBuild("c", 100, make);                // max 2 entries: b goes
  EXPECT_EQ(cache.stats().entries, 2u);
  EXPECT_EQ(cache.stats().evictions, 1);
  EXPECT_EQ(cache.GetOrBuild("a", 100, make), a);
  EXPECT_NE(cache.GetOrBuild("b", 100, make), b);  // rebuilt
  cache.GetOrBuild("big", 301, make);              // larger than the capacity: not kept
  EXPECT_EQ(cache.stats().bytes, 200u);
  cache.SetCapacity(150, 2);  // shrinking evicts down to the bound
  EXPECT_EQ(cache.stats().entries, 1u);
  EXPECT_EQ(cache.stats().bytes, 100u);
  cache.SetCapacity(0);
  EXPECT_EQ(cache.stats().entries, 0u);
  EXPECT_NE(cache.GetOrBuild("a", 1, make), cache.GetOrBuild("a", 1, make));
}

TEST_F(ChannelCacheTest, AFailedBuildStoresNothing) {
  ChannelCache cache;
  EXPECT_THROW(cache.GetOrBuild("x",
                                1,
                                []() -> std::shared_ptr<const ChannelQuality> {
                                  throw std::runtime_error("no");
                                }),
               std::runtime_error);
  EXPECT_EQ(cache.stats().entries, 0u);
}

}  // namespace
}  // namespace ocpb
