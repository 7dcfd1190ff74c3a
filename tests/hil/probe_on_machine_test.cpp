// Probe moves on the emulated machine (issue 27/28): the firmware's probe
// move against emu::Machine's touch probe on [stock], judged by the
// stock's own faces. Down onto the top face and sideways onto a side face:
// the reported trip position lies within one tick's travel at the probe's
// feed (the input and the encoders are latched together once per tick)
// and a count of the encoder of where the stylus ball touches the face.
// The probe is a touch probe's stylus, not the end mill: the machine cuts
// where the tool is, and a tool point resting in the stock with the
// spindle stopped is a crash (reference plant), so the ball (0.5 mm) trips
// before the shank's point reaches the stock and it rests clear of it.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "emulator/cutting_at_tool.hpp"
#include "emulator/scenario_file.hpp"
#include "emulator/scenario_validation.hpp"
#include "tests/hil/hil_rig.hpp"

namespace tnv::hil {
namespace {

namespace motion = fw::motion;
constexpr std::size_t kX = hal::index(hal::Axis::x), kZ = hal::index(hal::Axis::z);
constexpr double kTop_mm = -155.0;     // the stock's top face (tool point; the gauge depths of [boring] must reach below it)
constexpr double kSideX_mm = 3.0;      // its side face at X max (the table powers up at X = 6)
constexpr double kFeed_mm_s = 2.0;     // the probe's feed
constexpr double kTick_s = 1e-3;
constexpr double kTip_mm = 0.5;            // the stylus ball's radius around the tool point
constexpr double kShankDiameter_mm = 0.8;  // the "tool" in the spindle: the probe's shank

emu::Scenario with_stock() {
  emu::Scenario s = *emu::builtin_scenario("no-cut");
  s.stock.enabled = true;
  s.stock.top_mm = kTop_mm;
  s.stock.x_min_mm = -50.0;
  s.stock.x_max_mm = kSideX_mm;
  s.probe.tip_radius_mm = kTip_mm;
  s.tool.diameter_mm = kShankDiameter_mm;
  return s;
}

std::unique_ptr<::tnv::test::HilRig> holding_rig(const emu::Scenario& s) {
  // A Machine is built from a validated scenario (asserted in builds with assertions).
  const std::string invalid = emu::validate_scenario(s);
  EXPECT_EQ(invalid, "");
  if (!invalid.empty()) return nullptr;
  auto rig = std::make_unique<::tnv::test::HilRig>(s);
  if (!rig->init_ok) return nullptr;
  for (int i = 0; i < 3; ++i) rig->tick();
  if (rig->task.hold_position() != fw::CommandStatus::ok) return nullptr;
  for (int i = 0; i < 10; ++i) rig->tick();
  return rig;
}

void push(::tnv::test::HilRig& rig, const motion::Segment& s) {
  motion::SegmentRefusal why{};
  ASSERT_EQ(rig.task.push_segment(s, why), fw::CommandStatus::ok) << motion::to_string(why);
}

// Ticks until a new probe report; true if one came within 60 s.
bool run_to_report(::tnv::test::HilRig& rig, std::uint32_t count_before) {
  for (int t = 0; t < 60'000; ++t) {
    rig.tick();
    if (rig.task.probe_report().count != count_before) return true;
  }
  return false;
}

// One encoder count (the reported position is the encoder's).
double count_mm(const ::tnv::test::HilRig& rig, std::size_t axis) { return rig.task.config().axis[axis].count_mm; }

TEST(ProbeOnMachine, DownOntoTheTopFaceAndSidewaysOntoASideFace) {
  const emu::Scenario s = with_stock();
  auto rig = holding_rig(s);
  ASSERT_TRUE(rig);
  const double tool_mm = s.tool.length_mm;  // the firmware's Z is the spindle nose
  // Over the stock (X = 0, the tool point 10 mm above the top), then down
  // (G38.2) to 10 mm into it.
  motion::PlanePoint over = rig->task.next_segment_start_mm();
  over[kX] = 0.0;
  over[kZ] = kTop_mm + 10.0 + tool_mm;
  push(*rig, motion::line_to(over, 10.0));
  motion::PlanePoint end = over;
  end[kZ] = kTop_mm - 10.0 + tool_mm;
  push(*rig, motion::probe_to(motion::ProbeKind::toward_or_error, end, kFeed_mm_s, 5));
  ASSERT_TRUE(run_to_report(*rig, 0)) << "no probe outcome";
  fw::ProbeReport p = rig->task.probe_report();
  ASSERT_EQ(p.outcome, motion::ProbeOutcome::tripped)
      << motion::to_string(p.outcome) << ": rests at Z " << p.rest_mm[kZ] << ", the tool point at "
      << rig->machine.truth(hal::Axis::z).position_mm - tool_mm;
  // Latency: the input is sampled with the encoders at each tick latch, so
  // the first latch at or past the face is at most one tick's travel
  // beyond it: feed x 1 ms = 2 um, plus a count (0.42 um) of rounding.
  const double tolerance_z_mm = kFeed_mm_s * kTick_s + count_mm(*rig, kZ);
  const double trip_tool_z_mm = p.trip_mm[kZ] - tool_mm;
  const double touch_z_mm = kTop_mm + kTip_mm;  // the tool point when the ball touches the top
  EXPECT_LE(trip_tool_z_mm, touch_z_mm + count_mm(*rig, kZ));
  EXPECT_GE(trip_tool_z_mm, touch_z_mm - tolerance_z_mm)
      << "tripped " << (touch_z_mm - trip_tool_z_mm) * 1e3 << " um past the ball's touch";
  const double rest_tool_z_mm = rig->machine.truth(hal::Axis::z).position_mm - tool_mm;
  EXPECT_LT(rest_tool_z_mm, touch_z_mm) << "it rests in contact";
  EXPECT_GT(rest_tool_z_mm, kTop_mm) << "the point stopped clear of the stock (within the ball)";
  EXPECT_TRUE(rig->task.program_running());

  // Up 5 mm and beside the stock: 1 mm below the top at X = 6 (3 mm off the side face).
  motion::PlanePoint up = rig->task.next_segment_start_mm();
  up[kZ] = kTop_mm + 5.0 + tool_mm;
  push(*rig, motion::line_to(up, 10.0));
  motion::PlanePoint beside = up;
  beside[kX] = kSideX_mm + 3.0;
  push(*rig, motion::line_to(beside, 10.0));
  motion::PlanePoint down = beside;
  down[kZ] = kTop_mm - 1.0 + tool_mm;
  push(*rig, motion::line_to(down, 10.0));
  // Sideways (G38.3) toward -X onto the side face.
  motion::PlanePoint side = down;
  side[kX] = kSideX_mm - 5.0;
  push(*rig, motion::probe_to(motion::ProbeKind::toward, side, kFeed_mm_s, 9));
  ASSERT_TRUE(run_to_report(*rig, 1)) << "no second probe outcome";
  p = rig->task.probe_report();
  ASSERT_EQ(p.outcome, motion::ProbeOutcome::tripped);
  EXPECT_EQ(p.tag, 9u);
  const double tolerance_x_mm = kFeed_mm_s * kTick_s + count_mm(*rig, kX);
  const double touch_x_mm = kSideX_mm + kTip_mm;
  EXPECT_LE(p.trip_mm[kX], touch_x_mm + count_mm(*rig, kX));
  EXPECT_GE(p.trip_mm[kX], touch_x_mm - tolerance_x_mm)
      << "tripped " << (touch_x_mm - p.trip_mm[kX]) * 1e3 << " um past the ball's touch";
  EXPECT_EQ(rig->machine.cutting_at_tool()->crashes().count(), 0u) << "the stylus never cut";
  EXPECT_NEAR(p.trip_mm[kZ] - tool_mm, kTop_mm - 1.0, 0.01) << "Z held while probing sideways";

  // A probe that starts in contact is refused and the program stops.
  push(*rig, motion::probe_to(motion::ProbeKind::toward, {0.0, 0.0, p.rest_mm[kZ]}, kFeed_mm_s, 11));
  ASSERT_TRUE(run_to_report(*rig, 2));
  EXPECT_EQ(rig->task.probe_report().outcome, motion::ProbeOutcome::already_tripped);
  for (int t = 0; t < 2000 && rig->task.program_running(); ++t) rig->tick();
  EXPECT_FALSE(rig->task.program_running()) << "the program did not stop";
}

TEST(ProbeOnMachine, WithoutAStockAProbeFindsNothing) {
  emu::Scenario s = with_stock();
  s.stock.x_max_mm = std::numeric_limits<double>::infinity();  // under the tool, were it there
  s.stock.enabled = false;
  auto rig = holding_rig(s);
  ASSERT_TRUE(rig);
  motion::PlanePoint end = rig->task.next_segment_start_mm();
  end[kZ] -= 20.0;  // 10 mm through where the top face would be
  push(*rig, motion::probe_to(motion::ProbeKind::toward_or_error, end, 5.0, 3));
  ASSERT_TRUE(run_to_report(*rig, 0));
  EXPECT_EQ(rig->task.probe_report().outcome, motion::ProbeOutcome::failed);
  for (int t = 0; t < 2000 && rig->task.program_running(); ++t) rig->tick();
  EXPECT_FALSE(rig->task.program_running()) << "G38.2 without contact stops the program";
}

}  // namespace
}  // namespace tnv::hil
