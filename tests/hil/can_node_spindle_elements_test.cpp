// A program's spindle commands as SEGMENT frames on the node: one frame
// each, accepted into the queue in program order; a start above the
// spindle's max_rpm is refused out_of_range naming SEGMENT.x, and the
// queue is left as it was. While a program is active a SPINDLE start or
// speed from the side is refused busy (the program's elements command the
// spindle); a SPINDLE stop is always taken.
#include <gtest/gtest.h>

#include "tests/hil/program_frames.hpp"

namespace tnv::test {
namespace {

namespace can = fw::can;
using can::MessageId;
namespace fld = can::fields;

TEST(CanNodeSpindleElements, OneFrameEachAndAStartAboveMaxRpmIsRefusedNamingX) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  const double max_rpm = r->task().spindle().params().max_rpm;
  const std::vector<ElementAck> ok =
      host.send(fw::motion::spindle_here(fw::motion::SpindleChange::reverse, 0.5 * max_rpm));
  ASSERT_EQ(ok.size(), 1u);
  EXPECT_EQ(ok[0].result, kOk);
  EXPECT_EQ(ok[0].request, static_cast<std::uint32_t>(MessageId::segment)) << "no SEGMENT_TAIL for a spindle command";
  EXPECT_EQ(r->task().motion().queued(), 1u);
  const std::vector<ElementAck> refused =
      host.send(fw::motion::spindle_here(fw::motion::SpindleChange::forward, 1.5 * max_rpm));
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(refused[0].result, static_cast<std::uint32_t>(can::ErrorCode::out_of_range));
  EXPECT_EQ(refused[0].detail, fld::index_of(fld::kSegmentMsg, fld::kSegmentX));
  EXPECT_EQ(r->task().motion().queued(), 1u) << "the refusal changed the queue";
  EXPECT_EQ(host.send(fw::motion::spindle_here(fw::motion::SpindleChange::stop, 0.0)).at(0).result, kOk);
  EXPECT_EQ(r->task().motion().queued(), 2u);
}

hal::CanFrame spindle_request(fw::can::SpindleOp op, double rpm) {
  hal::CanFrame f = frame_to(MessageId::spindle, kRigNode);
  set_raw(f, MessageId::spindle, "op", static_cast<std::uint32_t>(op));
  set_raw(f, MessageId::spindle, "direction", 0);
  set_value(f, MessageId::spindle, "rpm", rpm);
  return f;
}

TEST(CanNodeSpindleElements, DuringAProgramOnlyAStopIsTakenFromTheSide) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  ASSERT_EQ(host.send(fw::motion::dwell_for(5.0)).at(0).result, kOk);  // the program is running
  const double rpm = 0.5 * r->task().spindle().params().max_rpm;
  EXPECT_EQ(ack_result(*r, spindle_request(fw::can::SpindleOp::start, rpm)),
            static_cast<std::uint32_t>(can::ErrorCode::busy));
  EXPECT_EQ(ack_result(*r, spindle_request(fw::can::SpindleOp::speed, rpm)),
            static_cast<std::uint32_t>(can::ErrorCode::busy));
  for (int k = 0; k < 20; ++k) r->step();
  EXPECT_FALSE(r->task().spindle().commanded_on()) << "a start from the side turned the spindle during a program";
  EXPECT_EQ(ack_result(*r, spindle_request(fw::can::SpindleOp::stop, 0.0)), kOk);
  // The same start once the program is aborted: taken (the refusal was the program's).
  ASSERT_EQ(ack_result(*r, command(kRigNode, fw::can::CommandCode::abort_program)), kOk);
  ASSERT_TRUE(r->run_until(fw::MotionState::holding, 100));  // an abort ends the dwell
  for (int k = 0; k < 2; ++k) r->step();
  ASSERT_EQ(r->node->program().state(), can::ProgramState::aborted);
  EXPECT_EQ(ack_result(*r, spindle_request(fw::can::SpindleOp::start, rpm)), kOk);
}

}  // namespace
}  // namespace tnv::test
