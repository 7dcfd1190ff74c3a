// Issue item 5: every kind of bad input, table-driven. Each case sends one
// frame to a node at rest and checks the answer the protocol prescribes
// (or silence where it says "ignored"), and that nothing changed: every
// parameter of the node and of the running task, the motion state, the
// latched fault, the staged set, the capture and the boring planner's
// learned state (more BORE_GAUGE cases with the planner on:
// can_node_boring_refusal_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "firmware/can/capture_channels.hpp"
#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

constexpr auto kPastTheList = static_cast<std::uint8_t>(hal::kAxisCount);  // the first number that is no axis'

using fw::can::CaptureOp;
using fw::can::CommandCode;
using fw::can::ErrorCode;
using fw::can::MessageId;
using fw::can::ParamOp;

struct Snapshot {
  std::vector<double> node_params;
  std::vector<double> task_params;
  fw::MotionState state;
  fw::FaultReason fault;
  std::size_t staged;
  fw::can::CaptureState capture;
  std::uint8_t owner;
  fw::BoringStationState bore_state;
  bool operator==(const Snapshot&) const = default;
};

Snapshot snapshot(const NodeBench& b) {
  Snapshot s{};
  fw::can::NodeSettings from_task = b.node->settings();
  from_task.firmware = b.task.config();
  for (const fw::can::ParamDef& p : fw::can::param_table()) {
    s.node_params.push_back(p.get(b.node->settings()));
    s.task_params.push_back(p.get(from_task));
  }
  s.state = b.task.state();
  s.fault = b.task.fault().reason;
  s.staged = b.node->staged_count();
  s.capture = b.node->capture_state();
  s.owner = b.node->owner();
  s.bore_state = b.node->settings().bore_state;
  return s;
}

struct Case {
  std::string name;
  hal::CanFrame frame;
  std::optional<MessageId> reply;  // nullopt: the node must stay silent
  ErrorCode result = ErrorCode::ok;
  std::optional<std::uint32_t> value;  // PARAM_REPLY.value expected, if it matters
  std::optional<std::uint32_t> detail;  // COMMAND_ACK.detail expected, if it matters
};

void add(std::vector<Case>& c, std::string name, const hal::CanFrame& frame, std::optional<MessageId> reply,
         ErrorCode result = ErrorCode::ok, std::optional<std::uint32_t> value = std::nullopt,
         std::optional<std::uint32_t> detail = std::nullopt) {
  c.push_back(Case{std::move(name), frame, reply, result, value, detail});
}

hal::CanFrame with_dlc(hal::CanFrame f, std::uint8_t dlc) {
  f.dlc = dlc;
  return f;
}

std::vector<Case> cases() {
  std::vector<Case> c;
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  constexpr float kInf = std::numeric_limits<float>::infinity();
  const std::uint16_t gamma = id_of("x.sliding.gamma");
  const std::uint32_t gamma_now = f32_raw(static_cast<float>(fw::can::default_node_settings().firmware.axis[0].sliding.gamma));

  // Wrong DLC, every to_node message that is answered: too short and empty.
  for (const fw::can::MessageDef& m : fw::can::kMessages) {
    if (m.direction != fw::can::Direction::to_node || m.id == static_cast<std::uint8_t>(MessageId::estop)) continue;
    const auto id = static_cast<MessageId>(m.id);
    const MessageId answer = id == MessageId::param_request     ? MessageId::param_reply
                             : id == MessageId::capture_control ? MessageId::capture_status
                             : id == MessageId::bore_gauge      ? MessageId::bore_infeed
                                                                : MessageId::command_ack;
    // A frame that would be accepted with the right length (a set of gamma, a stop, ...).
    hal::CanFrame f = id == MessageId::param_request ? param_request(kNode, ParamOp::set, gamma, f32_raw(0.2f))
                      : id == MessageId::command     ? command(kNode, CommandCode::enable)
                                                     : frame_to(id, kNode);
    for (const std::uint8_t dlc : {static_cast<std::uint8_t>(m.dlc - 1), std::uint8_t{0}})
      add(c, std::string(m.name) + " with dlc " + std::to_string(dlc), with_dlc(f, dlc), answer, ErrorCode::bad_length);
  }
  // Unknown codes and operations.
  add(c, "unknown command code", command(kNode, static_cast<CommandCode>(fw::can::kCommandCodeCount)),
               MessageId::command_ack, ErrorCode::unknown_command, {}, 1u);
  add(c, "command code 255", command(kNode, static_cast<CommandCode>(255)), MessageId::command_ack,
               ErrorCode::unknown_command);
  add(c, "unknown param op", param_request(kNode, static_cast<ParamOp>(fw::can::kParamOpCount), gamma, f32_raw(0.2f)),
               MessageId::param_reply, ErrorCode::unknown_command);
  add(c, "param op 255", param_request(kNode, static_cast<ParamOp>(255), gamma), MessageId::param_reply,
               ErrorCode::unknown_command);
  add(c, "unknown capture op", capture_control(kNode, static_cast<CaptureOp>(fw::can::kCaptureOpCount)),
               MessageId::capture_status, ErrorCode::unknown_command);
  // Bad parameter ids.
  for (const ParamOp op : {ParamOp::get, ParamOp::set, ParamOp::stage})
    for (const std::uint16_t bad : {std::uint16_t{0x000F}, std::uint16_t{0x01FF}, std::uint16_t{0xFFFF}})
      add(c, "param id " + std::to_string(bad) + " op " + std::to_string(static_cast<int>(op)),
                   param_request(kNode, op, bad, f32_raw(1.0f)), MessageId::param_reply, ErrorCode::unknown_id, 0u);
  // Values that are not numbers, out of range, or read-only.
  for (const ParamOp op : {ParamOp::set, ParamOp::stage}) {
    const std::string o = op == ParamOp::set ? "set " : "stage ";
    add(c, o + "gamma NaN", param_request(kNode, op, gamma, f32_raw(kNaN)), MessageId::param_reply,
                 ErrorCode::not_finite, gamma_now);
    add(c, o + "gamma +inf", param_request(kNode, op, gamma, f32_raw(kInf)), MessageId::param_reply,
                 ErrorCode::not_finite, gamma_now);
    add(c, o + "gamma -inf", param_request(kNode, op, gamma, f32_raw(-kInf)), MessageId::param_reply,
                 ErrorCode::not_finite, gamma_now);
    add(c, o + "gamma 1.5", param_request(kNode, op, gamma, f32_raw(1.5f)), MessageId::param_reply,
                 ErrorCode::out_of_range, gamma_now);
    add(c, o + "gamma -0.1", param_request(kNode, op, gamma, f32_raw(-0.1f)), MessageId::param_reply,
                 ErrorCode::out_of_range, gamma_now);
    add(c, o + "heartbeat 70000 ms", param_request(kNode, op, id_of("tlm.heartbeat_ms"), 70000),
                 MessageId::param_reply, ErrorCode::out_of_range, 0u);
    add(c, o + "bit rate 300", param_request(kNode, op, id_of("can.bitrate_kbit"), 300), MessageId::param_reply,
                 ErrorCode::out_of_range, 1000u);
    add(c, o + "controller 3", param_request(kNode, op, id_of("x.controller"), 3), MessageId::param_reply,
                 ErrorCode::out_of_range, 2u);
    add(c, o + "shaper freq 1000 Hz", param_request(kNode, op, id_of("y.shaper.freq_hz"), f32_raw(1000.0f)),
                 MessageId::param_reply, ErrorCode::out_of_range);
    add(c, o + "read-only protocol version", param_request(kNode, op, id_of("sys.protocol_version"), 7),
                 MessageId::param_reply, ErrorCode::read_only, fw::can::kProtocolVersion);
  }
  // Each value in range, the set as a whole not: phi below eta / (q + 1) (S1 Theorem 2).
  add(c, "set phi below eta/(q+1)", param_request(kNode, ParamOp::set, id_of("x.sliding.phi_mm_s"), f32_raw(0.05f)),
               MessageId::param_reply, ErrorCode::invalid);
  // Safety parameters outside commissioning mode: refused before any other check.
  add(c, "set position_min above max", param_request(kNode, ParamOp::set, id_of("y.limits.position_min_mm"),
                                                           f32_raw(300.0f)),
               MessageId::param_reply, ErrorCode::commissioning_required);
  add(c, "set following floor 100 mm", param_request(kNode, ParamOp::set, id_of("x.limits.following_floor_mm"),
                                                           f32_raw(100.0f)),
               MessageId::param_reply, ErrorCode::commissioning_required);
  add(c, "stage max missed ticks 1000", param_request(kNode, ParamOp::stage, id_of("supervisor.max_missed_ticks"), 1000),
               MessageId::param_reply, ErrorCode::commissioning_required);
  add(c, "enter commissioning while holding", command(kNode, CommandCode::enter_commissioning), MessageId::command_ack,
               ErrorCode::busy);
  // Bad axes.
  add(c, "zero axis past the list", command(kNode, CommandCode::zero, kPastTheList, 0, 1.0), MessageId::command_ack, ErrorCode::bad_axis, {}, 2u);
  add(c, "zero axis 255", command(kNode, CommandCode::zero, 255, 0, 1.0), MessageId::command_ack, ErrorCode::bad_axis);
  add(c, "select_controller axis 7", command(kNode, CommandCode::select_controller, 7, 0), MessageId::command_ack,
               ErrorCode::bad_axis, {}, 2u);
  add(c, "select_controller kind 3", command(kNode, CommandCode::select_controller, 0, 3), MessageId::command_ack,
               ErrorCode::out_of_range, {}, 3u);
  add(c, "shaper_enable axis past the list", command(kNode, CommandCode::shaper_enable, kPastTheList, 1), MessageId::command_ack,
               ErrorCode::bad_axis);
  add(c, "shaper_enable arg 2", command(kNode, CommandCode::shaper_enable, 0, 2), MessageId::command_ack,
               ErrorCode::out_of_range);
  add(c, "move axis past the list", move(kNode, kPastTheList, 10.0, 1.0), MessageId::command_ack, ErrorCode::bad_axis, {}, 1u);
  {
    hal::CanFrame f = frame_to(MessageId::shaper, kNode);
    set_raw(f, MessageId::shaper, "axis", 3);
    set_raw(f, MessageId::shaper, "type", 1);
    set_value(f, MessageId::shaper, "freq", 30.0);
    add(c, "shaper axis 3", f, MessageId::command_ack, ErrorCode::bad_axis, {}, 1u);
    set_raw(f, MessageId::shaper, "axis", 0);
    set_raw(f, MessageId::shaper, "type", 9);
    add(c, "shaper type 9", f, MessageId::command_ack, ErrorCode::out_of_range, {}, 2u);
    set_raw(f, MessageId::shaper, "type", 1);
    set_value(f, MessageId::shaper, "freq", 0.0);  // u16 at 0.01 Hz: NaN is not representable
    add(c, "shaper freq 0 Hz", f, MessageId::command_ack, ErrorCode::out_of_range, {}, 5u);
    set_value(f, MessageId::shaper, "freq", 1.0);
    add(c, "shaper freq 1 Hz", f, MessageId::command_ack, ErrorCode::out_of_range, {}, 5u);
  }
  // Motion requests with numbers that are not.
  add(c, "zero to NaN", command(kNode, CommandCode::zero, 0, 0, kNaN), MessageId::command_ack, ErrorCode::not_finite, {}, 4u);
  add(c, "zero beyond the soft limit", command(kNode, CommandCode::zero, 0, 0, 1e4), MessageId::command_ack,
               ErrorCode::out_of_range);
  add(c, "move distance inf", move(kNode, 0, 10.0, kInf), MessageId::command_ack, ErrorCode::not_finite, {}, 3u);
  add(c, "move speed 0", move(kNode, 0, 0.0, 1.0), MessageId::command_ack, ErrorCode::out_of_range, {}, 2u);
  add(c, "move beyond the soft limit", move(kNode, 0, 10.0, 400.0), MessageId::command_ack, ErrorCode::out_of_range);
  add(c, "circle radius NaN", circle(kNode, kNaN, 2.0), MessageId::command_ack, ErrorCode::not_finite, {}, 3u);
  add(c, "circle feed 0", circle(kNode, 6.0, 0.0), MessageId::command_ack, ErrorCode::out_of_range, {}, 2u);
  add(c, "circle radius -6", circle(kNode, -6.0, 2.0), MessageId::command_ack, ErrorCode::out_of_range, {}, 3u);
  add(c, "jog x beyond its limit", jog(kNode, 0, -300.0), MessageId::command_ack, ErrorCode::out_of_range, {}, 2u);
  add(c, "jog y beyond its limit", jog(kNode, 1, 300.0), MessageId::command_ack, ErrorCode::out_of_range, {}, 2u);
  add(c, "jog of an axis beyond the list", jog(kNode, static_cast<std::uint8_t>(hal::kAxisCount), 1.0),
      MessageId::command_ack, ErrorCode::bad_axis, {}, 1u);
  add(c, "jog of axis 255", jog(kNode, 255, 1.0), MessageId::command_ack, ErrorCode::bad_axis, {}, 1u);
  // Hosts: tag 0 is anonymous, and commands need command ownership (the bench's host 1 holds it).
  add(c, "enable from host 0", with_tag(command(kNode, CommandCode::enable), 0x01), MessageId::command_ack,
      ErrorCode::no_host);
  add(c, "get from host 0", with_tag(param_request(kNode, ParamOp::get, gamma), 0x00), MessageId::param_reply,
      ErrorCode::no_host);
  add(c, "disable from host 2", with_tag(command(kNode, CommandCode::disable), 0x21), MessageId::command_ack,
      ErrorCode::not_owner);
  add(c, "circle from host 2", with_tag(circle(kNode, 6.0, 2.0), 0x21), MessageId::command_ack, ErrorCode::not_owner);
  add(c, "set from host 2", with_tag(param_request(kNode, ParamOp::set, gamma, f32_raw(0.2f)), 0x21),
      MessageId::param_reply, ErrorCode::not_owner);
  add(c, "take ownership from host 2", with_tag(command(kNode, CommandCode::take_ownership), 0x21),
      MessageId::command_ack, ErrorCode::not_owner);
  // BORE_GAUGE with the planner off (the default): the op and the ownership are checked first.
  {
    hal::CanFrame f = frame_to(MessageId::bore_gauge, kNode);
    set_raw(f, MessageId::bore_gauge, "op", fw::can::kBoreOpCount);
    add(c, "bore op 3", f, MessageId::bore_infeed, ErrorCode::unknown_command, {}, 1u);
    set_raw(f, MessageId::bore_gauge, "op", static_cast<std::uint32_t>(fw::can::BoreOp::record));
    set_raw(f, MessageId::bore_gauge, "part", 1);
    add(c, "bore record from host 2", with_tag(f, 0x21), MessageId::bore_infeed, ErrorCode::not_owner, {}, 0u);
    add(c, "bore record, planner off", f, MessageId::bore_infeed, ErrorCode::not_ready, {}, 0u);
    set_raw(f, MessageId::bore_gauge, "op", static_cast<std::uint32_t>(fw::can::BoreOp::query));
    add(c, "bore query, planner off", with_tag(f, 0x21), MessageId::bore_infeed, ErrorCode::not_ready);
    add(c, "bore gauge from host 0", with_tag(f, 0x00), MessageId::bore_infeed, ErrorCode::no_host);
  }
  add(c, "upload 0 frames", capture_control(kNode, CaptureOp::upload, 0, 0), MessageId::capture_status,
               ErrorCode::out_of_range);
  add(c, "upload with no capture", capture_control(kNode, CaptureOp::upload, 4, 0), MessageId::capture_status,
               ErrorCode::not_ready);
  // Frames the node must ignore silently.
  add(c, "set for node 2", param_request(2, ParamOp::set, gamma, f32_raw(0.2f)), std::nullopt);
  add(c, "enable for node 31", command(31, CommandCode::enable), std::nullopt);
  add(c, "e-stop for node 2", frame_to(MessageId::estop, 2), std::nullopt);
  add(c, "heartbeat id sent to the node", frame_to(MessageId::heartbeat, kNode), std::nullopt);
  add(c, "command_ack id sent to the node", frame_to(MessageId::command_ack, kNode), std::nullopt);
  add(c, "param_reply id sent to the node", frame_to(MessageId::param_reply, kNode), std::nullopt);
  add(c, "capture_data id sent to the node", frame_to(MessageId::capture_data, kNode), std::nullopt);
  {
    hal::CanFrame f = param_request(kNode, ParamOp::set, gamma, f32_raw(0.2f));
    f.extended = true;
    add(c, "extended id with a set's bits", f, std::nullopt);
    hal::CanFrame e = frame_to(MessageId::estop, kNode);
    e.extended = true;
    add(c, "extended id with an e-stop's bits", e, std::nullopt);
    hal::CanFrame unknown = frame_to(MessageId::command, kNode);
    unknown.id = fw::can::make_can_id(0x1F, kNode);
    add(c, "unknown message id 0x1F", unknown, std::nullopt);
  }
  add(c, "set on broadcast", param_request(fw::can::kBroadcastNode, ParamOp::set, gamma, f32_raw(0.2f)), std::nullopt);
  add(c, "enable on broadcast", command(fw::can::kBroadcastNode, CommandCode::enable), std::nullopt);
  add(c, "circle on broadcast", circle(fw::can::kBroadcastNode, 6.0, 2.0), std::nullopt);
  return c;
}

TEST(CanNodeMalformed, EveryBadFrameIsAnsweredOrIgnoredAsTheProtocolSaysAndChangesNothing) {
  const std::vector<Case> all = cases();
  EXPECT_GE(all.size(), 80u);
  for (const Case& c : all) {
    SCOPED_TRACE(c.name);
    NodeBench b;
    // Not at power-up: servo on, holding (a state a stray frame could disturb).
    ASSERT_EQ(raw_of(b.reply(command(kNode, CommandCode::enable)), MessageId::command_ack, "result"), 0u);
    b.step(5);
    const Snapshot before = snapshot(b);
    const fw::can::NodeCounters counts_before = b.node->counters();
    const std::vector<hal::CanFrame> out = b.request(c.frame);
    b.step(2);  // anything applied "between ticks" would show now
    EXPECT_TRUE(snapshot(b) == before) << "state changed";
    EXPECT_TRUE(b.port.drain().empty()) << "late frames";
    if (!c.reply) {
      EXPECT_TRUE(out.empty()) << "answered a frame it must ignore";
      EXPECT_EQ(b.node->counters().rx_ignored, counts_before.rx_ignored + 1);
      continue;
    }
    ASSERT_EQ(out.size(), 1u);
    const hal::CanFrame& r = out[0];
    ASSERT_TRUE(is(r, *c.reply)) << "reply message " << int(fw::can::message_of(r.id));
    EXPECT_EQ(fw::can::node_of(r.id), kNode);
    EXPECT_EQ(r.dlc, 8);
    const char* result_field = "result";
    EXPECT_EQ(raw_of(r, *c.reply, result_field), static_cast<std::uint32_t>(c.result))
        << "got " << fw::can::to_string(static_cast<ErrorCode>(raw_of(r, *c.reply, result_field)));
    if (c.value) {
      EXPECT_EQ(raw_of(r, MessageId::param_reply, "value"), *c.value);
    }
    if (c.detail) {
      EXPECT_EQ(raw_of(r, *c.reply, "detail"), *c.detail);
    }
    if (*c.reply == MessageId::command_ack) {
      EXPECT_EQ(raw_of(r, MessageId::command_ack, "state"), static_cast<std::uint32_t>(fw::MotionState::holding));
      EXPECT_EQ(raw_of(r, MessageId::command_ack, "request"), fw::can::message_of(c.frame.id));
    }
    EXPECT_EQ(b.node->counters().requests_refused, counts_before.requests_refused + 1);
  }
}

TEST(CanNodeMalformed, EstopActsWhateverItsLengthAndOnBroadcast) {
  for (const std::uint8_t node : {kNode, fw::can::kBroadcastNode}) {
    for (const int dlc : {0, 3, 8}) {
      NodeBench b;
      b.reply(command(kNode, CommandCode::enable));
      hal::CanFrame f = frame_to(MessageId::estop, node);
      f.dlc = static_cast<std::uint8_t>(dlc);
      const std::vector<hal::CanFrame> out = b.request(f);
      EXPECT_EQ(b.task.fault().reason, fw::FaultReason::remote_estop) << "node " << int(node) << " dlc " << dlc;
      // Never acknowledged; the FAULT_EVENT tells.
      ASSERT_EQ(out.size(), 1u);
      EXPECT_TRUE(is(out[0], MessageId::fault_event));
      b.step();
      EXPECT_FALSE(b.board.written_enable[0]) << "outputs safe at the next tick";
    }
  }
}

}  // namespace
}  // namespace tnv::test
