// tnv-hil rt-budget as a script runs it: the JSON keys the docs quote, no
// lost tick while the bench session runs, and no call over 50 us of
// modelled board time (the work meter's block count, whatever the
// machine's load; the host CPU microseconds depend on the machine and are
// not checked here).
#include <gtest/gtest.h>

#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "firmware/tick/work_meter.hpp"
#include "tests/tools/cli_runner.hpp"

namespace tnv::test {
namespace {

TEST(RtBudgetCli, BenchSessionLosesNoTickAndNamesEveryRequestKind) {
  const CliRun r = run_tnv_hil("rt-budget --rounds 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* key : {"max_call_us", "p999_call_us", "missed_ticks", "late_ticks", "kinds", "requests", "replies"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["missed_ticks"], 0);
  EXPECT_EQ(j["late_ticks"], 0);
  EXPECT_TRUE(j["held"].get<bool>());
  EXPECT_GT(j["upload_frames"].get<int>(), 0);
  EXPECT_EQ(j["worker_jobs"], 6);  // a save, a load and a shaper design per round, all off the loop
  EXPECT_EQ(j.contains("board_time_metered"), !fw::work_meter_enabled()) << "a build without the meter says so";
  if (fw::work_meter_enabled()) {
    EXPECT_GT(j["max_board_us"].get<double>(), 0.0);
    EXPECT_LE(j["max_board_us"].get<double>(), 50.0) << "a call over the real-time budget of one request";
  }
  std::set<std::string> kinds;
  for (const auto& k : j["kinds"]) {
    for (const char* key : {"kind", "calls", "max_call_us", "p999_call_us"}) EXPECT_TRUE(k.contains(key)) << key;
    EXPECT_GT(k["calls"].get<int>(), 0);
    EXPECT_GE(k["max_call_us"].get<double>(), k["p999_call_us"].get<double>());
    EXPECT_EQ(k["refused"], 0) << k["kind"];
    kinds.insert(k["kind"].get<std::string>());
  }
  for (const char* kind : {"tick", "save_params", "load_params", "storage_reply", "restore_defaults", "param_commit",
                           "capture_upload", "excite", "param_get", "param_set", "bore_query", "bore_record_startup",
                           "bore_record", "shaper", "shaper_reply"})
    EXPECT_TRUE(kinds.count(kind)) << kind;
}

TEST(RtBudgetCli, RefusesZeroRounds) {
  const CliRun r = run_tnv_hil("rt-budget --rounds 0");
  EXPECT_EQ(r.exit_code, 2);
}

}  // namespace
}  // namespace tnv::test
