// A program pause (SEGMENT kind pause: M0, M1, M6) on the node over CAN:
// the node reaches it at rest, reports PROGRAM_STATUS paused naming the
// pause element, holds there, and goes on only on COMMAND cycle_start from
// the command owner; cycle_start is refused (not_ready) when nothing is
// paused; an abort while paused ends the program where it rests; a silent
// host's timeout while paused stops everything. A tool change (SEGMENT kind
// tool_change) is such a pause that tells the node its tool: PROGRAM_TOOL
// says unknown from start-up and during the change, the tool once
// cycle_start continues it, unknown again after a change left unconfirmed,
// and a restarted node does not know it.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/hil/program_frames.hpp"

namespace tnv::test {
namespace {

namespace can = fw::can;
using can::CommandCode;
using can::ErrorCode;
using can::MessageId;
using fw::motion::PlanePoint;

constexpr auto error_code(ErrorCode e) { return static_cast<std::uint32_t>(e); }

PlanePoint moved_by(const PlanePoint& p, double dx, double dy) { return {p[0] + dx, p[1] + dy}; }

// line 3 mm, pause, line 3 mm; the program ended. Returns the pause's end point (where it rests).
PlanePoint send_line_pause_line(CanRig& r, ProgramHost& host) {
  const PlanePoint start = host.at_mm();
  EXPECT_EQ(host.send(fw::motion::line_to(moved_by(start, 3.0, 0.0), 10.0)).at(0).result, kOk);
  const std::vector<ElementAck> acks = host.send(fw::motion::pause_here());
  EXPECT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks.at(0).result, kOk);
  EXPECT_EQ(acks.at(0).request, static_cast<std::uint32_t>(MessageId::segment)) << "a pause has no tail";
  EXPECT_EQ(host.send(fw::motion::line_to(moved_by(start, 3.0, 3.0), 10.0)).at(0).result, kOk);
  EXPECT_EQ(ack_result(r, command(kRigNode, CommandCode::end_program)), kOk);
  return moved_by(start, 3.0, 0.0);
}

bool run_until_paused(CanRig& r, int limit = 20000) {
  for (int k = 0; k < limit; ++k) {
    if (r.node->program().state() == can::ProgramState::paused) return true;
    r.step();
  }
  return false;
}

PlanePoint reference(CanRig& r) {
  return {r.task().last_record().axis[0].reference_mm, r.task().last_record().axis[1].reference_mm};
}

TEST(CanNodePause, ReachedAtRestReportedPausedAndHeldUntilCycleStart) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::cycle_start)), error_code(ErrorCode::busy)) << "no program";
  const PlanePoint pause_at = send_line_pause_line(*r, host);
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::cycle_start)), error_code(ErrorCode::not_ready))
      << "still on the way to the pause";
  r->port.drain();
  ASSERT_TRUE(run_until_paused(*r)) << "never paused";
  // The change to paused went out as a PROGRAM_STATUS naming element 2, the pause.
  const std::vector<hal::CanFrame> status = only(r->port.drain(), MessageId::program_status);
  ASSERT_FALSE(status.empty());
  EXPECT_EQ(raw_of(status.back(), MessageId::program_status, "state"), static_cast<std::uint32_t>(can::ProgramState::paused));
  EXPECT_EQ(raw_of(status.back(), MessageId::program_status, "segment"), 2u);
  EXPECT_LT(std::hypot(reference(*r)[0] - pause_at[0], reference(*r)[1] - pause_at[1]), 1e-9);
  for (int k = 0; k < 3000; ++k) r->step();  // three seconds: it waits, whatever feed_resume says
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::feed_resume)), kOk);
  for (int k = 0; k < 100; ++k) r->step();
  EXPECT_EQ(r->node->program().state(), can::ProgramState::paused);
  EXPECT_LT(std::hypot(reference(*r)[0] - pause_at[0], reference(*r)[1] - pause_at[1]), 1e-9) << "it moved";
  EXPECT_EQ(r->task().state(), fw::MotionState::moving) << "a pause is part of the running program";

  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::cycle_start)), kOk);
  ASSERT_TRUE(r->run_until(fw::MotionState::holding, 20000));
  for (int k = 0; k < 2; ++k) r->step();
  EXPECT_EQ(r->node->program().state(), can::ProgramState::done);
  EXPECT_NEAR(reference(*r)[1], pause_at[1] + 3.0, 1e-6) << "the line after the pause ran";
}

// The tool in the PROGRAM_TOOL frames that went out, in order.
std::vector<std::int32_t> tools_reported(const std::vector<hal::CanFrame>& frames) {
  std::vector<std::int32_t> tools;
  for (const hal::CanFrame& f : only(frames, MessageId::program_tool))
    tools.push_back(static_cast<std::int32_t>(value_of(f, MessageId::program_tool, "tool")));
  return tools;
}

// line 3 mm, tool change to `tool`, line back; the program ended.
void send_tool_change_program(CanRig& r, ProgramHost& host, int tool) {
  const PlanePoint start = host.at_mm();
  EXPECT_EQ(host.send(fw::motion::line_to(moved_by(start, 3.0, 0.0), 10.0)).at(0).result, kOk);
  const std::vector<ElementAck> acks = host.send_tool_change(tool);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks.at(0).result, kOk);
  EXPECT_EQ(host.send(fw::motion::line_to(start, 10.0)).at(0).result, kOk);
  EXPECT_EQ(ack_result(r, command(kRigNode, CommandCode::end_program)), kOk);
}

TEST(CanNodePause, AToolChangeTellsTheNodeItsToolOnceContinued) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  EXPECT_EQ(tools_reported(r->request(command(kRigNode, CommandCode::program_status))), std::vector<std::int32_t>{-1})
      << "a node just started knows no tool";
  ProgramHost host(*r);
  send_tool_change_program(*r, host, 7);
  r->port.drain();
  ASSERT_TRUE(run_until_paused(*r));
  EXPECT_EQ(r->node->tool_in_spindle(), -1) << "changing: the operator may have taken the old one out";
  EXPECT_EQ(tools_reported(r->port.drain()).back(), -1);
  for (int k = 0; k < 500; ++k) r->step();
  EXPECT_EQ(r->node->tool_in_spindle(), -1) << "known before the operator confirmed it";
  const std::vector<hal::CanFrame> after = r->request(command(kRigNode, CommandCode::cycle_start));
  EXPECT_EQ(tools_reported(after), std::vector<std::int32_t>{7}) << "the new tool goes out with the cycle start";
  ASSERT_TRUE(r->run_until(fw::MotionState::holding, 20000));
  for (int k = 0; k < 2; ++k) r->step();
  EXPECT_EQ(r->node->program().state(), can::ProgramState::done);
  r->port.drain();
  EXPECT_EQ(tools_reported(r->request(command(kRigNode, CommandCode::program_status))), std::vector<std::int32_t>{7});

  // A plain pause (M0) changes nothing; a change aborted at its pause leaves the tool unknown, not 7 nor 9.
  r->port.drain();
  send_line_pause_line(*r, host);
  ASSERT_TRUE(run_until_paused(*r));
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::cycle_start)), kOk);
  ASSERT_TRUE(r->run_until(fw::MotionState::holding, 20000));
  for (int k = 0; k < 2; ++k) r->step();
  EXPECT_EQ(r->node->tool_in_spindle(), 7);
  send_tool_change_program(*r, host, 9);
  ASSERT_TRUE(run_until_paused(*r));
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::abort_program)), kOk);
  ASSERT_TRUE(r->run_until(fw::MotionState::holding, 2000));
  for (int k = 0; k < 2; ++k) r->step();
  EXPECT_EQ(r->node->program().state(), can::ProgramState::aborted);
  EXPECT_EQ(r->node->tool_in_spindle(), -1);
  r->port.drain();
  EXPECT_EQ(tools_reported(r->request(command(kRigNode, CommandCode::program_status))), std::vector<std::int32_t>{-1});

  // A node that starts again does not know it either: nothing of it is stored.
  auto again = holding_rig();
  ASSERT_TRUE(again);
  EXPECT_EQ(again->node->tool_in_spindle(), -1);
}

// A tool change right after another pause (M0 then M6 with no move between):
// the node still says unknown while the change waits, then the new tool.
TEST(CanNodePause, AToolChangeRightAfterAnotherPauseIsStillUnknownUntilContinued) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  send_tool_change_program(*r, host, 3);
  ASSERT_TRUE(run_until_paused(*r));
  ASSERT_EQ(ack_result(*r, command(kRigNode, CommandCode::cycle_start)), kOk);
  ASSERT_TRUE(r->run_until(fw::MotionState::holding, 20000));
  for (int k = 0; k < 2; ++k) r->step();
  ASSERT_EQ(r->node->tool_in_spindle(), 3);

  const PlanePoint start = host.at_mm();
  ASSERT_EQ(host.send(fw::motion::pause_here()).at(0).result, kOk);
  ASSERT_EQ(host.send_tool_change(4).at(0).result, kOk);
  ASSERT_EQ(host.send(fw::motion::line_to(moved_by(start, 1.0, 0.0), 10.0)).at(0).result, kOk);
  ASSERT_EQ(ack_result(*r, command(kRigNode, CommandCode::end_program)), kOk);
  ASSERT_TRUE(run_until_paused(*r));
  EXPECT_EQ(r->node->program().element(r->task()), 1u);
  EXPECT_EQ(r->node->tool_in_spindle(), 3) << "a plain pause leaves the tool known";
  ASSERT_EQ(ack_result(*r, command(kRigNode, CommandCode::cycle_start)), kOk);
  int k = 0;
  for (; k < 20000 && r->node->program().element(r->task()) != 2u; ++k) r->step();
  for (int j = 0; j < 50; ++j) r->step();
  ASSERT_EQ(r->node->program().state(), can::ProgramState::paused);
  EXPECT_EQ(r->node->program().element(r->task()), 2u);
  EXPECT_EQ(r->node->tool_in_spindle(), -1) << "tool 3 claimed while it is being changed for 4";
  ASSERT_EQ(ack_result(*r, command(kRigNode, CommandCode::cycle_start)), kOk);
  EXPECT_EQ(r->node->tool_in_spindle(), 4);
}

TEST(CanNodePause, ANegativeToolIsRefusedNamingX) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  const std::vector<ElementAck> acks = host.send_tool_change(-1);
  ASSERT_EQ(acks.size(), 1u);
  EXPECT_EQ(acks[0].result, error_code(ErrorCode::out_of_range));
  EXPECT_EQ(acks[0].detail, static_cast<std::uint32_t>(can::fields::index_of(can::fields::kSegmentMsg, can::fields::kSegmentX)));
  EXPECT_EQ(r->task().motion().queued(), 0u) << "nothing was queued";
}

TEST(CanNodePause, OnlyTheOwnerContinues) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  send_line_pause_line(*r, host);
  ASSERT_TRUE(run_until_paused(*r));
  EXPECT_EQ(ack_result(*r, with_tag(command(kRigNode, CommandCode::cycle_start), 0x21)), error_code(ErrorCode::not_owner))
      << "host 2 does not own the node";
  for (int k = 0; k < 200; ++k) r->step();
  EXPECT_EQ(r->node->program().state(), can::ProgramState::paused);
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::cycle_start)), kOk);
  for (int k = 0; k < 50; ++k) r->step();
  EXPECT_NE(r->node->program().state(), can::ProgramState::paused);
}

TEST(CanNodePause, AnAbortWhilePausedEndsTheProgramWhereItRests) {
  auto r = holding_rig();
  ASSERT_TRUE(r);
  ProgramHost host(*r);
  const PlanePoint pause_at = send_line_pause_line(*r, host);
  ASSERT_TRUE(run_until_paused(*r));
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::abort_program)), kOk);
  ASSERT_TRUE(r->run_until(fw::MotionState::holding, 2000));
  for (int k = 0; k < 2; ++k) r->step();
  EXPECT_EQ(r->node->program().state(), can::ProgramState::aborted);
  EXPECT_EQ(r->task().motion().queued(), 0u);
  EXPECT_LT(std::hypot(reference(*r)[0] - pause_at[0], reference(*r)[1] - pause_at[1]), 1e-9);
  EXPECT_EQ(ack_result(*r, command(kRigNode, CommandCode::cycle_start)), error_code(ErrorCode::busy)) << "nothing to continue";
}

TEST(CanNodePause, ASilentHostWhilePausedStopsEverything) {
  auto r = CanRig::make();
  ASSERT_TRUE(r);
  ASSERT_EQ(r->result(command(kRigNode, CommandCode::enter_commissioning)), kOk);  // a safety parameter, while disabled
  ASSERT_EQ(r->result(param_request(kRigNode, can::ParamOp::set, param_id("can.host_timeout_ms"), 300)), kOk);
  ASSERT_EQ(r->result(command(kRigNode, CommandCode::enable)), kOk);
  for (int k = 0; k < 5; ++k) r->step();
  r->port.drain();
  ProgramHost host(*r);
  const PlanePoint pause_at = send_line_pause_line(*r, host);
  // The host keeps talking (program_status) until the pause, then falls silent.
  for (int k = 0; k < 20000 && r->node->program().state() != can::ProgramState::paused; ++k) {
    if (k % 100 == 0) r->port.send(command(kRigNode, CommandCode::program_status));
    r->step();
  }
  ASSERT_EQ(r->node->program().state(), can::ProgramState::paused);
  for (int k = 0; k < 1000; ++k) r->step();
  EXPECT_NE(r->node->heartbeat_errors() & can::kHbHostTimeout, 0);
  EXPECT_EQ(r->node->program().state(), can::ProgramState::aborted);
  EXPECT_EQ(r->task().state(), fw::MotionState::holding);
  EXPECT_EQ(r->task().motion().queued(), 0u);
  EXPECT_LT(std::hypot(reference(*r)[0] - pause_at[0], reference(*r)[1] - pause_at[1]), 1e-9);
  EXPECT_FALSE(r->task().fault().active());
}

}  // namespace
}  // namespace tnv::test
