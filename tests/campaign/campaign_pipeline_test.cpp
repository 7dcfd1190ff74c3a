// plan -> run in shards -> merge -> replay, in process, on a short circle.
#include <sqlite3.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "firmware/tick/work_meter.hpp"
#include "tests/campaign/campaign_fixture.hpp"
#include "tools/campaign/campaign_file.hpp"
#include "tools/campaign/experiment_row.hpp"
#include "tools/campaign/manifest.hpp"
#include "tools/campaign/merge.hpp"
#include "tools/campaign/report.hpp"
#include "tools/campaign/shard.hpp"

namespace tnv::campaign {
namespace {

namespace fs = std::filesystem;
using test::read_all;
using test::write_all;

const std::string kCampaign = test::example_campaign({.controllers = R"(["pid", "rdvsc"])", .scenario = "short.toml", .runs = 3, .sampling = ""});

class CampaignPipeline : public ::testing::Test {
 protected:
  void SetUp() override {
    write_all(tmp_.path() / "short.toml", test::kShortScenario);
    write_all(tmp_.path() / "study.toml", kCampaign);
  }
  // Plans kCampaign (or `text`) into DIR and loads the manifest.
  Manifest plan(const std::string& text = kCampaign) { return test::plan_text(tmp_.path(), text, dir()); }
  fs::path dir() const { return tmp_.path() / "camp"; }
  fs::path shard_path(int i, int n) const { return dir() / "shards" / shard_file_name(i, n); }
  test::TempDir tmp_;
};

TEST_F(CampaignPipeline, PlanResolvesEveryRunWithItsOwnSeedAndIsRepeatable) {
  const Manifest m = plan();
  ASSERT_EQ(m.runs.size(), 6u);  // 3 samples x 2 controllers
  EXPECT_EQ(m.inputs.size(), 3u);
  for (std::size_t i = 0; i < m.runs.size(); ++i) {
    const ManifestRun& r = m.runs[i];
    EXPECT_EQ(r.run_id, i + 1);
    EXPECT_EQ(r.sample, i / 2 + 1);
    EXPECT_EQ(r.controller, i % 2 == 0 ? fw::ControllerKind::pid : fw::ControllerKind::rdvsc);
    EXPECT_EQ(r.seed, run_seed(7, r.sample));
    const double gain = r.inputs.at("plant.y.gain").get<double>();
    EXPECT_GE(gain, 0.8);
    EXPECT_LE(gain, 1.2);
  }
  EXPECT_NE(m.runs[0].seed, m.runs[2].seed);
  EXPECT_NE(m.runs[0].inputs, m.runs[2].inputs);
  EXPECT_EQ(m.runs[0].inputs, m.runs[1].inputs);  // a sample's controllers see the same machine
  EXPECT_EQ(m.scenario, kScenarioCopyName);       // the scenario file is copied with the plan
  EXPECT_TRUE(fs::exists(dir() / kScenarioCopyName));

  // The same file planned again into the same directory: nothing changes.
  const std::string before = read_all(dir() / kManifestName);
  const CampaignResult spec = load_campaign_file((tmp_.path() / "study.toml").string());
  EXPECT_TRUE(plan_campaign(*spec.spec, kCampaign, dir()).ok);
  EXPECT_EQ(read_all(dir() / kManifestName), before);
  // Another campaign into it is refused.
  std::string other = kCampaign;
  other.replace(other.find("seed = 7"), 8, "seed = 8");
  const CampaignResult spec2 = parse_campaign_text(other, "other.toml", tmp_.path());
  const PlanResult refused = plan_campaign(*spec2.spec, other, dir());
  EXPECT_FALSE(refused.ok);
  EXPECT_NE(refused.error.find("another campaign"), std::string::npos) << refused.error;
  EXPECT_EQ(read_all(dir() / kManifestName), before);
}

TEST_F(CampaignPipeline, ADrawOutsideAKeysRangeIsRefusedAtPlanWithLineAndKeyAndNothingWritten) {
  // The mean is valid; a normal with this sigma draws negative friction.
  std::string text = kCampaign;
  text.replace(text.find("runs = 3"), 8, "runs = 40");
  text.replace(text.find("normal = [1.5, 0.3]"), 19, "normal = [0.2, 1.0]");
  write_all(tmp_.path() / "study.toml", text);
  const CampaignResult spec = load_campaign_file((tmp_.path() / "study.toml").string());
  ASSERT_TRUE(spec.spec) << spec.error;
  const PlanResult p = plan_campaign(*spec.spec, text, dir());
  EXPECT_FALSE(p.ok);
  EXPECT_NE(p.error.find("study.toml:7:1: vary.\"plant.x.coulomb_mm_s\": sample "), std::string::npos) << p.error;
  EXPECT_NE(p.error.find("outside the valid range"), std::string::npos) << p.error;
  EXPECT_FALSE(fs::exists(dir()));
}

TEST_F(CampaignPipeline, ShardsRunMergeAndEveryRunReplaysBitForBit) {
  const Manifest m = plan();
  const ShardRunResult a = run_shard(dir(), m, 1, 2);
  const ShardRunResult b = run_shard(dir(), m, 2, 2);
  ASSERT_TRUE(a.error.empty()) << a.error;
  ASSERT_TRUE(b.error.empty()) << b.error;
  EXPECT_EQ(a.ran + b.ran, 6u);

  // Run twice: the same bytes, nothing run.
  const std::string first = read_all(shard_path(1, 2));
  const ShardRunResult again = run_shard(dir(), m, 1, 2);
  EXPECT_EQ(again.ran, 0u);
  EXPECT_EQ(again.already_done, 3u);
  EXPECT_EQ(read_all(shard_path(1, 2)), first);

  // Each recorded line is what a replay of that run prints.
  std::vector<std::string> lines;
  for (int s = 1; s <= 2; ++s) {
    std::string text = read_all(shard_path(s, 2));
    std::size_t at = text.find('\n') + 1;  // past the header
    while (at < text.size()) {
      const std::size_t end = text.find('\n', at);
      lines.push_back(text.substr(at, end - at));
      at = end + 1;
    }
  }
  ASSERT_EQ(lines.size(), 6u);
  for (const ManifestRun& r : m.runs) {
    const auto row = run_row(m, r);
    EXPECT_EQ(row.dump(), lines[r.run_id - 1]) << "run " << r.run_id;
    EXPECT_EQ(row["status"], "ok") << row.dump();
    EXPECT_GT(row["max_um"].get<double>(), 0.0);
  }

  const MergeResult merged = merge_campaign(dir());
  ASSERT_TRUE(merged.error.empty()) << merged.error;
  EXPECT_EQ(merged.rows, 6u);
  EXPECT_EQ(merged.shards, 2u);

  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open_v2((dir() / kDatabaseName).c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db,
                               "SELECT run_id, status, \"plant.x.coulomb_mm_s\", \"plant.y.gain\", \"x.sliding.gamma\", "
                               "max_um, tool_version, build_id, controller FROM runs ORDER BY run_id",
                               -1, &st, nullptr),
            SQLITE_OK)
      << sqlite3_errmsg(db);
  int n = 0;
  while (sqlite3_step(st) == SQLITE_ROW) {
    const ManifestRun& r = m.runs[static_cast<std::size_t>(n)];
    EXPECT_EQ(sqlite3_column_int64(st, 0), static_cast<std::int64_t>(r.run_id));
    EXPECT_STREQ(reinterpret_cast<const char*>(sqlite3_column_text(st, 1)), "ok");
    EXPECT_EQ(sqlite3_column_double(st, 2), r.inputs.at("plant.x.coulomb_mm_s").get<double>());
    EXPECT_EQ(sqlite3_column_double(st, 4), r.inputs.at("x.sliding.gamma").get<double>());
    EXPECT_EQ(sqlite3_column_double(st, 5), run_row(m, r)["max_um"].get<double>());  // bit for bit
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(sqlite3_column_text(st, 6))), tool_version_text());
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(sqlite3_column_text(st, 7))), tool_build_id_text());
    ++n;
  }
  sqlite3_finalize(st);
  sqlite3_close(db);
  EXPECT_EQ(n, 6);

  // The report over it: yield counts the rows at or under the limit.
  const CampaignReport report = report_campaign(dir() / kDatabaseName, "max_um", 1e9);
  ASSERT_TRUE(report.error.empty()) << report.error;
  ASSERT_EQ(report.controllers.size(), 2u);
  EXPECT_EQ(report.controllers[0].controller, "pid");
  EXPECT_EQ(report.controllers[0].runs, 3u);
  EXPECT_DOUBLE_EQ(report.controllers[0].yield, 1.0);
  EXPECT_EQ(report.controllers[0].sensitivity.size(), 3u);
  const CampaignReport strict = report_campaign(dir() / kDatabaseName, "max_um", 0.0);
  EXPECT_DOUBLE_EQ(strict.controllers[1].yield, 0.0);
}

TEST_F(CampaignPipeline, AKilledShardRunAgainContinuesToTheSameBytes) {
  const Manifest m = plan();
  ASSERT_TRUE(run_shard(dir(), m, 1, 1).error.empty());
  const std::string whole = read_all(shard_path(1, 1));
  // As if killed in the middle of writing the third row.
  std::size_t cut = 0;
  for (int line = 0; line < 3; ++line) cut = whole.find('\n', cut) + 1;  // header + 2 rows
  cut += 17;
  write_all(shard_path(1, 1), whole.substr(0, cut));
  const ShardRunResult resumed = run_shard(dir(), m, 1, 1);
  ASSERT_TRUE(resumed.error.empty()) << resumed.error;
  EXPECT_EQ(resumed.already_done, 2u);
  EXPECT_EQ(resumed.ran, 4u);
  EXPECT_EQ(read_all(shard_path(1, 1)), whole);
}

TEST_F(CampaignPipeline, MergeRefusesAMissingCorruptOrDuplicateShardByNameAndWritesNothing) {
  const Manifest m = plan();
  ASSERT_TRUE(run_shard(dir(), m, 1, 3).error.empty());
  ASSERT_TRUE(run_shard(dir(), m, 3, 3).error.empty());
  const fs::path db = dir() / kDatabaseName;

  MergeResult r = merge_campaign(dir());
  EXPECT_NE(r.error.find(shard_file_name(2, 3) + ": missing"), std::string::npos) << r.error;
  EXPECT_FALSE(fs::exists(db));

  ASSERT_TRUE(run_shard(dir(), m, 2, 3).error.empty());
  const std::string good = read_all(shard_path(2, 3));
  std::string bad = good;
  bad[bad.find("\"status\"")] = '#';  // a damaged row
  write_all(shard_path(2, 3), bad);
  r = merge_campaign(dir());
  EXPECT_NE(r.error.find(shard_file_name(2, 3) + ": line 2 is corrupt"), std::string::npos) << r.error;
  EXPECT_FALSE(fs::exists(db));

  write_all(shard_path(2, 3), good.substr(0, good.size() - 5));  // torn at the end
  r = merge_campaign(dir());
  EXPECT_NE(r.error.find(shard_file_name(2, 3) + ": incomplete"), std::string::npos) << r.error;
  EXPECT_FALSE(fs::exists(db));

  write_all(shard_path(2, 3), good);
  ASSERT_TRUE(run_shard(dir(), m, 1, 2).error.empty());  // the same runs sharded twice
  r = merge_campaign(dir());
  EXPECT_NE(r.error.find("two shardings"), std::string::npos) << r.error;
  EXPECT_FALSE(fs::exists(db));

  fs::remove(shard_path(1, 2));
  r = merge_campaign(dir());
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.rows, 6u);
  EXPECT_TRUE(fs::exists(db));
}

TEST_F(CampaignPipeline, AShardFromAnotherCampaignIsNotResumed) {
  const Manifest m = plan();
  write_all(shard_path(1, 2), "{\"format\":\"tnv-campaign-shard 1\",\"campaign\":\"0\"}\n");
  const ShardRunResult r = run_shard(dir(), m, 1, 2);
  EXPECT_NE(r.error.find("not resuming"), std::string::npos) << r.error;
}

TEST_F(CampaignPipeline, ARunThatFaultsIsARowWithItsReason) {
  write_all(tmp_.path() / "short.toml",
            std::string(test::kShortScenario) + "[[fault]]\nkind = \"estop\"\nstart_s = 0.3\n");
  const Manifest m = plan();
  ASSERT_TRUE(run_shard(dir(), m, 1, 1).error.empty());
  const std::string text = read_all(shard_path(1, 1));
  EXPECT_NE(text.find("\"status\":\"fault\""), std::string::npos) << text;
  EXPECT_NE(text.find("estop"), std::string::npos) << text;
  const auto row = run_row(m, m.runs[0]);
  EXPECT_EQ(row["status"], "fault");
  EXPECT_TRUE(row["max_um"].is_null());
  ASSERT_TRUE(merge_campaign(dir()).error.empty());
  const CampaignReport report = report_campaign(dir() / kDatabaseName, "max_um", 1e9);
  EXPECT_EQ(report.controllers[0].ok, 0u);
  EXPECT_DOUBLE_EQ(report.controllers[0].yield, 0.0);  // a run that did not finish is out
}

// An [io] run's output writes land after the firmware's metered work; a
// build without the meter lands them sooner (docs/performance.md). Its rows
// say so, the database has the column, the report counts them; a metered
// build's rows carry no mark, and neither does a run without [io].
TEST_F(CampaignPipeline, AnIoRunOnABuildWithoutTheWorkMeterIsMarkedInRowDatabaseAndReport) {
  write_all(tmp_.path() / "short.toml", std::string(test::kShortScenario) + "[io]\nread_latency_us = 30.0\n");
  const Manifest m = plan();
  ASSERT_TRUE(run_shard(dir(), m, 1, 1).error.empty());
  const bool unmetered = !fw::work_meter_enabled();
  for (const ManifestRun& r : m.runs) {
    const auto row = run_row(m, r);
    EXPECT_EQ(row["status"], "ok") << row.dump();
    EXPECT_EQ(row.contains("io_work_unmetered"), unmetered) << row.dump();
  }
  ASSERT_TRUE(merge_campaign(dir()).error.empty());
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open_v2((dir() / kDatabaseName).c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* st = nullptr;
  ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT sum(io_work_unmetered), count(*) FROM runs", -1, &st, nullptr), SQLITE_OK);
  ASSERT_EQ(sqlite3_step(st), SQLITE_ROW);
  EXPECT_EQ(sqlite3_column_int64(st, 0), unmetered ? 6 : 0);
  EXPECT_EQ(sqlite3_column_int64(st, 1), 6);
  sqlite3_finalize(st);
  sqlite3_close(db);
  const CampaignReport report = report_campaign(dir() / kDatabaseName, "max_um", 1e9);
  ASSERT_TRUE(report.error.empty()) << report.error;
  EXPECT_EQ(report.io_work_unmetered_runs, unmetered ? 6u : 0u);
  EXPECT_EQ(report_text(report).find("warning: 6 runs ran an [io] scenario") != std::string::npos, unmetered);
  EXPECT_EQ(report_json(report)["io_work_unmetered_runs"], unmetered ? 6 : 0);
}

TEST_F(CampaignPipeline, ARunWithoutIoCarriesNoUnmeteredMark) {
  const Manifest m = plan();
  EXPECT_FALSE(run_row(m, m.runs[0]).contains("io_work_unmetered"));
}

}  // namespace
}  // namespace tnv::campaign
