// S, M3 and M5 of a program streamed over the virtual bus to the emulated
// node (issue 27): the spindle really turns from its place in the program
// on (never before), the feed moves after M3 start only with it at speed,
// M5 stops it (the move after M5 does not wait for it to come to rest, as
// in LinuxCNC: it brakes during that move), and the end leaves it stopped. Judged
// on the emulated machine's spindle and table, not on the firmware's view.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "tools/can/program_run.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv {
namespace {

using can_host::StreamResult;

constexpr double kProgramRpm = 3000.0;

TEST(ProgramSpindle, TheSpindleTurnsFromM3ToM5AndTheFeedWaitsForIt) {
  can_host::EmulatedNodeOptions o;
  o.storage_path = (std::filesystem::temp_directory_path() / ("tnv_spindle_" + std::to_string(::getpid()))).string();
  std::string error;
  auto bus = can_host::EmulatedBus::create(o, error);
  ASSERT_TRUE(bus) << error;
  can_host::NodeClient client(*bus, 1);
  const double x0 = bus->rig().machine.truth(hal::Axis::x).position_mm;
  // 2 mm rapid, S3000 M3, 2 mm feed, M5, 12 mm feed (1.2 s: the spindle ramps down to rest meanwhile).
  const std::string text = "G21 G91 G17\nG0 X2\nS3000 M3\nG1 X2 F600\nM5\nG1 X12\nM2\n";
  double max_rpm_before_m3 = 0.0;   // while the table is short of the rapid's end
  double min_rpm_in_cut = 1e9;      // while the table runs the feed after M3 (between 2.05 and 3.95 mm)
  double max_rpm_after_m5 = 0.0;    // the end of the last feed (past 14.5 mm: 1.05 s after M5)
  can_host::ProgramRunOptions ro;
  ro.on_frame = [&](const hal::CanFrame&, auto) {
    const double x = bus->rig().machine.truth(hal::Axis::x).position_mm - x0;
    const double rpm = std::fabs(bus->rig().machine.spindle_truth().speed_rpm);
    if (x < 1.9) max_rpm_before_m3 = std::max(max_rpm_before_m3, rpm);
    if (x > 2.05 && x < 3.95) min_rpm_in_cut = std::min(min_rpm_in_cut, rpm);
    if (x > 14.5 && x < 15.95) max_rpm_after_m5 = std::max(max_rpm_after_m5, rpm);
  };
  const can_host::ProgramRunResult r = can_host::run_gcode(client, text, ro);
  ASSERT_EQ(r.stream.end, StreamResult::End::done) << r.stream.message;
  EXPECT_EQ(r.program.spindle_changes, 2u);
  EXPECT_LT(max_rpm_before_m3, 1.0) << "the spindle turned before its place in the program";
  EXPECT_GE(min_rpm_in_cut, 0.95 * kProgramRpm) << "the feed after M3 ran with the spindle below speed";
  EXPECT_LT(min_rpm_in_cut, 1.05 * kProgramRpm);
  EXPECT_LT(max_rpm_after_m5, 0.05 * kProgramRpm) << "M5 did not stop the spindle";
  EXPECT_NEAR(bus->rig().machine.truth(hal::Axis::x).position_mm - x0, 16.0, 0.01);
  EXPECT_FALSE(bus->rig().task.spindle().commanded_on());
  ASSERT_TRUE(r.stream.final_heartbeat);
  EXPECT_EQ(r.stream.final_heartbeat->fault, fw::FaultReason::none);
  std::filesystem::remove(o.storage_path);
}

}  // namespace
}  // namespace tnv
