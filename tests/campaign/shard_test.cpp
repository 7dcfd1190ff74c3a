#include "tools/campaign/shard.hpp"

#include <gtest/gtest.h>

#include <map>
#include <string>

namespace tnv::campaign {
namespace {

TEST(CampaignShards, EveryRunIsInExactlyOneShard) {
  for (std::size_t runs : {1u, 7u, 100u, 10000u}) {
    for (int n : {1, 2, 3, 8, 64}) {
      std::uint64_t next = 1;
      for (int i = 1; i <= n; ++i) {
        const ShardRange r = shard_range(runs, i, n);
        if (r.size() == 0) continue;
        EXPECT_EQ(r.first_run, next) << runs << " runs, shard " << i << "/" << n;
        next = r.last_run + 1;
      }
      EXPECT_EQ(next, runs + 1) << runs << " runs, " << n << " shards";
    }
  }
}

TEST(CampaignShards, ShardFileNamesRoundTrip) {
  EXPECT_EQ(shard_file_name(3, 12), "shard-0003-of-0012.jsonl");
  EXPECT_EQ(parse_shard_file_name("shard-0003-of-0012.jsonl"), std::make_pair(3, 12));
  EXPECT_FALSE(parse_shard_file_name("shard-0013-of-0012.jsonl"));
  EXPECT_FALSE(parse_shard_file_name("shard-3-of-12.jsonl"));
  EXPECT_FALSE(parse_shard_file_name("shard-0003-of-0012.jsonl~"));
}

TEST(CampaignShards, ShardTextIsIOfNFromOne) {
  EXPECT_EQ(parse_shard_text("2/5").shard, 2);
  EXPECT_EQ(parse_shard_text("2/5").shards, 5);
  for (const char* bad : {"0/5", "6/5", "2", "a/b", "2/5/1", "-1/5", ""})
    EXPECT_FALSE(parse_shard_text(bad).error.empty()) << bad;
}

TEST(CampaignShards, TheShardComesFromSlurmOrKubernetes) {
  std::map<std::string, std::string> env;
  const auto get = [&](const char* name) -> const char* {
    const auto it = env.find(name);
    return it == env.end() ? nullptr : it->second.c_str();
  };
  EXPECT_FALSE(shard_from_environment(std::nullopt, get).error.empty());  // neither

  env = {{"SLURM_ARRAY_TASK_ID", "7"}, {"SLURM_ARRAY_TASK_MIN", "5"}, {"SLURM_ARRAY_TASK_COUNT", "4"}};
  ShardChoice c = shard_from_environment(std::nullopt, get);
  EXPECT_TRUE(c.error.empty()) << c.error;
  EXPECT_EQ(c.shard, 3);
  EXPECT_EQ(c.shards, 4);
  env["SLURM_ARRAY_TASK_ID"] = "9";  // past the array
  EXPECT_FALSE(shard_from_environment(std::nullopt, get).error.empty());

  env = {{"JOB_COMPLETION_INDEX", "0"}};
  EXPECT_FALSE(shard_from_environment(std::nullopt, get).error.empty());  // N must be given
  c = shard_from_environment(3, get);
  EXPECT_EQ(c.shard, 1);
  EXPECT_EQ(c.shards, 3);
  env["JOB_COMPLETION_INDEX"] = "3";
  EXPECT_FALSE(shard_from_environment(3, get).error.empty());
}

}  // namespace
}  // namespace tnv::campaign
