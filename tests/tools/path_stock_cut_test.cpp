// Cutting where the tool is, on the emulated machine with a stock ([stock]
// on, emu::CuttingAtTool stepped by emu::Machine): a program that cuts with
// the spindle on (no crash, the milling force on the axes), one that feeds
// into the stock with the spindle off (a crash, the run failed), and one
// that starts a feed right after M3 (the firmware waits: no feed move
// before the spindle is at speed, as the machine measures it). The judge
// is the machine's truth, so a firmware whose at-speed window is too wide
// is caught too.
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {
namespace path_stock_cut_test {
namespace {

constexpr std::size_t kX = hal::index(hal::Axis::x);
constexpr std::size_t kZ = hal::index(hal::Axis::z);

// The head powers up with the spindle nose at -25 mm and a 125 mm tool: the
// tool point 1 mm above a stock whose top is at -151 mm.
emu::Scenario stock_scenario() {
  std::optional<emu::Scenario> s = emu::builtin_scenario("no-cut");
  EXPECT_TRUE(s.has_value());
  s->stock.enabled = true;
  s->stock.top_mm = -151.0;
  return *s;
}

PathRunResult run(const std::string& program, const fw::FirmwareConfig& config = fw::default_firmware_config()) {
  return run_path(stock_scenario(), config, fw::ControllerKind::rdvsc, program);
}

// a_p = 1 mm; 20 mm/s at 6000 rpm with 4 flutes is f_z = 0.05 mm: the
// reference plant's 150 N, 1.5 mm/s on X through 100 N per mm/s.
constexpr const char* kCutWithSpindleOn =
    "G21 G91\n"
    "S6000 M3\n"
    "G1 Z-2 F300\n"
    "G1 X40 F1200\n"
    "G0 Z2\n"
    "M5\n"
    "M2\n";

TEST(PathStockCut, ACutWithTheSpindleOnDoesNotCrashAndLoadsTheAxes) {
  const PathRunResult r = run(kCutWithSpindleOn);
  ASSERT_TRUE(r.completed) << r.error;
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.crashes, 0u);
  EXPECT_EQ(r.feed_before_at_speed, 0u);
  EXPECT_GE(r.feed_onsets, 1u) << "the plunge (the cut follows it through the corner without stopping)";
  EXPECT_NEAR(r.tool_force_max_n, 150.0, 6.0) << "F_ss at a_p 1 mm, f_z 0.05 mm (the spindle's droop adds a little)";
  EXPECT_NEAR(r.cutting_load_max_mm_s[kX], 1.5, 0.06) << "F / 100 N per mm/s against the feed on X";
  EXPECT_EQ(r.cutting_load_max_mm_s[kZ], 0.0) << "the force is in XY";
  std::printf("stock cut: force max %.1f N, X load %.3f mm/s, %u feed starts\n", r.tool_force_max_n,
              r.cutting_load_max_mm_s[kX], r.feed_onsets);
}

TEST(PathStockCut, FeedingIntoTheStockWithTheSpindleOffIsACrashAndFailsTheRun) {
  const PathRunResult r = run("G21 G91\nG1 Z-2 F300\nG1 X10 F1200\nG0 Z2\nM2\n");
  EXPECT_GE(r.crashes, 1u);
  ASSERT_FALSE(r.crash_events.empty());
  EXPECT_EQ(r.crash_events.front().commanded_rpm, 0.0);
  EXPECT_LT(r.crash_events.front().z_mm, -151.0) << "below the stock top";
  EXPECT_EQ(r.error.rfind("crash", 0), 0u) << "the crash is the run's first failure: " << r.error;
  EXPECT_EQ(r.feed_before_at_speed, 0u) << "the spindle was never commanded on";
}

TEST(PathStockCut, AFeedRightAfterM3WaitsForTheSpindle) {
  const PathRunResult r = run("G21 G91\nS3000 M3\nG1 X5 F600\nM5\nM2\n");
  ASSERT_TRUE(r.completed) << r.error;
  EXPECT_EQ(r.crashes, 0u) << "above the stock";
  EXPECT_EQ(r.feed_onsets, 1u);
  EXPECT_EQ(r.feed_before_at_speed, 0u);
}

TEST(PathStockCut, AFirmwareThatFeedsBeforeAtSpeedIsCaughtByTheMachine) {
  // The widest at-speed window the firmware takes and the drive's fastest
  // ramp: its gate opens at the ramp's end with the drive ~1,200 rpm behind
  // (6,000 rpm/s x tau_sp 0.2 s), far outside a 5 % window.
  fw::FirmwareConfig config = fw::default_firmware_config();
  config.spindle.accel_rpm_s = 6000.0;
  config.spindle.at_speed_fraction = 0.5;
  config.spindle.at_speed_floor_rpm = 1000.0;
  config.spindle.at_speed_ticks = 1;
  const PathRunResult r = run("G21 G91\nS6000 M3\nG1 X5 F600\nM5\nM2\n", config);
  ASSERT_TRUE(r.completed) << r.error;
  EXPECT_EQ(r.feed_onsets, 1u);
  EXPECT_EQ(r.feed_before_at_speed, 1u);
}

}  // namespace
}  // namespace path_stock_cut_test
}  // namespace tnv::hil
