// Campaigns of every experiment besides circle (path, faults, homing,
// boring, arsc tick): a small campaign planned, run in two shards (twice:
// the same bytes), merged, every run replayed to its recorded line; a run
// that faults is a row with its reason; a bad file is refused with its
// line and key before anything is written.
#include <sqlite3.h>

#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

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
using ojson = nlohmann::ordered_json;
using test::read_all;
using test::write_all;

// A 2 mm square at 20 mm/s.
constexpr const char* kSquare =
    "G21 G90\n"
    "G1 X2 Y0 F1200\n"
    "G1 X2 Y2\n"
    "G1 X0 Y2\n"
    "G1 X0 Y0\n"
    "M2\n";

class CampaignExperiments : public ::testing::Test {
 protected:
  fs::path dir() const { return tmp_.path() / "camp"; }

  CampaignResult parse(const std::string& text) {
    write_all(tmp_.path() / "study.toml", text);
    return load_campaign_file((tmp_.path() / "study.toml").string());
  }

  Manifest plan(const std::string& text) { return test::plan_text(tmp_.path(), text, dir()); }

  // The file is refused by the parser with this text in its one-line error.
  void expect_refused(const std::string& text, const std::string& expected) {
    const CampaignResult spec = parse(text);
    EXPECT_FALSE(spec.spec) << "accepted:\n" << text;
    EXPECT_NE(spec.error.find(expected), std::string::npos) << spec.error;
    EXPECT_FALSE(fs::exists(dir()));
  }

  // Two shards, each run twice (the same bytes), merged; every run
  // replays to its recorded line. Returns the rows, by run id.
  std::vector<ojson> run_merge_replay(const Manifest& m) {
    for (int s = 1; s <= 2; ++s) {
      const ShardRunResult r = run_shard(dir(), m, s, 2);
      EXPECT_TRUE(r.error.empty()) << r.error;
    }
    std::vector<std::string> lines;
    for (int s = 1; s <= 2; ++s) {
      const fs::path path = dir() / "shards" / shard_file_name(s, 2);
      const std::string first = read_all(path);
      const ShardRunResult again = run_shard(dir(), m, s, 2);
      EXPECT_EQ(again.ran, 0u);
      EXPECT_EQ(read_all(path), first);
      // The same shard run afresh: the same bytes.
      fs::remove(path);
      EXPECT_TRUE(run_shard(dir(), m, s, 2).error.empty());
      EXPECT_EQ(read_all(path), first) << "shard " << s << " run afresh differs";
      std::size_t at = first.find('\n') + 1;
      while (at < first.size()) {
        const std::size_t end = first.find('\n', at);
        lines.push_back(first.substr(at, end - at));
        at = end + 1;
      }
    }
    EXPECT_EQ(lines.size(), m.runs.size());
    std::vector<ojson> rows;
    for (const ManifestRun& r : m.runs) {
      const ojson row = run_row(m, r);
      if (r.run_id - 1 < lines.size()) {
        EXPECT_EQ(row.dump(), lines[r.run_id - 1]) << "run " << r.run_id;
      }
      rows.push_back(row);
    }
    const MergeResult merged = merge_campaign(dir());
    EXPECT_TRUE(merged.error.empty()) << merged.error;
    EXPECT_EQ(merged.rows, m.runs.size());
    return rows;
  }

  // One column of the merged table, by run id, as text ("" for NULL).
  std::vector<std::string> column(const std::string& name) {
    std::vector<std::string> out;
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open_v2((dir() / kDatabaseName).c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
    sqlite3_stmt* st = nullptr;
    const std::string sql = "SELECT \"" + name + "\" FROM runs ORDER BY run_id";
    EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &st, nullptr), SQLITE_OK) << sqlite3_errmsg(db);
    while (st != nullptr && sqlite3_step(st) == SQLITE_ROW) {
      const unsigned char* t = sqlite3_column_text(st, 0);
      out.emplace_back(t != nullptr ? reinterpret_cast<const char*>(t) : "");
    }
    sqlite3_finalize(st);
    sqlite3_close(db);
    return out;
  }

  std::string fault_scenario(const std::string& name, double start_s) {
    const std::string file = name + ".toml";
    write_all(tmp_.path() / file, "name = \"" + name + "\"\n[[fault]]\nkind = \"estop\"\nstart_s = " +
                                      std::to_string(start_s) + "\n");
    return file;
  }

  test::TempDir tmp_;
};

// --- path

std::string path_campaign(const std::string& scenario = "no-cut") {
  return "experiment = \"path\"\n"
         "program = \"square.ngc\"\n"
         "controllers = [\"pid\", \"rdvsc\"]\n"
         "scenario = \"" + scenario + "\"\n"
         "runs = 2\n"
         "seed = 3\n"
         "[vary]\n"
         "\"plant.x.gain\" = { uniform = [0.9, 1.1] }\n"
         "\"x.sliding.gamma\" = { uniform = [0.35, 0.45] }\n";
}

TEST_F(CampaignExperiments, PathPlansRunsMergesAndReplays) {
  write_all(tmp_.path() / "square.ngc", kSquare);
  const Manifest m = plan(path_campaign());
  ASSERT_EQ(m.runs.size(), 4u);
  EXPECT_EQ(m.program_text, kSquare);  // copied with the plan: runs never read the original
  EXPECT_EQ(m.settings.at("rapid_feed_mm_s"), 50.0);  // the default, recorded
  fs::remove(tmp_.path() / "square.ngc");
  const std::vector<ojson> rows = run_merge_replay(m);
  for (const ojson& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row.dump();
    EXPECT_GT(row["contour_error_max_um"].get<double>(), 0.0);
    EXPECT_EQ(row["segments"], 4u);
    // The square, and the move from where the table holds to its first corner.
    EXPECT_GT(row["programmed_length_mm"].get<double>(), 8.0);
  }
  EXPECT_EQ(column("controller"), (std::vector<std::string>{"pid", "rdvsc", "pid", "rdvsc"}));
  EXPECT_EQ(column("segments"), (std::vector<std::string>{"4", "4", "4", "4"}));
  const CampaignReport report = report_campaign(dir() / kDatabaseName, "", std::nullopt);
  ASSERT_TRUE(report.error.empty()) << report.error;
  EXPECT_EQ(report.metric, "contour_error_max_um");  // the experiment's default
}

TEST_F(CampaignExperiments, PathRunThatFaultsIsARowWithItsReason) {
  write_all(tmp_.path() / "square.ngc", kSquare);
  const Manifest m = plan(path_campaign(fault_scenario("estop", 0.3)));
  const std::vector<ojson> rows = run_merge_replay(m);
  for (const ojson& row : rows) {
    EXPECT_EQ(row["status"], "fault") << row.dump();
    EXPECT_NE(row["reason"].get<std::string>().find("estop"), std::string::npos) << row.dump();
    EXPECT_TRUE(row["contour_error_max_um"].is_null());
  }
}

TEST_F(CampaignExperiments, PathBadFilesAreRefusedWithLineAndKey) {
  write_all(tmp_.path() / "square.ngc", "G21 G90\nG1 X2 Q7 F1200\nM2\n");
  expect_refused(path_campaign(), "study.toml:2:1: program: square.ngc: line 2");
  write_all(tmp_.path() / "square.ngc", kSquare);
  std::string missing = path_campaign();
  missing.erase(missing.find("program = "), std::string("program = \"square.ngc\"\n").size());
  expect_refused(missing, "study.toml:1:1: program: required for experiment \"path\"");
  EXPECT_TRUE(parse(path_campaign()).spec);  // the same file with both mended
}

// --- faults

std::string faults_campaign(const std::string& fault_case) {
  return "experiment = \"faults\"\n"
         "fault_case = \"" + fault_case + "\"\n"
         "controllers = [\"rdvsc\"]\n"
         "scenario = \"no-cut\"\n"
         "runs = 3\n"
         "seed = 5\n"
         "[vary]\n"
         "\"plant.x.coulomb_mm_s\" = { uniform = [1.0, 2.0] }\n"
         "\"x.sliding.gamma\" = { uniform = [0.35, 0.45] }\n";
}

TEST_F(CampaignExperiments, FaultsPlansRunsMergesAndReplays) {
  const Manifest m = plan(faults_campaign("runaway"));
  ASSERT_EQ(m.runs.size(), 3u);
  const std::vector<ojson> rows = run_merge_replay(m);
  for (const ojson& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row.dump();
    EXPECT_EQ(row["latched"], "runaway") << row.dump();
    EXPECT_EQ(row["ok"], true) << row.dump();
    EXPECT_GE(row["ticks_to_detect"].get<std::uint64_t>(), 1u);
    EXPECT_GT(row["time_to_safe_ms"].get<double>(), 0.0);
  }
  EXPECT_EQ(column("latched"), (std::vector<std::string>{"runaway", "runaway", "runaway"}));
  EXPECT_EQ(column("ok"), (std::vector<std::string>{"1", "1", "1"}));
}

TEST_F(CampaignExperiments, FaultsBadFilesAreRefusedWithLineAndKey) {
  expect_refused(faults_campaign("nosuch"), "study.toml:2:1: fault_case: \"nosuch\": no such fault case (estop,");
  std::string missing = faults_campaign("estop");
  missing.erase(missing.find("fault_case = "), std::string("fault_case = \"estop\"\n").size());
  expect_refused(missing, "fault_case: required for experiment \"faults\"");
  expect_refused("program = \"x.ngc\"\n" + faults_campaign("estop"),
                 "study.toml:1:1: program: a key of experiment \"path\", not of \"faults\"");
}

// --- homing

std::string homing_campaign(const std::string& scenario = "no-cut") {
  return "experiment = \"homing\"\n"
         "controllers = [\"pid\", \"rdvsc\"]\n"
         "scenario = \"" + scenario + "\"\n"
         "runs = 2\n"
         "seed = 11\n"
         "[vary]\n"
         "\"x.homing.latch_mm_s\" = { uniform = [1.5, 2.5] }\n"
         "\"plant.x.gain\" = { uniform = [0.9, 1.1] }\n";
}

TEST_F(CampaignExperiments, HomingPlansRunsMergesAndReplays) {
  const Manifest m = plan(homing_campaign());
  ASSERT_EQ(m.runs.size(), 4u);
  const std::vector<ojson> rows = run_merge_replay(m);
  for (const ojson& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row.dump();
    // The homing goal: within 0.5 um at the mark (one count is 0.417 um).
    EXPECT_LE(row["home_error_um_max"].get<double>(), 0.5) << row.dump();
    EXPECT_GT(row["time_s"].get<double>(), 0.0);
  }
  // Each sample powers up elsewhere (its own seed); its controllers start alike.
  EXPECT_EQ(rows[0]["power_up_offset_x_mm"], rows[1]["power_up_offset_x_mm"]);
  EXPECT_NE(rows[0]["power_up_offset_x_mm"], rows[2]["power_up_offset_x_mm"]);
}

TEST_F(CampaignExperiments, HomingRunThatFaultsIsARowWithItsReason) {
  const Manifest m = plan(homing_campaign(fault_scenario("estop", 0.2)));
  const std::vector<ojson> rows = run_merge_replay(m);
  for (const ojson& row : rows) {
    EXPECT_EQ(row["status"], "fault") << row.dump();
    EXPECT_NE(row["reason"].get<std::string>().find("estop"), std::string::npos) << row.dump();
    EXPECT_TRUE(row["home_error_um_max"].is_null());
  }
}

TEST_F(CampaignExperiments, HomingBadFilesAreRefusedWithLineAndKey) {
  std::string no_controllers = homing_campaign();
  no_controllers.erase(no_controllers.find("controllers = "), std::string("controllers = [\"pid\", \"rdvsc\"]\n").size());
  expect_refused(no_controllers, "study.toml:1:1: controllers: required");
  std::string bad_speed = homing_campaign();
  bad_speed.replace(bad_speed.find("[1.5, 2.5]"), 10, "[1.5, 900.0]");
  expect_refused(bad_speed, "study.toml:7:1: vary.\"x.homing.latch_mm_s\": uniform high end (900)");
}

// --- boring

std::string boring_campaign() {
  return "experiment = \"boring\"\n"
         "scenario = \"no-cut\"\n"
         "runs = 3\n"
         "seed = 2\n"
         "parts = 12\n"
         "change_at = [7]\n"
         "[vary]\n"
         "\"bore.alpha0\" = { uniform = [0.4, 0.6] }\n"
         "\"noise.bore_gauge_um_rms\" = { uniform = [0.0, 2.0] }\n";
}

TEST_F(CampaignExperiments, BoringPlansRunsMergesAndReplays) {
  const Manifest m = plan(boring_campaign());
  ASSERT_EQ(m.runs.size(), 3u);  // no controllers: one run a sample
  EXPECT_FALSE(m.runs[0].controller.has_value());
  EXPECT_EQ(m.settings.at("change_at"), ojson::array({7}));
  const std::vector<ojson> rows = run_merge_replay(m);
  for (const ojson& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row.dump();
    EXPECT_GE(row["bad_parts"].get<int>(), 0);
    EXPECT_LE(row["bad_parts"].get<int>(), 12);
    EXPECT_GT(row["deflection_rms_mm"].get<double>(), 0.0);
  }
  // The gauge noise differs between the samples: so do the parts.
  EXPECT_NE(rows[0]["deflection_rms_mm"], rows[1]["deflection_rms_mm"]);
  EXPECT_EQ(column("controller"), (std::vector<std::string>{"none", "none", "none"}));
}

TEST_F(CampaignExperiments, BoringBadFilesAreRefusedWithLineAndKey) {
  expect_refused(boring_campaign() + "\"plant.x.gain\" = { uniform = [0.9, 1.1] }\n",
                 "study.toml:10:1: vary.\"plant.x.gain\": not an input of experiment \"boring\"");
  expect_refused("controllers = [\"pid\"]\n" + boring_campaign(), "study.toml:1:1: controllers: \"boring\" runs no axis loops");
  std::string bad_change = boring_campaign();
  bad_change.replace(bad_change.find("[7]"), 3, "[7, 5]");
  expect_refused(bad_change, "study.toml:6:1: change_at: change points must increase");
  std::string bad_alpha = boring_campaign();
  bad_alpha.replace(bad_alpha.find("[0.4, 0.6]"), 10, "[0.4, 9.0]");
  expect_refused(bad_alpha, "study.toml:8:1: vary.\"bore.alpha0\": uniform high end (9)");
}

// --- arsc tick

std::string arsc_tick_campaign(const std::string& scenario = "no-cut") {
  return "experiment = \"arsc tick\"\n"
         "scenario = \"" + scenario + "\"\n"
         "runs = 2\n"
         "seed = 4\n"
         "period_ms = 10\n"
         "[vary]\n"
         "\"plant.x.gain\" = { uniform = [0.9, 1.1] }\n";
}

TEST_F(CampaignExperiments, ArscTickPlansRunsMergesAndReplays) {
  const Manifest m = plan(arsc_tick_campaign());
  ASSERT_EQ(m.runs.size(), 2u);
  EXPECT_EQ(m.runs[0].controller, fw::ControllerKind::rdvsc);  // the study's loops
  const std::vector<ojson> rows = run_merge_replay(m);
  for (const ojson& row : rows) {
    EXPECT_EQ(row["status"], "ok") << row.dump();
    EXPECT_GT(row["force_error_max_pct"].get<double>(), 0.0);
    EXPECT_EQ(row["diverged"], false);
  }
  EXPECT_NE(rows[0]["force_error_rms_pct"], rows[1]["force_error_rms_pct"]);
}

TEST_F(CampaignExperiments, ArscTickRunThatFaultsIsARowWithItsReason) {
  // After the test stage (its own machine, 4 s), in the cut.
  const Manifest m = plan(arsc_tick_campaign(fault_scenario("estop", 6.0)));
  const std::vector<ojson> rows = run_merge_replay(m);
  for (const ojson& row : rows) {
    EXPECT_EQ(row["status"], "fault") << row.dump();
    EXPECT_NE(row["reason"].get<std::string>().find("estop"), std::string::npos) << row.dump();
    EXPECT_TRUE(row["force_error_max_pct"].is_null());
  }
}

TEST_F(CampaignExperiments, ArscTickBadFilesAreRefusedWithLineAndKey) {
  expect_refused(arsc_tick_campaign() + "\"x.sliding.gamma\" = { uniform = [0.35, 0.45] }\n",
                 "study.toml:8:1: vary.\"x.sliding.gamma\": not an input of experiment \"arsc tick\"");
  std::string bad_poles = arsc_tick_campaign();
  bad_poles.insert(bad_poles.find("[vary]"), "poles = \"case9\"\n");
  expect_refused(bad_poles, "study.toml:6:1: poles: must be \"case1\"");
  expect_refused("controllers = [\"pid\"]\n" + arsc_tick_campaign(),
                 "study.toml:1:1: controllers: \"arsc tick\" runs R-DVSC+DDC only");
}

}  // namespace
}  // namespace tnv::campaign
