// Heartbeat and cyclic telemetry: each message at its own period, counted
// over many ticks; FAULT_EVENT exactly once per latched fault.
#include <gtest/gtest.h>

#include <algorithm>

#include <map>

#include "firmware/can/node_fields.hpp"
#include "firmware/can/telemetry_scheduler.hpp"
#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

using fw::can::MessageId;

TEST(TelemetryScheduler, EachMessageEveryPeriodAndAChangedPeriodRestartsItsCount) {
  fw::can::TelemetryScheduler s;
  // heartbeat, position, sliding, output, contour, arsc, spindle
  fw::can::TelemetryPeriods p{100, 10, 3, 0, 1, 4, 0};
  std::map<int, int> sent;
  for (int k = 0; k < 1000; ++k) {
    const std::uint32_t due = s.advance(p, 1);
    for (int bit = 0; bit < 7; ++bit) sent[bit] += (due >> bit) & 1u;
  }
  EXPECT_EQ(sent[0], 10);
  EXPECT_EQ(sent[1], 100);
  EXPECT_EQ(sent[2], 333);
  EXPECT_EQ(sent[3], 0) << "0 = off";
  EXPECT_EQ(sent[4], 1000);
  EXPECT_EQ(sent[5], 250) << "TLM_ARSC";
  EXPECT_EQ(sent[6], 0) << "TLM_SPINDLE off";
  p.heartbeat_ms = 50;
  int hb = 0;
  for (int k = 0; k < 49; ++k) hb += s.advance(p, 1) & 1u;
  EXPECT_EQ(hb, 0) << "the first frame after a change comes one new period later";
  EXPECT_EQ(s.advance(p, 1) & 1u, 1u);
}

TEST(CanNodeTelemetry, FrameCountsOverTwoSecondsMatchThePeriods) {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry = {100, 10, 50, 7, 0, 0, 0};
  NodeBench b(s);
  b.port.drain();
  constexpr int kTicks = 2000;
  std::map<MessageId, int> count;
  for (int k = 0; k < kTicks; ++k) {
    b.step();
    for (const hal::CanFrame& f : b.port.drain()) ++count[static_cast<MessageId>(fw::can::message_of(f.id))];
  }
  EXPECT_EQ(count[MessageId::heartbeat], kTicks / 100);
  // One frame per axis of each per-axis message, every period.
  for (const hal::Axis a : hal::kAxes) {
    SCOPED_TRACE(hal::axis_label(a));
    const auto i = hal::index(a);
    EXPECT_EQ(count[static_cast<MessageId>(fw::can::fields::kPositionMsgs[i]->id)], kTicks / 10);
    EXPECT_EQ(count[static_cast<MessageId>(fw::can::fields::kSlidingMsgs[i]->id)], kTicks / 50);
    EXPECT_EQ(count[static_cast<MessageId>(fw::can::fields::kDacMsgs[i]->id)], kTicks / 7);
  }
  EXPECT_EQ(count[MessageId::tlm_output], kTicks / 7);
  EXPECT_EQ(count[MessageId::tlm_contour], 0) << "off";
  EXPECT_EQ(b.node->counters().tx_dropped, 0u);
}

TEST(CanNodeTelemetry, APeriodSetOverCanTakesEffect) {
  NodeBench b;
  b.reply(param_request(kNode, fw::can::ParamOp::set, fw::can::find_param("tlm.heartbeat_ms")->id, 5));
  int hb = 0;
  for (int k = 0; k < 100; ++k) {
    b.step();
    hb += static_cast<int>(only(b.port.drain(), MessageId::heartbeat).size());
  }
  EXPECT_EQ(hb, 20);
}

TEST(CanNodeTelemetry, HeartbeatCarriesStateFaultAndTick) {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry.heartbeat_ms = 10;
  NodeBench b(s);
  b.reply(command(kNode, fw::can::CommandCode::enable));
  std::vector<hal::CanFrame> hb;
  std::uint64_t sent_at = 0;
  for (int k = 0; k < 10 && hb.empty(); ++k) {
    b.step();
    hb = only(b.port.drain(), MessageId::heartbeat);
    sent_at = b.task.last_record().tick;
  }
  ASSERT_EQ(hb.size(), 1u);
  EXPECT_EQ(sent_at % 10, 0u) << "every 10th tick";
  EXPECT_EQ(raw_of(hb[0], MessageId::heartbeat, "state"), static_cast<std::uint32_t>(fw::MotionState::holding));
  EXPECT_EQ(raw_of(hb[0], MessageId::heartbeat, "fault"), 0u);
  EXPECT_EQ(raw_of(hb[0], MessageId::heartbeat, "errors"), 0u);
  EXPECT_EQ(raw_of(hb[0], MessageId::heartbeat, "axes"), 0u) << "nothing homed, no shaper on";
}

// The error bits of the next heartbeat from the node (at most 20 ticks away).
std::uint32_t next_heartbeat_errors(NodeBench& b) {
  for (int k = 0; k < 20; ++k) {
    b.step();
    const std::vector<hal::CanFrame> hb = only(b.port.drain(), MessageId::heartbeat);
    if (!hb.empty()) return raw_of(hb.back(), MessageId::heartbeat, "errors");
  }
  ADD_FAILURE() << "no heartbeat within 20 ticks";
  return 0;
}

TEST(CanNodeTelemetry, CanErrorFramesRaiseTheHeartbeatBitUntilTheNextHeartbeat) {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry.heartbeat_ms = 10;
  NodeBench b(s);
  EXPECT_EQ(next_heartbeat_errors(b) & fw::can::kHbCanErrors, 0u) << "no error frames yet";
  b.port.error_frame_count = 3;  // the controller saw three error frames
  EXPECT_NE(next_heartbeat_errors(b) & fw::can::kHbCanErrors, 0u);
  EXPECT_EQ(next_heartbeat_errors(b) & fw::can::kHbCanErrors, 0u) << "none since the last heartbeat";
}

TEST(CanNodeTelemetry, PositionTelemetryIsTheEncoderPositionInNanometres) {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry.position_ms = 1;
  NodeBench b(s);
  b.board.counts = {480, 0xFFFF - 23};  // +0.2 mm and -24 counts (16-bit wrap)
  b.step();
  const std::vector<hal::CanFrame> out = b.port.drain();
  const std::vector<hal::CanFrame> pos_x = only(out, MessageId::tlm_position_x);
  const std::vector<hal::CanFrame> pos_y = only(out, MessageId::tlm_position_y);
  ASSERT_EQ(pos_x.size(), 1u);
  ASSERT_EQ(pos_y.size(), 1u);
  EXPECT_NEAR(value_of(pos_x[0], MessageId::tlm_position_x, "position"), 6.2, 1e-6);
  EXPECT_NEAR(value_of(pos_x[0], MessageId::tlm_position_x, "following"),
              b.task.last_record().axis[0].reference_mm - b.task.last_record().axis[0].position_mm, 1e-6)
      << "the same tick's following error in the same frame";
  EXPECT_NEAR(value_of(pos_y[0], MessageId::tlm_position_y, "position"), -24 * 10.0 / 24000.0, 1e-6);
}

TEST(CanNodeTelemetry, FaultEventIsSentOnceAndAgainOnlyAfterAClearAndANewFault) {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry.heartbeat_ms = 10;
  NodeBench b(s);
  b.reply(command(kNode, fw::can::CommandCode::enable));
  b.board.in.estop = true;  // the e-stop input
  int events = 0;
  for (int k = 0; k < 200; ++k) {
    b.step();
    for (const hal::CanFrame& f : only(b.port.drain(), MessageId::fault_event)) {
      ++events;
      EXPECT_EQ(raw_of(f, MessageId::fault_event, "reason"), static_cast<std::uint32_t>(fw::FaultReason::estop));
      EXPECT_EQ(raw_of(f, MessageId::fault_event, "tick_low"), b.task.fault().tick & 0xFFFFu);
    }
  }
  EXPECT_EQ(events, 1);
  const hal::CanFrame refused = b.reply(command(kNode, fw::can::CommandCode::clear_faults));
  EXPECT_EQ(raw_of(refused, MessageId::command_ack, "result"), static_cast<std::uint32_t>(fw::can::ErrorCode::cause_present));
  b.board.in.estop = false;
  b.step();
  b.port.drain();
  const hal::CanFrame cleared = b.reply(command(kNode, fw::can::CommandCode::clear_faults));
  EXPECT_EQ(raw_of(cleared, MessageId::command_ack, "result"), 0u);
  EXPECT_EQ(raw_of(cleared, MessageId::command_ack, "fault"), 0u);
  b.step(50);
  EXPECT_TRUE(only(b.port.drain(), MessageId::fault_event).empty());
  const std::vector<hal::CanFrame> out = b.request(frame_to(MessageId::estop, kNode));
  EXPECT_EQ(only(out, MessageId::fault_event).size(), 1u) << "a new fault: a new event";
  EXPECT_EQ(b.task.fault().reason, fw::FaultReason::remote_estop);
  b.step(50);
  EXPECT_TRUE(only(b.port.drain(), MessageId::fault_event).empty());
}

// The port takes one frame at a time: everything else waits in the node's
// priority queue, which fills with heartbeats and telemetry. Telemetry is
// what gets dropped (and counted); replies then leave first, in order,
// then the heartbeats, telemetry last.
TEST(CanNodeTelemetry, RepliesAndHeartbeatsLeaveBeforeTelemetryAndAFullQueueDropsTelemetryFirst) {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry = {1, 1, 0, 0, 0, 0, 0};
  NodeBench b(s);
  b.port.tx_capacity = 1;
  b.step(40);  // 40 heartbeats and 80 telemetry frames offered; 48 places in the queue
  const fw::can::NodeCounters& c = b.node->counters();
  EXPECT_GT(c.telemetry_dropped, 0u) << "the queue must have filled";
  EXPECT_EQ(c.tx_dropped, c.telemetry_dropped) << "only telemetry may be dropped";
  b.port.send(param_request(kNode, fw::can::ParamOp::get, 0x0000));
  b.port.send(param_request(kNode, fw::can::ParamOp::get, 0x0001));
  b.port.send(param_request(kNode, fw::can::ParamOp::get, 0x0002));
  b.node->service();
  b.port.drain();  // the frame the port held before the requests came
  std::vector<hal::CanFrame> out;
  for (int k = 0; k < 100; ++k) {
    b.node->service();
    for (const hal::CanFrame& f : b.port.drain()) out.push_back(f);
  }
  ASSERT_GE(out.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    ASSERT_TRUE(is(out[i], MessageId::param_reply)) << "frame " << i << " is not a reply";
    EXPECT_EQ(raw_of(out[i], MessageId::param_reply, "param"), i) << "replies in the order asked";
  }
  std::size_t last_heartbeat = 0;
  std::size_t first_telemetry = out.size();
  for (std::size_t i = 0; i < out.size(); ++i) {
    if (is(out[i], MessageId::heartbeat)) last_heartbeat = i;
    if (fw::can::message_of(out[i].id) >= static_cast<std::uint8_t>(MessageId::tlm_output))  // the first telemetry id
      first_telemetry = std::min(first_telemetry, i);
  }
  EXPECT_GT(last_heartbeat, 0u) << "no heartbeat came out";
  EXPECT_LT(last_heartbeat, first_telemetry) << "a heartbeat waited behind telemetry";
  EXPECT_LT(first_telemetry, out.size()) << "the telemetry kept in the queue never went out";
  EXPECT_EQ(b.node->tx_pending(), 0u);
  EXPECT_NE(b.node->heartbeat_errors() & fw::can::kHbTxDropped, 0);
}

}  // namespace
}  // namespace tnv::test
