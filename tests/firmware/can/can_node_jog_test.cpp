// JOG names its axis (protocol 5): each frame drives one axis' stream and
// no other axis, and a frame for an axis the list does not have is refused
// with bad_axis and changes nothing (can_node_malformed_test.cpp checks the
// refusal's ack and the unchanged node for every such frame).
#include <gtest/gtest.h>

#include "firmware/can/node_fields.hpp"
#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::ErrorCode;
using fw::can::MessageId;

// A few ticks only: the fake board's table stands, so a longer jog ends in a following-error fault.
TEST(CanNodeJog, AFrameJogsTheAxisItNamesAndNoOther) {
  for (const hal::Axis jogged : hal::kAxes) {
    SCOPED_TRACE(hal::axis_label(jogged));
    NodeBench b;
    ASSERT_EQ(ack_result(b.reply(command(kNode, CommandCode::enable))), ErrorCode::ok);
    b.step(5);
    const fw::TickRecord before = b.task.last_record();
    const auto j = static_cast<std::uint8_t>(hal::index(jogged));
    for (int k = 0; k < 8; ++k) {  // 8 ms of a -0.5 mm/s stream, one frame per tick
      ASSERT_EQ(ack_result(b.reply(jog(kNode, j, -0.5))), ErrorCode::ok) << "tick " << k;
      b.step();
    }
    EXPECT_TRUE(b.task.jogging());
    EXPECT_FALSE(b.task.fault().active());
    for (const hal::Axis a : hal::kAxes) {
      const std::size_t i = hal::index(a);
      if (a == jogged) {
        EXPECT_LT(b.task.last_record().axis[i].reference_mm, before.axis[i].reference_mm - 1e-7) << "it moves down";
      } else {
        EXPECT_EQ(b.task.last_record().axis[i].reference_mm, before.axis[i].reference_mm)
            << hal::axis_label(a) << " has no stream: it holds";
      }
    }
  }
}

TEST(CanNodeJog, AnAxisBeyondTheListIsRefusedAndNothingMoves) {
  NodeBench b(quiet_settings());
  ASSERT_EQ(ack_result(b.reply(command(kNode, CommandCode::enable))), ErrorCode::ok);
  b.step(5);
  const hal::CanFrame r = b.reply(jog(kNode, static_cast<std::uint8_t>(hal::kAxisCount), 5.0));
  EXPECT_EQ(ack_result(r), ErrorCode::bad_axis);
  EXPECT_EQ(ack_detail(r), fw::can::fields::index_of(fw::can::fields::kJogMsg, fw::can::fields::kJogAxis))
      << "detail names the axis field";
  b.step(20);
  EXPECT_FALSE(b.task.jogging());
  EXPECT_EQ(b.task.state(), fw::MotionState::holding);
}

}  // namespace
}  // namespace tnv::test
