// COMMAND at rest: enable / disable / stop / zero / e-stop / clear, the
// storage commands, node id and broadcast handling, the answer sequence.
#include <gtest/gtest.h>

#include "firmware/can/param_image.hpp"
#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::ErrorCode;
using fw::can::MessageId;

TEST(CanNodeCommands, EnableDisableAndTheAckCarriesStateCodeTagAndOwner) {
  NodeBench b;
  const hal::CanFrame on = b.reply(command(kNode, CommandCode::enable));
  EXPECT_EQ(ack_result(on), ErrorCode::ok);
  EXPECT_EQ(raw_of(on, MessageId::command_ack, "request"), static_cast<std::uint32_t>(MessageId::command));
  EXPECT_EQ(raw_of(on, MessageId::command_ack, "code"), static_cast<std::uint32_t>(CommandCode::enable));
  EXPECT_EQ(raw_of(on, MessageId::command_ack, "state"), static_cast<std::uint32_t>(fw::MotionState::holding));
  EXPECT_EQ(raw_of(on, MessageId::command_ack, "tag"), kTestTag);
  EXPECT_EQ(raw_of(on, MessageId::command_ack, "owner"), 1u);
  b.step();
  EXPECT_TRUE(b.board.written_enable[0]);
  const hal::CanFrame off = b.reply(with_tag(command(kNode, CommandCode::disable), 0x1E));
  EXPECT_EQ(raw_of(off, MessageId::command_ack, "state"), static_cast<std::uint32_t>(fw::MotionState::disabled));
  EXPECT_EQ(raw_of(off, MessageId::command_ack, "tag"), 0x1Eu) << "the reply echoes the request's tag";
  b.step();
  EXPECT_FALSE(b.board.written_enable[0]);
}

TEST(CanNodeCommands, ZeroMovesTheFrameWithoutABump) {
  NodeBench b;
  b.reply(command(kNode, CommandCode::enable));
  b.step(3);
  const fw::AxisTickRecord before = b.task.last_record().axis[0];
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::zero, 0, 0, 100.0))), ErrorCode::ok);
  b.step(3);
  const fw::AxisTickRecord& after = b.task.last_record().axis[0];
  EXPECT_NEAR(after.position_mm, 100.0, 1e-9);
  EXPECT_NEAR(after.reference_mm - after.position_mm, before.reference_mm - before.position_mm, 1e-9)
      << "the following error is unchanged";
  EXPECT_EQ(after.dac_code, before.dac_code) << "no bump in the output";
  EXPECT_EQ(b.task.state(), fw::MotionState::holding);
}

TEST(CanNodeCommands, StopAtRestIsOkAndEstopLatchesUntilCleared) {
  NodeBench b;
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::stop))), ErrorCode::ok);
  b.reply(command(kNode, CommandCode::enable));
  b.request(frame_to(MessageId::estop, kNode));
  b.step();
  EXPECT_EQ(b.task.state(), fw::MotionState::faulted);
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::enable))), ErrorCode::faulted);
  EXPECT_EQ(ack_result(b.reply(circle(kNode, 6.0, 2.0))), ErrorCode::faulted);
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::clear_faults))), ErrorCode::ok);
  EXPECT_EQ(b.task.state(), fw::MotionState::disabled);
}

TEST(CanNodeCommands, BroadcastAcceptsOnlyEstopAndStop) {
  NodeBench b;
  b.reply(command(kNode, CommandCode::enable));
  const std::vector<hal::CanFrame> stop = b.request(command(fw::can::kBroadcastNode, CommandCode::stop));
  ASSERT_EQ(stop.size(), 1u);
  EXPECT_EQ(ack_result(stop[0]), ErrorCode::ok);
  EXPECT_EQ(fw::can::node_of(stop[0].id), kNode) << "answered with the node's own id";
  EXPECT_TRUE(b.request(command(fw::can::kBroadcastNode, CommandCode::disable)).empty());
  EXPECT_EQ(b.task.state(), fw::MotionState::holding);
  b.request(frame_to(MessageId::estop, fw::can::kBroadcastNode));
  EXPECT_EQ(b.task.fault().reason, fw::FaultReason::remote_estop);
}

TEST(CanNodeCommands, ANodeWithAnotherIdAnswersOnlyToIt) {
  fw::can::NodeSettings s = quiet_settings();
  s.can.node_id = 17;
  NodeBench b(s);
  EXPECT_TRUE(b.request(command(kNode, CommandCode::enable)).empty());
  const hal::CanFrame r = b.reply(command(17, CommandCode::enable));
  EXPECT_EQ(fw::can::node_of(r.id), 17);
  EXPECT_EQ(ack_result(r), ErrorCode::ok);
}

TEST(CanNodeCommands, SelectControllerAtRestAndShaperEnableNeedsNoConfiguringFirst) {
  NodeBench b;
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::select_controller, 255, 1))), ErrorCode::ok);
  EXPECT_EQ(b.task.controller(hal::Axis::x), fw::ControllerKind::dvsc);
  EXPECT_EQ(b.task.controller(hal::Axis::y), fw::ControllerKind::dvsc);
  EXPECT_EQ(b.node->settings().firmware.axis[1].controller, fw::ControllerKind::dvsc);
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::shaper_enable, 1, 1))), ErrorCode::ok);
  b.step();
  EXPECT_TRUE(b.task.shaper(hal::Axis::y).shaping()) << "the default spec (zvd, 30 Hz) was configured";
  EXPECT_TRUE(b.node->settings().shaper[1].enabled);
}

// A board ticking at 2 ms (a slowed tick line): restore_defaults keeps the
// period the node was started with, like the encoder and DAC scales.
TEST(CanNodeCommands, RestoreDefaultsKeepsTheBoardsTickPeriod) {
  fw::can::NodeSettings s = quiet_settings();
  s.firmware.supervisor.tick_period_clocks = 20'000;
  s.firmware.supervisor.period_tolerance_clocks = 10'000;
  NodeBench b(s);
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::restore_defaults))), ErrorCode::ok);
  EXPECT_EQ(b.node->settings().firmware.supervisor.tick_period_clocks, 20'000u);
  EXPECT_EQ(b.task.config().supervisor.tick_period_clocks, 20'000u);
  EXPECT_EQ(b.task.config().supervisor.period_tolerance_clocks, 10'000u);
}

TEST(CanNodeCommands, SaveLoadAndRestoreDefaults) {
  NodeBench b;
  const std::uint16_t kp = fw::can::find_param("y.pid.kp")->id;
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::load_params))), ErrorCode::not_ready) << "nothing stored";
  b.reply(param_request(kNode, fw::can::ParamOp::set, kp, f32_raw(333.0f)));
  EXPECT_TRUE(b.node->params_unsaved());
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::save_params))), ErrorCode::ok);
  EXPECT_FALSE(b.node->params_unsaved());
  EXPECT_EQ(b.storage.writes, 1);

  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::restore_defaults))), ErrorCode::ok);
  EXPECT_EQ(b.task.pid_params(hal::Axis::y).kp, fw::default_firmware_config().axis[1].pid.kp);
  EXPECT_EQ(b.node->settings().firmware.axis[0].count_mm, quiet_settings().firmware.axis[0].count_mm);
  EXPECT_TRUE(b.node->params_unsaved());

  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::load_params))), ErrorCode::ok);
  EXPECT_EQ(b.task.pid_params(hal::Axis::y).kp, 333.0);
  EXPECT_FALSE(b.node->params_unsaved());

  // A damaged image: refused whole, the storage bit raised until a good save.
  b.reply(param_request(kNode, fw::can::ParamOp::set, kp, f32_raw(444.0f)));
  b.storage.bytes[20] ^= 0x40;
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::load_params))), ErrorCode::storage_corrupt);
  EXPECT_EQ(b.task.pid_params(hal::Axis::y).kp, 444.0);
  EXPECT_NE(b.node->heartbeat_errors() & fw::can::kHbStorageFault, 0);
  b.storage.fail_write = true;
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::save_params))), ErrorCode::storage_error);
  b.storage.fail_write = false;
  EXPECT_EQ(ack_result(b.reply(command(kNode, CommandCode::save_params))), ErrorCode::ok);
  EXPECT_EQ(b.node->heartbeat_errors() & fw::can::kHbStorageFault, 0);
}

TEST(CanNodeCommands, AStartUpStorageFaultShowsInTheHeartbeat) {
  NodeBench b(quiet_settings(), true);
  EXPECT_NE(b.node->heartbeat_errors() & fw::can::kHbStorageFault, 0);
}

}  // namespace
}  // namespace tnv::test
