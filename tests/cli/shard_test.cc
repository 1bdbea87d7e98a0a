// Shards (1-based i/n), their records file names, and the coverage `merge` and `status` report.
#include <map>
#include <set>
#include <stdexcept>

#include <gtest/gtest.h>

#include "bench/cli/shard.h"
#include "bench/cli/shard_coverage.h"

namespace ocpb {
namespace {

TEST(Shard, ParsesOneBasedShards) {
  const Shard s = ParseShard("3/8");
  EXPECT_EQ(s.index, 3);
  EXPECT_EQ(s.count, 8);
  EXPECT_EQ(s.Text(), "3/8");
  EXPECT_EQ(ParseShard("8/8").index, 8);
  EXPECT_EQ(ParseShard("1/1").count, 1);
}

TEST(Shard, RefusesZeroBasedAndMalformedShards) {
  for (const char* bad : {"0/8",
                          "9/8",
                          "1/0",
                          "0/0",
                          "-1/8",
                          "1/-8",
                          "1",
                          "1/",
                          "/8",
                          "a/8",
                          "1/8x",
                          " 1/8",
                          "1/8/2",
                          "1/9999999999",
                          "+1/8"}) {
    EXPECT_THROW(ParseShard(bad), std::invalid_argument) << bad;
  }
  try {
    ParseShard("0/8");
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("numbered from 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--array=1-8"), std::string::npos) << e.what();
  }
}

// Every case belongs to exactly one shard, round robin, and CaseCount counts them.
TEST(Shard, ShardsPartitionTheSuiteRoundRobin) {
  for (int n = 1; n <= 7; ++n) {
    for (size_t cases : {0u, 1u, 5u, 16u, 23u}) {
      std::vector<int> owners(cases, 0);
      for (int i = 1; i <= n; ++i) {
        const Shard s{i, n};
        size_t owned = 0;
        for (size_t c = 0; c < cases; ++c) {
          if (s.Owns(c)) {
            ++owners[c];
            ++owned;
            EXPECT_EQ(static_cast<int>(c % n) + 1, i);
          }
        }
        EXPECT_EQ(owned, s.CaseCount(cases)) << i << "/" << n << " of " << cases;
      }
      for (size_t c = 0; c < cases; ++c) EXPECT_EQ(owners[c], 1) << c;
    }
  }
}

TEST(Shard, RecordsFileNamesRoundTrip) {
  const Shard s{2, 8};
  EXPECT_EQ(s.RecordsFileName(), "records.shard-2-of-8.jsonl");
  const std::optional<Shard> back = ShardOfRecordsFileName(s.RecordsFileName());
  ASSERT_TRUE(back.has_value());
  EXPECT_EQ(back->index, 2);
  EXPECT_EQ(back->count, 8);
  for (const char* other : {"records.jsonl",
                            "records.shard-2-of-8.jsonl.prev",
                            "records.shard-2-of-8.jsonl.tmp.123",
                            "records.shard-x-of-8.jsonl",
                            "records.shard-2-8.jsonl",
                            "summary.md"}) {
    EXPECT_FALSE(ShardOfRecordsFileName(other).has_value()) << other;
  }
  // A folder of the earlier 0-based numbering is refused, not merged wrongly.
  EXPECT_THROW(ShardOfRecordsFileName("records.shard-0-of-8.jsonl"), std::invalid_argument);
  EXPECT_THROW(ShardOfRecordsFileName("records.shard-9-of-8.jsonl"), std::invalid_argument);
}

std::vector<std::string> Keys(int n) {
  std::vector<std::string> k;
  for (int i = 0; i < n; ++i) k.push_back("case" + std::to_string(i));
  return k;
}

TEST(ShardCoverage, CompleteWhenEveryCaseIsThereOnce) {
  const auto keys = Keys(5);  // shard 1: 0, 2, 4; shard 2: 1, 3
  const ShardCoverage c =
      ComputeShardCoverage(keys, 2, {{1, {"case0", "case2", "case4"}}, {2, {"case3", "case1"}}});
  EXPECT_TRUE(c.Complete());
  EXPECT_EQ(c.recorded, 5u);
  EXPECT_EQ(c.expected, 5u);
  ASSERT_EQ(c.progress.size(), 2u);
  EXPECT_EQ(c.progress[0].expected, 3u);
  EXPECT_EQ(c.progress[1].recorded, 2u);
  EXPECT_EQ(c.IncompleteShardList(), "");
  EXPECT_EQ(DescribeShardCoverage(c, 20).size(), 1u);
}

TEST(ShardCoverage, ReportsMissingShardsMissingDuplicatedAndForeignCasesByKey) {
  const auto keys = Keys(16);  // 8 shards of 2 cases: shard i owns case i-1 and case i+7
  std::map<int, std::vector<std::string>> found;
  for (int s : {1, 2, 3, 4, 5, 6, 7}) found[s] = {keys[s - 1], keys[s + 7]};
  found[3] = {keys[2]};         // shard 3 stopped after one case
  found[4].push_back(keys[3]);  // case3 twice
  found[5].push_back("a case of another suite");
  const ShardCoverage c = ComputeShardCoverage(keys, 8, found);
  EXPECT_FALSE(c.Complete());
  EXPECT_EQ(c.recorded, 13u);
  EXPECT_EQ(c.missing, (std::vector<std::string>{"case7", "case10", "case15"}));
  EXPECT_EQ(c.duplicated, (std::vector<std::string>{"case3"}));
  EXPECT_EQ(c.foreign, (std::vector<std::string>{"a case of another suite"}));
  EXPECT_FALSE(c.progress[7].file_present);
  EXPECT_EQ(c.progress[2].recorded, 1u);
  EXPECT_EQ(c.IncompleteShardList(), "3,8");
  const std::vector<std::string> lines = DescribeShardCoverage(c, 2);
  auto has = [&](const std::string& text) {
    for (const std::string& l : lines) {
      if (l.find(text) != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_TRUE(has("13 of 16 cases recorded in 8 shards: incomplete"));
  EXPECT_TRUE(has("shard 3 of 8: 1 of 2 cases recorded (records.shard-3-of-8.jsonl)"));
  EXPECT_TRUE(has("shard 8 of 8: missing (no records.shard-8-of-8.jsonl; 2 cases)"));
  EXPECT_TRUE(has("missing case: case7"));
  EXPECT_TRUE(has("missing case: case10"));
  EXPECT_FALSE(has("missing case: case15"));         // beyond max_keys ...
  EXPECT_TRUE(has("missing case: ... and 1 more"));  // ... but counted
  EXPECT_TRUE(has("duplicated case: case3"));
  EXPECT_TRUE(has("not a case of the suite: a case of another suite"));
  EXPECT_TRUE(has("shards to run again: 3,8"));
}

TEST(ShardCoverage, ShardListsCompressRuns) {
  const auto keys = Keys(10);
  const ShardCoverage c = ComputeShardCoverage(keys, 10, {{1, {"case0"}}, {4, {"case3"}}});
  EXPECT_EQ(c.IncompleteShardList(), "2-3,5-10");
}

}  // namespace
}  // namespace ocpb
