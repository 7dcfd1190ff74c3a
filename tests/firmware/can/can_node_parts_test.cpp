// The CAN node's parts on their own (firmware/can: NodeTransmit, HostAccess,
// CommissioningMode, NodeStorage, NodeParameters, NodeTelemetry, and the
// request handlers MotionRequests, SpindleRequest, BoreGaugeRequest), through
// their narrow interfaces; the node as a whole is tested by the
// can_node_*_test files.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "firmware/can/bore_gauge_request.hpp"
#include "firmware/can/commissioning_mode.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/motion_acceptance.hpp"
#include "firmware/can/motion_requests.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/node_capture.hpp"
#include "firmware/can/node_parameters.hpp"
#include "firmware/can/node_storage.hpp"
#include "firmware/can/node_telemetry.hpp"
#include "firmware/can/program_stream.hpp"
#include "firmware/can/shaper_design_deferral.hpp"
#include "firmware/can/spindle_request.hpp"
#include "firmware/can/telemetry_scheduler.hpp"
#include "firmware/can/node_transmit.hpp"
#include "firmware/can/request_tag.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tests/firmware/can/bore_frames.hpp"
#include "tests/firmware/can/can_test_doubles.hpp"
#include "tests/firmware/can/node_bench.hpp"
#include "tests/firmware/fake_io_board.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::ErrorCode;

hal::CanFrame frame_with_id(std::uint32_t id) {
  hal::CanFrame f{};
  f.id = id;
  f.dlc = 8;
  return f;
}

TEST(NodeTransmit, SendsAtMostTheBudgetPerServiceInIdOrderAndKeepsTheRest) {
  FakeCanPort port;
  fw::can::NodeTransmit tx(port);
  tx.begin_service();
  for (int i = 0; i < fw::can::kMaxTxPerService + 8; ++i) tx.queue(frame_with_id(0x700u - static_cast<std::uint32_t>(i)), false);
  tx.flush();
  const std::vector<hal::CanFrame> sent = port.drain();
  ASSERT_EQ(sent.size(), static_cast<std::size_t>(fw::can::kMaxTxPerService));
  EXPECT_EQ(tx.pending(), 8u);
  for (std::size_t i = 1; i < sent.size(); ++i) EXPECT_LT(sent[i - 1].id, sent[i].id) << "lowest id first";
  EXPECT_FALSE(tx.send_now(frame_with_id(0x100))) << "the budget is spent";
  tx.begin_service();
  tx.flush();
  EXPECT_EQ(port.drain().size(), 8u);
  EXPECT_TRUE(tx.idle());
  EXPECT_EQ(tx.counters().tx_frames, static_cast<std::uint64_t>(fw::can::kMaxTxPerService + 8));
}

TEST(NodeTransmit, AnswersAreCountedAndAFullQueueDropsTelemetryFirst) {
  FakeCanPort port;
  fw::can::NodeTransmit tx(port);
  tx.answer(frame_with_id(0x200), ErrorCode::ok);
  tx.answer(frame_with_id(0x200), ErrorCode::busy);
  tx.answer(frame_with_id(0x200), ErrorCode::unknown_command);
  EXPECT_EQ(tx.sequence(), 3u);
  EXPECT_EQ(tx.counters().requests_refused, 2u);
  EXPECT_EQ(tx.counters().unknown_commands, 1u);
  EXPECT_FALSE(tx.dropped_since_heartbeat());
  // Fill the rest of the queue with telemetry, then one more reply: a telemetry frame makes room.
  while (tx.pending() < fw::can::TxPriorityQueue::kCapacity) tx.queue(frame_with_id(0x600), true);
  tx.answer(frame_with_id(0x200), ErrorCode::ok);
  EXPECT_EQ(tx.counters().telemetry_dropped, 1u);
  EXPECT_EQ(tx.counters().tx_dropped, 1u);
  EXPECT_TRUE(tx.dropped_since_heartbeat());
  tx.heartbeat_sent();
  EXPECT_FALSE(tx.dropped_since_heartbeat());
  tx.begin_service();
  tx.flush();
  const std::vector<hal::CanFrame> sent = port.drain();
  ASSERT_GE(sent.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(sent[i].id, 0x200u) << "the answers leave first";
}

TEST(HostAccess, OwnershipIsTakenReleasedAndLostBySilence) {
  fw::can::HostAccess access;
  const std::uint8_t host1 = fw::can::make_tag(1, 3);
  const std::uint8_t host2 = fw::can::make_tag(2, 5);
  access.begin_request(host1, false);
  EXPECT_FALSE(access.owns());
  EXPECT_EQ(access.ownership(CommandCode::take_ownership), ErrorCode::ok);
  EXPECT_TRUE(access.owns());
  EXPECT_EQ(access.owner(), 1u);
  access.begin_request(host2, false);
  EXPECT_FALSE(access.owns());
  EXPECT_EQ(access.ownership(CommandCode::take_ownership), ErrorCode::not_owner);
  EXPECT_EQ(access.ownership(CommandCode::release_ownership), ErrorCode::not_owner);
  access.begin_request(0x00, true);
  EXPECT_TRUE(access.broadcast());
  EXPECT_EQ(access.ownership(CommandCode::take_ownership), ErrorCode::no_host);
  EXPECT_EQ(access.owner(), 1u) << "refusals change nothing";

  EXPECT_FALSE(access.owner_timed_out(99, 100));
  access.heard_from(2);  // not the owner: its silence goes on
  EXPECT_TRUE(access.owner_timed_out(1, 100));
  EXPECT_EQ(access.owner(), fw::can::kAnonymousHost);

  access.begin_request(host2, false);
  EXPECT_EQ(access.ownership(CommandCode::take_ownership), ErrorCode::ok);
  EXPECT_FALSE(access.owner_timed_out(99, 100));
  access.heard_from(2);
  EXPECT_FALSE(access.owner_timed_out(99, 100)) << "a frame from the owner restarts the count";
  EXPECT_FALSE(access.owner_timed_out(1000000, 0)) << "0: no timeout";
  EXPECT_EQ(access.ownership(CommandCode::release_ownership), ErrorCode::ok);
  EXPECT_EQ(access.owner(), fw::can::kAnonymousHost);
  access.answer_as(host1);
  EXPECT_EQ(access.tag(), host1);
  EXPECT_EQ(access.host(), 1u);
}

TEST(CommissioningMode, EnteredOnlyWhenAllowedAndLeftWhenAsked) {
  FakeIoBoard board;
  fw::TickTask task(board, quiet_settings().firmware);  // disabled, no fault: the mode may be entered
  fw::can::CommissioningMode mode(task);
  EXPECT_FALSE(mode.active());
  EXPECT_EQ(mode.enter(), ErrorCode::ok);
  EXPECT_TRUE(mode.active());
  EXPECT_TRUE(mode.refresh());
  mode.leave();
  EXPECT_FALSE(mode.active());
  mode.allow(false);
  EXPECT_EQ(mode.enter(), ErrorCode::not_permitted);
  EXPECT_FALSE(mode.active());
  mode.allow(true);
  EXPECT_EQ(mode.enter(), ErrorCode::ok);
  mode.allow(false);
  EXPECT_FALSE(mode.active()) << "withdrawing the permission leaves the mode";
}

TEST(NodeStorage, SaveThenLoadWithoutAWorkerAnswersWithTheRequestsTag) {
  MemoryStorage current;
  fw::can::NodeStorage storage(current, nullptr, nullptr, true);
  EXPECT_TRUE(storage.fault());
  hal::CanFrame request{};
  request.dlc = 8;
  request.data[0] = 0x27;

  // Nothing stored yet: a load is not_ready and changes nothing.
  ASSERT_EQ(storage.begin(request, CommandCode::load_params, quiet_settings()), ErrorCode::ok);
  EXPECT_TRUE(storage.pending());
  fw::can::NodeStorage::Finished done = storage.finish();
  EXPECT_FALSE(storage.pending());
  EXPECT_EQ(done.result, ErrorCode::not_ready);
  EXPECT_EQ(done.loaded, nullptr);
  EXPECT_TRUE(storage.fault());

  fw::can::NodeSettings saved = quiet_settings();
  saved.can.host_timeout_ms = 777;
  storage.changed();
  ASSERT_EQ(storage.begin(request, CommandCode::save_params, saved), ErrorCode::ok);
  done = storage.finish();
  EXPECT_EQ(done.code, CommandCode::save_params);
  EXPECT_EQ(done.tag, 0x27);
  EXPECT_EQ(done.result, ErrorCode::ok);
  EXPECT_FALSE(storage.fault()) << "a good save clears the fault";
  EXPECT_FALSE(storage.unsaved());
  EXPECT_EQ(current.writes, 1);

  ASSERT_EQ(storage.begin(request, CommandCode::load_params, quiet_settings()), ErrorCode::ok);
  done = storage.finish();
  EXPECT_EQ(done.code, CommandCode::load_params);
  ASSERT_NE(done.loaded, nullptr);
  EXPECT_EQ(done.loaded->settings().can.host_timeout_ms, 777u);
  storage.changed();
  storage.loaded_applied();
  EXPECT_FALSE(storage.unsaved()) << "the current generation loaded: what is saved";

  current.fail_write = true;
  ASSERT_EQ(storage.begin(request, CommandCode::save_params, saved), ErrorCode::ok);
  done = storage.finish();
  EXPECT_NE(done.result, ErrorCode::ok);
  EXPECT_TRUE(storage.fault());
}

// The node's parts as CanNode wires them, without the node (the capture
// part holds its 512 KiB buffer: on the heap).
struct PartsBench {
  explicit PartsBench(const fw::can::NodeSettings& s = quiet_settings())
      : task(board, s.firmware),
        mode(task),
        tx(port),
        ack(kNode, task, access, tx),
        programs(kNode, task, access, ack, tx),
        storage(current, nullptr, nullptr, false),
        capture(std::make_unique<fw::can::NodeCapture>(kNode, task, access, tx)),
        params(kNode, task, access, mode, tx, storage, design, *capture, s),
        telemetry(kNode, task, port, tx, access, mode, storage, params, programs, *capture) {}
  // What the parts queued, sent.
  std::vector<hal::CanFrame> sent() {
    tx.begin_service();
    tx.flush();
    return port.drain();
  }

  FakeIoBoard board;
  FakeCanPort port;
  MemoryStorage current;
  fw::TickTask task;
  fw::can::HostAccess access;
  fw::can::CommissioningMode mode;
  fw::can::NodeTransmit tx;
  fw::can::CommandAck ack;
  fw::can::ProgramStream programs;
  fw::can::NodeStorage storage;
  fw::can::ShaperDesignDeferral design{nullptr};
  std::unique_ptr<fw::can::NodeCapture> capture;
  fw::can::NodeParameters params;
  fw::can::NodeTelemetry telemetry;
};

TEST(NodeParameters, AChangeAppliesWholeOrNotAtAllAndRequestsAreAnswered) {
  PartsBench b;
  using fw::can::MessageId;
  using fw::can::ParamOp;
  // A set refused by validate() changes nothing and names no unsaved change.
  fw::can::NodeSettings bad = b.params.settings();
  bad.telemetry.position_ms = 20;
  bad.motion.circle_ramp_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(b.params.apply(bad, false), ErrorCode::invalid);
  EXPECT_EQ(b.params.settings().telemetry.position_ms, 0u);
  EXPECT_FALSE(b.storage.unsaved());
  fw::can::NodeSettings good = b.params.settings();
  good.telemetry.position_ms = 20;
  EXPECT_EQ(b.params.apply(good, false), ErrorCode::ok);
  EXPECT_EQ(b.params.settings().telemetry.position_ms, 20u);
  EXPECT_TRUE(b.storage.unsaved());

  // get is open to every host; set needs ownership; stage goes to the host's own set.
  const std::uint16_t id = id_of("tlm.position_ms");
  b.access.begin_request(fw::can::make_tag(2, 1), false);
  b.params.handle(param_request(kNode, ParamOp::get, id));
  std::vector<hal::CanFrame> out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(raw_of(out[0], MessageId::param_reply, "result"), static_cast<std::uint32_t>(ErrorCode::ok));
  EXPECT_EQ(raw_of(out[0], MessageId::param_reply, "value"), 20u);
  b.params.handle(param_request(kNode, ParamOp::set, id, 50));
  out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(raw_of(out[0], MessageId::param_reply, "result"), static_cast<std::uint32_t>(ErrorCode::not_owner));
  EXPECT_EQ(b.params.settings().telemetry.position_ms, 20u);
  b.params.handle(param_request(kNode, ParamOp::stage, id, 50));
  out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(raw_of(out[0], MessageId::param_reply, "result"), static_cast<std::uint32_t>(ErrorCode::ok));
  EXPECT_EQ(b.params.staged_count(2), 1u);
  EXPECT_EQ(b.params.staged_count(1), 0u);
  EXPECT_EQ(b.params.staged_count(), 1u);
  EXPECT_EQ(b.params.settings().telemetry.position_ms, 20u) << "staged, not applied";
}

TEST(NodeTelemetry, SendsWhatIsDueAndTheHeartbeatsStickyBitsClearOnAcceptedMotion) {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry.heartbeat_ms = 2;
  s.telemetry.position_ms = 1;
  PartsBench b(s);
  using fw::can::MessageId;
  EXPECT_EQ(b.telemetry.on_tick(1), fw::can::cyclic_bit(fw::can::Cyclic::position));
  const std::uint32_t due = b.telemetry.on_tick(1);
  EXPECT_EQ(due, fw::can::cyclic_bit(fw::can::Cyclic::position) | fw::can::cyclic_bit(fw::can::Cyclic::heartbeat));
  b.telemetry.host_timed_out();
  const std::uint16_t bits = b.telemetry.heartbeat_errors();
  EXPECT_NE(bits & fw::can::kHbHostTimeout, 0);
  b.telemetry.send(due);
  const std::vector<hal::CanFrame> out = b.sent();
  ASSERT_EQ(out.size(), 1u + hal::kAxisCount) << "the heartbeat and a position frame per axis";
  EXPECT_EQ(only(out, MessageId::heartbeat).size(), 1u);
  EXPECT_EQ(only(out, MessageId::tlm_position_x).size(), 1u);
  EXPECT_EQ(raw_of(only(out, MessageId::heartbeat)[0], MessageId::heartbeat, "errors"), bits);
  b.telemetry.motion_accepted();
  EXPECT_EQ(b.telemetry.heartbeat_errors() & fw::can::kHbHostTimeout, 0);
  b.telemetry.check_fault();
  EXPECT_TRUE(b.sent().empty()) << "no fault latched: no FAULT_EVENT";
  b.task.estop();
  b.telemetry.check_fault();
  b.telemetry.check_fault();
  EXPECT_EQ(only(b.sent(), MessageId::fault_event).size(), 1u) << "once per latch";
}

// The request handlers as CanNode wires them, over the parts above.
struct RequestsBench : PartsBench {
  explicit RequestsBench(const fw::can::NodeSettings& s = quiet_settings()) : PartsBench(s) {}
  fw::can::MotionAcceptance motion{mode, telemetry};
  fw::can::MotionRequests motions{task, access, ack, params, motion};
  fw::can::SpindleRequest spindle{task, access, ack, programs, motion};
  fw::can::BoreGaugeRequest bore{kNode, access, tx, storage, params};
};

TEST(MotionRequests, ARefusalStartsNothingAndAnAcceptedJogClearsTheStickyBits) {
  RequestsBench b;
  b.task.tick();
  b.access.begin_request(kTestTag, false);
  b.motions.jog(jog(kNode, 0, 1.0));
  std::vector<hal::CanFrame> out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(ack_result(out[0]), ErrorCode::not_owner);
  EXPECT_FALSE(b.task.moving());

  ASSERT_EQ(b.access.ownership(CommandCode::take_ownership), ErrorCode::ok);
  ASSERT_EQ(b.task.hold_position(), fw::CommandStatus::ok);
  b.telemetry.host_timed_out();
  b.motions.move(move(kNode, 0, 0.0, 5.0));
  out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(ack_result(out[0]), ErrorCode::out_of_range);
  EXPECT_EQ(ack_detail(out[0]), fw::can::fields::index_of(fw::can::fields::kMoveMsg, fw::can::fields::kMoveSpeed));
  EXPECT_FALSE(b.task.moving()) << "refused: nothing started";
  EXPECT_NE(b.telemetry.heartbeat_errors() & fw::can::kHbHostTimeout, 0);

  b.motions.jog(jog(kNode, 0, 1.0));
  out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(ack_result(out[0]), ErrorCode::ok);
  EXPECT_TRUE(b.task.jogging());
  EXPECT_EQ(b.telemetry.heartbeat_errors() & fw::can::kHbHostTimeout, 0);
}

TEST(MotionAcceptance, LeavesCommissioningAndClearsTheStickyBits) {
  RequestsBench b;
  b.task.tick();
  ASSERT_EQ(b.mode.enter(), ErrorCode::ok);  // disabled: the mode may be entered
  b.telemetry.host_timed_out();
  b.motion.accepted();
  EXPECT_FALSE(b.mode.active());
  EXPECT_EQ(b.telemetry.heartbeat_errors() & fw::can::kHbHostTimeout, 0);
}

TEST(SpindleRequest, NeedsOwnershipAndAKnownOp) {
  RequestsBench b;
  b.task.tick();
  using fw::can::MessageId;
  hal::CanFrame f = frame_to(MessageId::spindle, kNode);
  set_raw(f, MessageId::spindle, "op", static_cast<std::uint32_t>(fw::can::kSpindleOpCount));
  b.access.begin_request(kTestTag, false);
  b.spindle.handle(f);
  std::vector<hal::CanFrame> out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(ack_result(out[0]), ErrorCode::unknown_command);
  set_raw(f, MessageId::spindle, "op", static_cast<std::uint32_t>(fw::can::SpindleOp::stop));
  b.spindle.handle(f);
  out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(ack_result(out[0]), ErrorCode::not_owner);
  ASSERT_EQ(b.access.ownership(CommandCode::take_ownership), ErrorCode::ok);
  b.spindle.handle(f);
  out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(ack_result(out[0]), ErrorCode::ok) << "a stop is always taken";
}

TEST(BoreGaugeRequest, AnswersInBoreInfeedWithTheRequestsTag) {
  fw::can::NodeSettings s = quiet_settings();
  s.bore.enabled = false;
  RequestsBench b(s);
  using fw::can::MessageId;
  const std::uint8_t host2 = fw::can::make_tag(2, 7);
  b.access.begin_request(host2, false);
  b.bore.handle(bore_gauge(kNode, fw::can::BoreOp::record, 1, 0.01, 0.01));
  std::vector<hal::CanFrame> out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  ASSERT_TRUE(is(out[0], MessageId::bore_infeed));
  EXPECT_EQ(raw_of(out[0], MessageId::bore_infeed, "result"), static_cast<std::uint32_t>(ErrorCode::not_owner));
  EXPECT_EQ(raw_of(out[0], MessageId::bore_infeed, "tag"), host2);
  b.bore.handle(bore_gauge(kNode, fw::can::BoreOp::query));
  out = b.sent();
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(raw_of(out[0], MessageId::bore_infeed, "result"), static_cast<std::uint32_t>(ErrorCode::not_ready))
      << "query is open to every host; the planner is off";
  EXPECT_FALSE(b.storage.unsaved()) << "nothing learned";
}

}  // namespace
}  // namespace tnv::test
