// The shaper in the tick's reference path, the point-to-point move and the
// operator jog, on a scripted board whose table follows the reference the
// controllers were given (perfect servo, one tick late).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "firmware/motion/discrete_braking.hpp"
#include "firmware/shaper/stream_shaper.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tests/firmware/fake_io_board.hpp"
#include "tests/firmware/test_units.hpp"

namespace tnv::fw {
namespace {

using test_units::kCountMm;
constexpr double kHomeMm = 6.0;
using test_units::kPeriodS;

class TickShaperTest : public ::testing::Test {
 protected:
  TickShaperTest() : task(board, make_config()) {}

  static FirmwareConfig make_config() {
    FirmwareConfig c = default_firmware_config();
    c.axis[0].home_position_mm = kHomeMm;
    c.axis[1].home_position_mm = 0.0;
    // The table below follows the reference whatever the DAC says, so the
    // loop winds up against it; that is not a stall worth a fault here.
    for (auto& a : c.supervisor.axis) a.stall.command_mm_s = 1e4;
    return c;
  }

  // The table stands where the last tick's reference was (a perfect servo).
  void tick() {
    board.next_tick();
    task.tick();
    for (std::size_t i = 0; i < 2; ++i) {
      const double home = i == 0 ? kHomeMm : 0.0;
      board.counts[i] =
          static_cast<std::uint32_t>(std::lround((task.last_record().axis[i].reference_mm - home) / kCountMm));
    }
  }

  void servo_on_holding() {
    tick();
    ASSERT_EQ(task.hold_position(), CommandStatus::ok);
    tick();
    ASSERT_EQ(task.state(), MotionState::holding);
  }

  tnv::test::FakeIoBoard board;
  TickTask task;
};

TEST_F(TickShaperTest, UnshapedMoveFollowsTheProfileExactly) {
  servo_on_holding();
  const MoveSpec spec{hal::Axis::x, 5.0, 50.0, 0.02, 0.0};
  ASSERT_EQ(task.start_move(spec), CommandStatus::ok);
  const PointToPointMove move(spec, kHomeMm);
  EXPECT_NEAR(move.duration_s(), 0.12, 1e-15) << "move time = distance / speed + ramp";
  int ticks = 0;
  do {
    tick();
    const TickRecord& r = task.last_record();
    if (r.motion_tick >= 0) {
      ASSERT_EQ(r.axis[0].reference_mm, move.at(static_cast<double>(r.motion_tick) * kPeriodS).position_mm);
      ASSERT_EQ(r.axis[0].reference_mm, r.axis[0].unshaped_reference_mm);
      ASSERT_EQ(r.axis[1].reference_mm, 0.0) << "the other axis holds";
      ++ticks;
    }
  } while (task.state() == MotionState::moving);
  EXPECT_EQ(ticks, 121);
  EXPECT_EQ(task.state(), MotionState::holding);
  EXPECT_EQ(task.last_record().axis[0].reference_mm, kHomeMm + 5.0);
}

// With the shaper on, the reference the controllers get is the offline
// shaping of the move's samples, and the motion lasts until the shaped
// reference is at rest, exactly at the end point.
TEST_F(TickShaperTest, ShapedMoveIsTheOfflineShapingOfTheProfile) {
  const ShaperSpec zvd{ShaperType::zvd, {30.0, 0.02}, {0.0, 0.0}};
  ASSERT_EQ(task.configure_shaper(hal::Axis::x, zvd), CommandStatus::ok);
  ASSERT_EQ(task.enable_shaper(hal::Axis::x, true), CommandStatus::ok);
  servo_on_holding();
  ASSERT_TRUE(task.shaper(hal::Axis::x).shaping());
  EXPECT_TRUE(task.shaper(hal::Axis::y).shaping()) << "every axis of the path runs x's shaper";
  EXPECT_NEAR(task.shaper_delay_s(hal::Axis::x), task.shaper_design(hal::Axis::x).delay_s(), 1e-15);
  EXPECT_EQ(task.shaper_delay_s(hal::Axis::y), task.shaper_delay_s(hal::Axis::x)) << "delayed equally";
  const MoveSpec spec{hal::Axis::x, -3.0, 40.0, 0.025, 0.0};
  ASSERT_EQ(task.start_move(spec), CommandStatus::ok);
  const PointToPointMove move(spec, kHomeMm);
  std::vector<AxisSample> raw;
  std::vector<double> shaped;
  while (task.state() != MotionState::holding) {
    tick();
    ASSERT_NE(task.state(), MotionState::faulted);
    const TickRecord& r = task.last_record();
    if (r.motion_tick < 0) continue;
    raw.push_back(move.at(static_cast<double>(r.motion_tick) * kPeriodS));
    shaped.push_back(r.axis[0].reference_mm);
    ASSERT_EQ(r.axis[0].unshaped_reference_mm, raw.back().position_mm);
    ASSERT_LT(raw.size(), 1000u);
  }
  const TapSet& taps = task.shaper_design(hal::Axis::x).taps;
  std::vector<AxisSample> offline(raw.size());
  shape_offline(taps, raw.data(), offline.data(), raw.size(), {kHomeMm, 0.0});
  for (std::size_t k = 0; k < raw.size(); ++k) ASSERT_EQ(shaped[k], offline[k].position_mm) << "motion tick " << k;
  EXPECT_GE(raw.size(), static_cast<std::size_t>(std::ceil(move.duration_s() / kPeriodS)) + taps.span())
      << "the motion lasts until the shaped tail is done";
  EXPECT_EQ(shaped.back(), kHomeMm - 3.0) << "end point exact";
}

// The supervisor checks the following error against the shaped reference
// (what the loop follows): a 10 Hz ZVDD delays the reference by 75 ms, far
// more than the speed-scaled limit allows against the unshaped command.
TEST_F(TickShaperTest, FollowingErrorIsMeasuredAgainstTheShapedReference) {
  ASSERT_EQ(task.configure_shaper(hal::Axis::x, {ShaperType::zvdd, {10.0, 0.0}, {0.0, 0.0}}), CommandStatus::ok);
  ASSERT_EQ(task.enable_shaper(hal::Axis::x, true), CommandStatus::ok);
  servo_on_holding();
  const FollowingErrorLimit& limit = task.config().supervisor.axis[0].following;
  ASSERT_EQ(task.start_move({hal::Axis::x, 20.0, 50.0, 0.02, 0.0}), CommandStatus::ok);
  double worst_unshaped_excess_mm = -1e9;
  while (task.state() == MotionState::moving) {
    tick();
    const AxisTickRecord& r = task.last_record().axis[0];
    worst_unshaped_excess_mm = std::fmax(worst_unshaped_excess_mm, std::fabs(r.unshaped_reference_mm - r.position_mm) -
                                                                       limit.at(r.reference_speed_mm_s));
  }
  EXPECT_EQ(task.state(), MotionState::holding) << "fault: " << to_string(task.fault().reason);
  EXPECT_GT(worst_unshaped_excess_mm, 1.0) << "mm beyond the limit: a delay-blind check would have tripped";
}

TEST_F(TickShaperTest, AShaperChangeWaitsUntilTheAxisIsAtRest) {
  ASSERT_EQ(task.configure_shaper(hal::Axis::x, {ShaperType::zv, {30.0, 0.0}, {0.0, 0.0}}), CommandStatus::ok);
  servo_on_holding();
  ASSERT_EQ(task.start_move({hal::Axis::x, 2.0, 20.0, 0.02, 0.0}), CommandStatus::ok);
  tick();
  tick();
  ASSERT_EQ(task.enable_shaper(hal::Axis::x, true), CommandStatus::ok) << "accepted while moving";
  while (task.state() == MotionState::moving) {
    tick();
    ASSERT_FALSE(task.shaper(hal::Axis::x).shaping()) << "switched on while moving";
    ASSERT_EQ(task.last_record().axis[0].reference_mm, task.last_record().axis[0].unshaped_reference_mm);
  }
  tick();
  tick();
  EXPECT_TRUE(task.shaper(hal::Axis::x).shaping()) << "applied once holding";
  EXPECT_EQ(task.last_record().axis[0].reference_mm, kHomeMm + 2.0);
}

TEST_F(TickShaperTest, ShaperCommandsValidateBeforeAnythingChanges) {
  EXPECT_EQ(task.enable_shaper(hal::Axis::y, true), CommandStatus::invalid) << "never configured";
  EXPECT_EQ(task.configure_shaper(hal::Axis::x, {ShaperType::zv, {std::nan(""), 0.0}, {0.0, 0.0}}),
            CommandStatus::invalid);
  EXPECT_EQ(task.configure_shaper(hal::Axis::x, {ShaperType::zv, {30.0, 0.0}, {300.0, 0.0}}), CommandStatus::invalid);
  EXPECT_EQ(task.enable_shaper(hal::Axis::x, true), CommandStatus::invalid) << "a refused design is not a design";
  EXPECT_EQ(task.enable_shaper(hal::Axis::x, false), CommandStatus::ok);
}

TEST_F(TickShaperTest, MoveCommandsAreRefusedWithAReason) {
  tick();
  EXPECT_EQ(task.start_move({hal::Axis::x, 0.0, 50.0, 0.02, 0.0}), CommandStatus::invalid);
  EXPECT_EQ(task.start_move({hal::Axis::x, 0.5, 50.0, 0.02, 0.0}), CommandStatus::invalid) << "ramps do not fit";
  EXPECT_EQ(task.start_move({hal::Axis::x, 300.0, 50.0, 0.02, 0.0}), CommandStatus::invalid) << "beyond +250 mm";
  EXPECT_EQ(task.start_move({hal::Axis::x, 5.0, INFINITY, 0.02, 0.0}), CommandStatus::invalid);
  EXPECT_EQ(task.state(), MotionState::disabled);
  EXPECT_STREQ(validate(MoveSpec{hal::Axis::x, 5.0, -1.0, 0.02, 0.0}), "speed_mm_s must be > 0 and finite");
  ASSERT_EQ(task.start_move({hal::Axis::y, -5.0, 50.0, 0.02, 0.1}), CommandStatus::ok) << "from servo-off";
  tick();
  EXPECT_EQ(task.state(), MotionState::dwell);
  EXPECT_EQ(task.start_move({hal::Axis::y, 5.0, 50.0, 0.02, 0.0}), CommandStatus::busy);
  EXPECT_EQ(task.jog(hal::Axis::x, 1.0), CommandStatus::busy);
}

TEST_F(TickShaperTest, JogFollowsTheOperatorAndTheDeadManStopsIt) {
  EXPECT_EQ(task.jog(hal::Axis::x, 10.0), CommandStatus::busy) << "servo off";
  servo_on_holding();
  EXPECT_EQ(task.jog(hal::Axis::x, std::nan("")), CommandStatus::invalid);
  EXPECT_EQ(task.jog(hal::Axis::x, 1e3), CommandStatus::invalid) << "beyond the jog speed limit";
  EXPECT_EQ(task.state(), MotionState::holding) << "a refused jog starts nothing";
  const JogLimits& lim = task.config().axis[0].jog;
  const double v = 20.0;
  // The pendant sends every tick for 0.3 s ...
  for (int k = 0; k < 300; ++k) {
    ASSERT_EQ(task.jog(hal::Axis::x, v), CommandStatus::ok);
    tick();
  }
  EXPECT_NEAR(task.last_record().axis[0].reference_speed_mm_s, v, 1e-9 * v) << "cruising at the jog speed";
  const double x_release = task.last_record().axis[0].reference_mm;
  // ... then goes silent: the axis brakes after deadman_s and holds.
  int ticks = 0;
  while (task.state() == MotionState::moving && ticks < 2000) {
    tick();
    ++ticks;
  }
  EXPECT_EQ(task.state(), MotionState::holding);
  EXPECT_EQ(task.jog_deadman_stops(), 1u);
  tick();  // the first holding tick: x_ref,k is the rest point
  const double coast_mm = task.last_record().axis[0].reference_mm - x_release;
  // The jog runs through the planner (docs/motion.md): the path point
  // coasts deadman_s, then brakes by dv = A dt per tick (A: the line's
  // rate, along an axis of equal axes path_accel_mm_s2); the reference
  // it is measured on trails the path point by the jerk filter's half
  // window plus the two ticks of look-ahead.
  const motion::DerivedLimits& d = task.motion().derived();
  const double dv = d.path_accel_mm_s2 * d.dt_s;
  const double brake_mm = motion::stop_distance_mm(v, dv, d.dt_s);
  const double lag_mm = v * d.dt_s * (0.5 * static_cast<double>(d.filter_taps - 1) + 2.0);
  const double expected_mm = v * lim.deadman_s + brake_mm + lag_mm;
  EXPECT_NEAR(coast_mm, expected_mm, v * 3.0 * kPeriodS) << "coasted deadman_s, then braked at the path acceleration";
  EXPECT_EQ(task.last_record().axis[0].reference_speed_mm_s, 0.0);
}

TEST_F(TickShaperTest, ShapedJogEndsExactlyWhereTheUnshapedJogDoes) {
  ASSERT_EQ(task.configure_shaper(hal::Axis::y, {ShaperType::zvdd, {25.0, 0.05}, {60.0, 0.05}}), CommandStatus::ok);
  ASSERT_EQ(task.enable_shaper(hal::Axis::y, true), CommandStatus::ok);
  servo_on_holding();
  double raw_end = 0.0;
  for (int k = 0; k < 400; ++k) {
    ASSERT_EQ(task.jog(hal::Axis::y, k < 150 ? -15.0 : (k < 250 ? 0.0 : 8.0)), CommandStatus::ok);
    tick();
  }
  ASSERT_EQ(task.jog(hal::Axis::y, 0.0), CommandStatus::ok);
  while (task.state() == MotionState::moving) {
    raw_end = task.last_record().axis[1].unshaped_reference_mm;
    tick();
  }
  EXPECT_EQ(task.state(), MotionState::holding);
  EXPECT_EQ(task.last_record().axis[1].reference_mm, raw_end);
  EXPECT_EQ(task.jog_deadman_stops(), 0u);
}

}  // namespace
}  // namespace tnv::fw

namespace tnv::fw {
namespace {

// Shaped axes stay in step: with a shaper on x only, a diagonal line of a
// program still runs exactly on its line (both axes are filtered alike),
// where shaping x alone would pull the start and the end off it.
TEST_F(TickShaperTest, ShapingOneAxisKeepsAProgrammedLineOnItsLine) {
  ASSERT_EQ(task.configure_shaper(hal::Axis::x, {ShaperType::zvd, {30.0, 0.05}, {0.0, 0.0}}), CommandStatus::ok);
  ASSERT_EQ(task.enable_shaper(hal::Axis::x, true), CommandStatus::ok);
  servo_on_holding();
  const motion::PlanePoint start{kHomeMm, 0.0};
  const motion::PlanePoint end{kHomeMm + 8.0, 6.0};
  motion::SegmentRefusal why = motion::SegmentRefusal::none;
  ASSERT_EQ(task.push_segment(motion::line_to(end, 20.0), why), CommandStatus::ok) << motion::to_string(why);
  ASSERT_EQ(task.end_program(), CommandStatus::ok);
  double worst_mm = 0.0;
  bool shaped_off_raw = false;
  int ticks = 0;
  while (task.state() != MotionState::holding && ticks < 5000) {
    tick();
    ++ticks;
    const TickRecord& r = task.last_record();
    const double x = r.axis[0].reference_mm - start[0];
    const double y = r.axis[1].reference_mm - start[1];
    worst_mm = std::max(worst_mm, std::fabs(x * 6.0 - y * 8.0) / 10.0);  // distance from the line through start
    shaped_off_raw = shaped_off_raw || r.axis[0].reference_mm != r.axis[0].unshaped_reference_mm;
  }
  ASSERT_EQ(task.state(), MotionState::holding);
  EXPECT_TRUE(shaped_off_raw) << "the shaper did act";
  EXPECT_LT(worst_mm, 1e-9) << "mm off the programmed line";
  EXPECT_NEAR(task.last_record().axis[0].reference_mm, end[0], 1e-9);
  EXPECT_NEAR(task.last_record().axis[1].reference_mm, end[1], 1e-9);
}

TEST_F(TickShaperTest, ASeriesThatDoesNotFitIsRefusedAndChangesNothing) {
  // Two two-mode ZVDD shapers at low frequencies: their series spans more
  // than the stream ring holds.
  const ShaperSpec slow_x{ShaperType::zvdd, {5.0, 0.3}, {6.0, 0.3}};
  const ShaperSpec slow_y{ShaperType::zvdd, {5.5, 0.3}, {7.0, 0.3}};
  ASSERT_EQ(task.configure_shaper(hal::Axis::x, slow_x), CommandStatus::ok);
  ASSERT_EQ(task.enable_shaper(hal::Axis::x, true), CommandStatus::ok);
  ASSERT_EQ(task.configure_shaper(hal::Axis::y, slow_y), CommandStatus::ok) << "y off: x alone fits";
  EXPECT_EQ(task.enable_shaper(hal::Axis::y, true), CommandStatus::invalid);
  servo_on_holding();
  EXPECT_FALSE(task.shaper_active(hal::Axis::y));
  EXPECT_TRUE(task.shaper_active(hal::Axis::x));
  EXPECT_NEAR(task.shaper_delay_s(hal::Axis::y), task.shaper_design(hal::Axis::x).delay_s(), 1e-12);
}

}  // namespace
}  // namespace tnv::fw
