// COMMAND home on the scriptable board: the cycle driven by the switch and
// index inputs to homed (heartbeat bits), and its refusals: bad axis, busy
// while moving, faulted, and motion refused before homing when
// homing.required is on (off by default).
#include <gtest/gtest.h>

#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::ErrorCode;
using fw::can::MessageId;

constexpr std::uint8_t kAxisAll = 255;

ErrorCode home_ack(const hal::CanFrame& r) {
  EXPECT_TRUE(is(r, MessageId::command_ack));
  return static_cast<ErrorCode>(raw_of(r, MessageId::command_ack, "result"));
}

fw::can::NodeSettings heartbeat_settings() {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry.heartbeat_ms = 5;
  return s;
}

// The axes field (homed and shaper bits) of the last heartbeat over 20
// ticks (frames the node queued before are sent first: the last one is from
// these ticks).
std::uint32_t heartbeat_axes(NodeBench& b) {
  std::vector<hal::CanFrame> hb;
  for (int i = 0; i < 20; ++i) {
    b.step();
    for (const hal::CanFrame& f : only(b.port.drain(), MessageId::heartbeat)) hb.push_back(f);
  }
  if (hb.empty()) {
    ADD_FAILURE() << "no heartbeat within 20 ticks";
    return 0;
  }
  return raw_of(hb.back(), MessageId::heartbeat, "axes");
}

// Walks X's cycle with the inputs: switch on at the start (the search ends
// at once), released after the stop, then one index edge latching `count`.
void walk_cycle(NodeBench& b, std::size_t axis, std::uint32_t count) {
  b.board.in.home_switch[axis] = true;
  b.step(3);  // search sees the switch, stops (already at rest), backs off
  b.board.in.home_switch[axis] = false;
  b.step();  // released
  b.board.index[axis] = {count, static_cast<std::uint8_t>(b.board.index[axis].edges + 1)};
  for (int i = 0; i < 10 && !b.task.homed(hal::axis_from_index(axis)); ++i) b.step();  // index edge, brake to rest
}

TEST(CanNodeHome, HomesOnTheIndexAfterTheSwitchAndTheHeartbeatSaysSo) {
  fw::can::NodeSettings s = heartbeat_settings();
  s.firmware.axis[0].homing.position_mm = -5.0;
  NodeBench b(s);
  b.port.drain();
  EXPECT_EQ(heartbeat_axes(b) & (fw::can::hb_homed_bit(hal::Axis::x) | fw::can::hb_homed_bit(hal::Axis::y)), 0u)
      << "not homed at power-up";
  b.port.drain();
  EXPECT_EQ(home_ack(b.reply(command(kNode, CommandCode::home, 0))), ErrorCode::ok);
  EXPECT_TRUE(b.task.homing());
  walk_cycle(b, 0, 65536 - 24);  // the index latched 24 counts below power-up's count 0 (16-bit wrap)
  ASSERT_FALSE(b.task.fault().active()) << fw::to_string(b.task.fault().reason);
  EXPECT_EQ(b.task.state(), fw::MotionState::holding);
  EXPECT_TRUE(b.task.homed(hal::Axis::x));
  EXPECT_FALSE(b.task.homed(hal::Axis::y));
  EXPECT_EQ(b.task.homing_result(hal::Axis::x), fw::HomingResult::homed);
  // The table stands at count 0, 24 counts above the index: home + 24 q.
  const double q = s.firmware.axis[0].count_mm;
  EXPECT_NEAR(b.task.last_record().axis[0].position_mm, -5.0 + 24.0 * q, 1e-9);
  const std::uint32_t bits = heartbeat_axes(b);
  EXPECT_NE(bits & fw::can::hb_homed_bit(hal::Axis::x), 0u);
  EXPECT_EQ(bits & fw::can::hb_homed_bit(hal::Axis::y), 0u);
}

TEST(CanNodeHome, AllHomesZThenXThenY) {
  constexpr std::size_t kX = hal::index(hal::Axis::x), kY = hal::index(hal::Axis::y), kZ = hal::index(hal::Axis::z);
  // The fake table cannot move: the homed head holds a few um off its
  // reference while X homes, and its DDC winds up against the rigid fake
  // (a stall after 4 ticks). The order is what this test is about.
  fw::can::NodeSettings s = quiet_settings();
  s.firmware.supervisor.axis[kZ].stall.ticks = 1000;
  NodeBench b(s);
  b.board.in.home_switch[kX] = true;  // x's and y's searches end at once too (the fake table cannot move to them)
  b.board.in.home_switch[kY] = true;
  EXPECT_EQ(home_ack(b.reply(command(kNode, CommandCode::home, kAxisAll))), ErrorCode::ok);
  walk_cycle(b, kZ, 100);
  ASSERT_FALSE(b.task.fault().active()) << fw::to_string(b.task.fault().reason) << " axis " << int(b.task.fault().axis);
  EXPECT_TRUE(b.task.homed(hal::Axis::z)) << "z first";
  EXPECT_FALSE(b.task.homed(hal::Axis::x));
  EXPECT_FALSE(b.task.homed(hal::Axis::y));
  EXPECT_TRUE(b.task.homing()) << "x follows z";
  b.board.in.home_switch[kX] = true;
  walk_cycle(b, kX, 100);
  ASSERT_FALSE(b.task.fault().active()) << fw::to_string(b.task.fault().reason) << " axis " << int(b.task.fault().axis);
  EXPECT_TRUE(b.task.homed(hal::Axis::x));
  EXPECT_TRUE(b.task.homing()) << "y follows x";
  walk_cycle(b, 1, 200);
  EXPECT_TRUE(b.task.homed(hal::Axis::y));
  EXPECT_EQ(b.task.state(), fw::MotionState::holding);
}

TEST(CanNodeHome, RefusesABadAxisWhileMovingAndWhenFaulted) {
  NodeBench b;
  const hal::CanFrame bad = b.reply(command(kNode, CommandCode::home, static_cast<std::uint8_t>(hal::kAxisCount)));
  EXPECT_EQ(home_ack(bad), ErrorCode::bad_axis);
  EXPECT_EQ(raw_of(bad, MessageId::command_ack, "detail"), 2u) << "the axis field";
  EXPECT_EQ(b.task.state(), fw::MotionState::disabled) << "a refused home starts nothing";

  EXPECT_EQ(home_ack(b.reply(command(kNode, CommandCode::home, 1))), ErrorCode::ok);
  b.step();
  EXPECT_EQ(home_ack(b.reply(command(kNode, CommandCode::home, 0))), ErrorCode::busy);
  EXPECT_EQ(home_ack(b.reply(command(kNode, CommandCode::zero, 1, 0, 1.0))), ErrorCode::busy);
  EXPECT_EQ(home_ack(b.reply(command(kNode, CommandCode::stop))), ErrorCode::ok);
  b.step(20);
  EXPECT_EQ(b.task.state(), fw::MotionState::holding) << "stop ends the cycle at rest";
  EXPECT_FALSE(b.task.homed(hal::Axis::y));
  EXPECT_EQ(b.task.homing_result(hal::Axis::y), fw::HomingResult::aborted);

  b.request(frame_to(MessageId::estop, kNode));
  b.step();
  EXPECT_EQ(home_ack(b.reply(command(kNode, CommandCode::home, kAxisAll))), ErrorCode::faulted);
}

TEST(CanNodeHome, MotionRefusedBeforeHomingWhenRequired) {
  fw::can::NodeSettings s = quiet_settings();
  s.firmware.homing_required = true;
  NodeBench b(s);
  b.reply(command(kNode, CommandCode::enable));
  EXPECT_EQ(home_ack(b.reply(circle(kNode, 6.0, 2.0))), ErrorCode::not_homed);
  EXPECT_EQ(b.task.start_move({hal::Axis::y, 1.0, 5.0, 0.02, 0.0}), fw::CommandStatus::not_homed);
  EXPECT_EQ(b.task.jog(hal::Axis::x, 1.0), fw::CommandStatus::ok) << "the operator may jog before homing";
  b.task.stop();
  b.step(50);
  ASSERT_EQ(b.task.state(), fw::MotionState::holding);
  EXPECT_EQ(home_ack(b.reply(command(kNode, CommandCode::home, 1))), ErrorCode::ok);
  walk_cycle(b, 1, 0);
  ASSERT_TRUE(b.task.homed(hal::Axis::y));
  EXPECT_EQ(b.task.start_move({hal::Axis::x, 1.0, 5.0, 0.02, 0.0}), fw::CommandStatus::not_homed) << "x is not";
  EXPECT_EQ(b.task.start_move({hal::Axis::y, 1.0, 5.0, 0.02, 0.0}), fw::CommandStatus::ok) << "y is homed";
}

TEST(CanNodeHome, HomingRequiredIsOffByDefaultAndSetAtRest) {
  NodeBench b;
  EXPECT_EQ(b.param("homing.required"), 0.0);
  const hal::CanFrame set = b.reply(param_request(kNode, fw::can::ParamOp::set, id_of("homing.required"), 1));
  EXPECT_EQ(static_cast<ErrorCode>(raw_of(set, MessageId::param_reply, "result")), ErrorCode::ok);
  EXPECT_TRUE(b.task.config().homing_required) << "applied to the tick task";
  EXPECT_EQ(NodeBench::find("x.homing.search_mm_s").get(b.node->settings()), 10.0);
  EXPECT_EQ(NodeBench::find("y.homing.latch_mm_s").get(b.node->settings()), 1.0);
}

}  // namespace
}  // namespace tnv::test
