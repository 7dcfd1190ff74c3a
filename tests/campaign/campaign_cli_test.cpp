// tnv-hil campaign as a user runs it: the shards through GNU parallel
// (tools/campaign/engines/parallel.sh), then merge, replay and report.
#include <gtest/gtest.h>

#include <string>

#include "tests/campaign/campaign_fixture.hpp"
#include "tests/tools/cli_runner.hpp"
#include "tools/campaign/manifest.hpp"
#include "tools/campaign/shard.hpp"

namespace tnv::campaign {
namespace {

namespace fs = std::filesystem;
using test::read_all;
using test::write_all;

const std::string kCliCampaign = test::example_campaign(
    {.controllers = R"(["pid", "rdvsc"])", .scenario = "short.toml", .runs = 3, .sampling = "latin-hypercube"});

// Quoted for the shell (GCC 12 warns about "'" + string: built up instead).
std::string q(const fs::path& p) {
  std::string quoted(1, '\'');
  quoted += p.string();
  quoted += '\'';
  return quoted;
}

TEST(CampaignCli, ABadCampaignFileIsRefusedWithFileLineAndKeyAndNothingPlanned) {
  test::TempDir tmp;
  std::string text = kCliCampaign;
  text.replace(text.find("x.sliding.gamma"), 15, "x.sliding.gama");
  write_all(tmp.path() / "short.toml", test::kShortScenario);
  write_all(tmp.path() / "study.toml", text);
  const auto r = tnv::test::run_tnv_hil("campaign plan " + q(tmp.path() / "study.toml") + " --out " + q(tmp.path() / "c"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("study.toml:10:1: vary.\"x.sliding.gama\": neither a scenario key"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(tmp.path() / "c"));
}

TEST(CampaignCli, ShardsThroughGnuParallelMergeReplayAndReport) {
  test::TempDir tmp;
  write_all(tmp.path() / "short.toml", test::kShortScenario);
  write_all(tmp.path() / "study.toml", kCliCampaign);
  const fs::path dir = tmp.path() / "c";
  auto r = tnv::test::run_tnv_hil("campaign plan " + q(tmp.path() / "study.toml") + " --out " + q(dir));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("6 runs"), std::string::npos) << r.out;

  std::string engine = "TNV_HIL=";
  engine += q(TNV_HIL_EXE);
  engine += " " TNV_CAMPAIGN_SCRIPTS_DIR "/parallel.sh ";
  engine += q(dir);
  engine += " 3 2";
  r = tnv::test::run_command(engine);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("6 runs from 3 shards"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(dir / "campaign.sqlite"));

  // Run 4 is shard 2's second row; the replay prints exactly that line.
  const std::string shard = read_all(dir / "shards" / shard_file_name(2, 3));
  const std::size_t row2 = shard.find('\n', shard.find('\n') + 1) + 1;
  const std::string line = shard.substr(row2, shard.find('\n', row2) - row2);
  ASSERT_NE(line.find("\"run_id\":4,"), std::string::npos) << line;
  r = tnv::test::run_tnv_hil("campaign replay " + q(dir) + " 4 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, line + "\n");
  EXPECT_NE(r.err.find("identical to its row"), std::string::npos) << r.err;

  // A shard run again by the engine (all done) leaves every byte as it was.
  const std::string before = read_all(dir / "shards" / shard_file_name(1, 3));
  r = tnv::test::run_tnv_hil("campaign run " + q(dir) + " --shard 1/3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_all(dir / "shards" / shard_file_name(1, 3)), before);

  // A Slurm array task's index picks the shard.
  fs::remove(dir / "shards" / shard_file_name(3, 3));
  std::string slurm_task = "SLURM_ARRAY_TASK_ID=3 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_COUNT=3 ";
  slurm_task += q(TNV_HIL_EXE);
  slurm_task += " campaign run ";
  slurm_task += q(dir);
  r = tnv::test::run_command(slurm_task);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "shards" / shard_file_name(3, 3)));

  r = tnv::test::run_tnv_hil("campaign report " + q(dir) + " --json --limit-um 1000");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["controllers"].size(), 2u);
  EXPECT_EQ(j["controllers"][0]["controller"], "pid");
  EXPECT_EQ(j["controllers"][0]["yield"], 1.0);
  EXPECT_EQ(j["controllers"][0]["sensitivity"].size(), 3u);  // one per varied input

  r = tnv::test::run_tnv_hil("campaign report " + q(dir) + " --plot " + q(tmp.path() / "c.svg"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("yield"), std::string::npos) << r.out;
  EXPECT_NE(read_all(tmp.path() / "c.svg").find("<svg"), std::string::npos);
}

TEST(CampaignCli, MergeOfACampaignWithAShardMissingNamesItAndWritesNothing) {
  test::TempDir tmp;
  write_all(tmp.path() / "short.toml", test::kShortScenario);
  write_all(tmp.path() / "study.toml", kCliCampaign);
  const fs::path dir = tmp.path() / "c";
  ASSERT_EQ(tnv::test::run_tnv_hil("campaign plan " + q(tmp.path() / "study.toml") + " --out " + q(dir)).exit_code, 0);
  ASSERT_EQ(tnv::test::run_tnv_hil("campaign run " + q(dir) + " --shard 2/2").exit_code, 0);
  const auto r = tnv::test::run_tnv_hil("campaign merge " + q(dir));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("shard-0001-of-0002.jsonl: missing"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "campaign.sqlite"));
}

// An experiment without a controller choice, through the tool: its rows
// say "none", the report judges the experiment's own metric and plots it.
TEST(CampaignCli, ABoringCampaignRunsMergesReplaysAndReports) {
  test::TempDir tmp;
  write_all(tmp.path() / "boring.toml",
            "experiment = \"boring\"\nscenario = \"no-cut\"\nruns = 4\nseed = 9\nparts = 12\nchange_at = [7]\n"
            "[vary]\n\"bore.alpha0\" = { uniform = [0.4, 0.6] }\n");
  const fs::path dir = tmp.path() / "c";
  auto r = tnv::test::run_tnv_hil("campaign plan " + q(tmp.path() / "boring.toml") + " --out " + q(dir));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("4 runs"), std::string::npos) << r.out;
  for (const char* shard : {"1/2", "2/2"})
    ASSERT_EQ(tnv::test::run_tnv_hil("campaign run " + q(dir) + " --shard " + shard).exit_code, 0);
  r = tnv::test::run_tnv_hil("campaign merge " + q(dir));
  ASSERT_EQ(r.exit_code, 0) << r.err;

  const std::string shard = read_all(dir / "shards" / shard_file_name(2, 2));
  const std::size_t row1 = shard.find('\n') + 1;
  const std::string line = shard.substr(row1, shard.find('\n', row1) - row1);
  ASSERT_NE(line.find("\"run_id\":3,"), std::string::npos) << line;
  r = tnv::test::run_tnv_hil("campaign replay " + q(dir) + " 3 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, line + "\n");

  r = tnv::test::run_tnv_hil("campaign report " + q(dir) + " --json --plot " + q(tmp.path() / "b.svg"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["metric"], "bad_parts");
  ASSERT_EQ(j["controllers"].size(), 1u);
  EXPECT_EQ(j["controllers"][0]["controller"], "none");
  EXPECT_EQ(j["controllers"][0]["finished"], 4);
  EXPECT_NE(read_all(tmp.path() / "b.svg").find("<svg"), std::string::npos);
}

}  // namespace
}  // namespace tnv::campaign
