// Probe moves in the tick task with a fake probe input on a perfect servo
// (the table stands where the last tick's reference was): the trip stops
// the move, the measured position is latched in the tick whose snapshot
// showed the change, each kind's outcome is reported, an error stops the
// program, a probe already tripped is refused, and a probe needs homing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "firmware/tick/tick_task.hpp"
#include "tests/firmware/fake_io_board.hpp"
#include "tests/firmware/test_units.hpp"

namespace tnv::fw {
namespace {

using test_units::kCountMm;
using test_units::kPeriodS;
constexpr std::size_t kZ = hal::index(hal::Axis::z);
constexpr double kContactZ_mm = -3.0;  // the fake stock's top
constexpr double kFeed_mm_s = 5.0;

class TickProbeTest : public ::testing::Test {
 protected:
  TickProbeTest() : task(board, make_config(false)) {}

  static FirmwareConfig make_config(bool homing_required) {
    FirmwareConfig c = default_firmware_config();
    for (auto& a : c.axis) a.home_position_mm = 0.0;
    for (auto& a : c.supervisor.axis) a.stall.command_mm_s = 1e4;  // the fake table ignores the DAC
    c.homing_required = homing_required;
    return c;
  }

  // The snapshot holds the table where the last tick's reference was and
  // the probe touching when Z is at or below the contact (toward) or, with
  // `away`, above it.
  void tick() {
    board.next_tick();
    const double z_mm = static_cast<double>(static_cast<std::int32_t>(board.counts[kZ])) * kCountMm;
    board.in.probe = touching_override ? *touching_override : z_mm <= kContactZ_mm;
    task.tick();
    for (std::size_t i = 0; i < hal::kAxisCount; ++i)
      board.counts[i] = static_cast<std::uint32_t>(std::lround(task.last_record().axis[i].reference_mm / kCountMm));
  }

  void servo_on_holding() {
    tick();
    ASSERT_EQ(task.hold_position(), CommandStatus::ok);
    tick();
    ASSERT_EQ(task.state(), MotionState::holding);
  }

  // Ticks until a new probe report (or the limit); true if one came.
  bool tick_until_report(std::uint32_t count_before, int limit = 20'000) {
    for (int k = 0; k < limit; ++k) {
      tick();
      if (task.probe_report().count != count_before) return true;
    }
    return false;
  }

  motion::Segment probe_down(motion::ProbeKind kind, double to_z_mm, std::uint32_t tag = 12) const {
    motion::PlanePoint end = task.next_segment_start_mm();
    end[kZ] = to_z_mm;
    return motion::probe_to(kind, end, kFeed_mm_s, tag);
  }

  tnv::test::FakeIoBoard board;
  TickTask task;
  std::optional<bool> touching_override;
};

TEST_F(TickProbeTest, TheTripStopsTheMoveAndLatchesThePositionOfTheTickThatSawIt) {
  servo_on_holding();
  motion::SegmentRefusal why{};
  ASSERT_EQ(task.push_segment(probe_down(motion::ProbeKind::toward_or_error, -10.0), why), CommandStatus::ok)
      << motion::to_string(why);
  ASSERT_TRUE(tick_until_report(0));
  const ProbeReport& p = task.probe_report();
  EXPECT_EQ(p.outcome, motion::ProbeOutcome::tripped);
  EXPECT_EQ(p.tag, 12u);
  // The snapshot that showed the contact held the table at or below it,
  // the one before above it: at most one tick's travel at the feed past it
  // (and a count's rounding).
  EXPECT_LE(p.trip_mm[kZ], kContactZ_mm + kCountMm);
  EXPECT_GE(p.trip_mm[kZ], kContactZ_mm - kFeed_mm_s * kPeriodS - kCountMm)
      << (kContactZ_mm - p.trip_mm[kZ]) * 1e3 << " um past the contact";
  EXPECT_LT(p.rest_mm[kZ], p.trip_mm[kZ]) << "it braked after the trip, so it rests beyond it";
  EXPECT_GT(p.rest_mm[kZ], -4.0) << "the rest of the move was not dropped";
  EXPECT_TRUE(task.program_running()) << "a trip is a success: the program goes on";
  EXPECT_NEAR(task.next_segment_start_mm()[kZ], p.rest_mm[kZ], 1e-12);
  // The program goes on: back up and end.
  motion::PlanePoint up = task.next_segment_start_mm();
  up[kZ] = 0.0;
  ASSERT_EQ(task.push_segment(motion::line_to(up, 20.0), why), CommandStatus::ok) << motion::to_string(why);
  ASSERT_EQ(task.end_program(), CommandStatus::ok);
  for (int k = 0; k < 5000 && task.state() != MotionState::holding; ++k) tick();
  EXPECT_EQ(task.state(), MotionState::holding);
  EXPECT_EQ(task.probe_report().count, 1u);
}

TEST_F(TickProbeTest, EachKindWithoutATripEndsAsItDemands) {
  struct Case {
    motion::ProbeKind kind;
    bool touching;  // held: never the tripping state
    motion::ProbeOutcome outcome;
  };
  servo_on_holding();
  std::uint32_t count = 0;
  for (const Case c : {Case{motion::ProbeKind::toward, false, motion::ProbeOutcome::not_tripped},
                       Case{motion::ProbeKind::away, true, motion::ProbeOutcome::not_tripped},
                       Case{motion::ProbeKind::toward_or_error, false, motion::ProbeOutcome::failed},
                       Case{motion::ProbeKind::away_or_error, true, motion::ProbeOutcome::failed}}) {
    SCOPED_TRACE(motion::to_string(c.outcome));
    touching_override = c.touching;
    const double from_z = task.next_segment_start_mm()[kZ];
    motion::SegmentRefusal why{};
    ASSERT_EQ(task.push_segment(probe_down(c.kind, from_z - 1.0), why), CommandStatus::ok) << motion::to_string(why);
    ASSERT_TRUE(tick_until_report(count));
    count = task.probe_report().count;
    EXPECT_EQ(task.probe_report().outcome, c.outcome);
    EXPECT_NEAR(task.probe_report().rest_mm[kZ], from_z - 1.0, 1e-9) << "it ran to its end";
    EXPECT_EQ(task.probe_report().trip_mm, task.probe_report().rest_mm);
    if (motion::is_error(c.outcome)) {
      // The program stops: nothing after it runs, and nothing more is taken.
      for (int k = 0; k < 100 && task.state() != MotionState::holding; ++k) tick();
      EXPECT_EQ(task.state(), MotionState::holding);
      EXPECT_FALSE(task.program_running());
    } else {
      EXPECT_TRUE(task.program_running());
      ASSERT_EQ(task.end_program(), CommandStatus::ok);
      for (int k = 0; k < 100 && task.state() != MotionState::holding; ++k) tick();
    }
  }
}

TEST_F(TickProbeTest, RefusedWhenTheInputIsAlreadyTrippedAndTheProgramStops) {
  servo_on_holding();
  touching_override = true;
  const double z0 = task.next_segment_start_mm()[kZ];
  motion::SegmentRefusal why{};
  ASSERT_EQ(task.push_segment(probe_down(motion::ProbeKind::toward, z0 - 5.0), why), CommandStatus::ok);
  ASSERT_TRUE(tick_until_report(0));
  EXPECT_EQ(task.probe_report().outcome, motion::ProbeOutcome::already_tripped);
  for (int k = 0; k < 100 && task.state() != MotionState::holding; ++k) tick();
  EXPECT_EQ(task.state(), MotionState::holding);
  EXPECT_EQ(task.last_record().axis[kZ].reference_mm, z0) << "it moved";
}

TEST_F(TickProbeTest, NothingIsTakenBehindAProbeUntilItsOutcome) {
  servo_on_holding();
  motion::SegmentRefusal why{};
  ASSERT_EQ(task.push_segment(probe_down(motion::ProbeKind::toward, -10.0), why), CommandStatus::ok);
  motion::PlanePoint next = task.next_segment_start_mm();
  next[0] += 1.0;
  EXPECT_EQ(task.push_segment(motion::line_to(next, 20.0), why), CommandStatus::invalid);
  EXPECT_EQ(why, motion::SegmentRefusal::probe_pending);
  EXPECT_EQ(task.motion().queued(), 1u);
}

TEST(TickProbe, AProbeNeedsHomingLikeAnyMotion) {
  tnv::test::FakeIoBoard board;
  FirmwareConfig c = default_firmware_config();
  c.homing_required = true;
  TickTask task(board, c);
  board.next_tick();
  task.tick();
  ASSERT_EQ(task.hold_position(), CommandStatus::ok);
  board.next_tick();
  task.tick();
  motion::PlanePoint end = task.next_segment_start_mm();
  end[kZ] -= 5.0;
  motion::SegmentRefusal why{};
  EXPECT_EQ(task.push_segment(motion::probe_to(motion::ProbeKind::toward, end, kFeed_mm_s), why),
            CommandStatus::not_homed);
  EXPECT_EQ(task.motion().queued(), 0u);
}

}  // namespace
}  // namespace tnv::fw
