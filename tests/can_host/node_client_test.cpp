// The client against a scripted node: timeouts name the request and the
// node, refusals name the ErrorCode and the parameter, foreign frames are
// ignored, and a capture upload recovers from lost frames.
#include <gtest/gtest.h>

#include "firmware/can/request_tag.hpp"

#include "firmware/can/can_id.hpp"
#include "tests/can_host/scripted_node_bus.hpp"
#include "tools/can/node_client.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
using can::field;
using can::message;
using can::MessageId;
using can_host::NodeClient;
using can_host::RequestError;
using test::ScriptedNodeBus;

constexpr std::uint8_t kNode = 3;
const can::ParamDef& gamma_x() { return *can::find_param("x.sliding.gamma"); }

// A PARAM_REPLY echoing `req`'s tag.
hal::CanFrame param_reply(std::uint8_t node, const hal::CanFrame& req, can::ErrorCode result, std::uint16_t param,
                          std::uint32_t value) {
  constexpr const can::MessageDef& m = message(MessageId::param_reply);
  hal::CanFrame f = can::make_frame(m, node);
  can::write_raw(f, field(m, "tag"), req.data[0]);
  can::write_raw(f, field(m, "result"), static_cast<std::uint32_t>(result));
  can::write_raw(f, field(m, "param"), param);
  can::write_raw(f, field(m, "value"), value);
  return f;
}

hal::CanFrame heartbeat(std::uint8_t node, fw::MotionState state) {
  constexpr const can::MessageDef& m = message(MessageId::heartbeat);
  hal::CanFrame f = can::make_frame(m, node);
  can::write_raw(f, field(m, "state"), static_cast<std::uint32_t>(state));
  return f;
}

std::string message_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const RequestError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(NodeClient, ATimeoutNamesTheReplyTheNodeTheRequestAndTheWait) {
  ScriptedNodeBus bus;  // nobody answers
  NodeClient client(bus, kNode);
  const std::string e = message_of([&] { client.get(gamma_x()); });
  EXPECT_NE(e.find("no PARAM_REPLY from node 3"), std::string::npos) << e;
  EXPECT_NE(e.find("'get x.sliding.gamma'"), std::string::npos) << e;
  EXPECT_NE(e.find("250 ms"), std::string::npos) << e;
  EXPECT_NE(e.find("scripted bus"), std::string::npos) << e;
  EXPECT_GE(bus.now().count(), 250'000) << "the wait must last the whole timeout";
}

TEST(NodeClient, ARefusalNamesTheErrorCodeTheParameterAndItsRange) {
  ScriptedNodeBus bus;
  bus.on_request = [](const hal::CanFrame& req, ScriptedNodeBus& b) {
    const std::uint32_t unchanged = can::float_bits(0.3f);
    b.reply(param_reply(kNode, req, can::ErrorCode::out_of_range, gamma_x().id, unchanged));
  };
  can_host::ClientOptions no_take;
  no_take.take_ownership_when_needed = false;
  NodeClient client(bus, kNode, no_take);
  try {
    client.set(gamma_x(), 2.0);
    FAIL() << "expected a refusal";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.kind(), RequestError::Kind::refused);
    EXPECT_EQ(e.code(), can::ErrorCode::out_of_range);
    const std::string m = e.what();
    EXPECT_NE(m.find("node 3 refused 'set x.sliding.gamma = 2': out_of_range"), std::string::npos) << m;
    EXPECT_NE(m.find("range 0 .. 1"), std::string::npos) << m;
    EXPECT_NE(m.find("value now 0.3"), std::string::npos) << m;
  }
}

TEST(NodeClient, FramesOfOtherNodesOtherMessagesAndBadLengthAreNotTakenAsTheReply) {
  ScriptedNodeBus bus;
  bus.on_request = [](const hal::CanFrame& req, ScriptedNodeBus& b) {
    const std::uint32_t wrong = can::float_bits(0.9f);
    b.reply(param_reply(kNode + 1, req, can::ErrorCode::ok, gamma_x().id, wrong));  // other node
    hal::CanFrame short_frame = param_reply(kNode, req, can::ErrorCode::ok, gamma_x().id, wrong);
    short_frame.dlc = 7;
    b.reply(short_frame);                                                                     // malformed
    b.reply(param_reply(kNode, req, can::ErrorCode::ok, gamma_x().id + 1, wrong));  // other param
    b.reply(heartbeat(kNode, fw::MotionState::holding));
    b.reply(param_reply(kNode, req, can::ErrorCode::ok, gamma_x().id, can::float_bits(0.25f)));
  };
  NodeClient client(bus, kNode);
  EXPECT_EQ(client.get(gamma_x()), 0.25);
  ASSERT_TRUE(client.last_heartbeat().has_value()) << "the heartbeat seen while waiting is kept";
  EXPECT_EQ(client.last_heartbeat()->state, fw::MotionState::holding);
}

// A stale reply (an earlier tag of this host) and another host's reply to the
// same parameter come first: neither is taken, both are counted.
TEST(NodeClient, RepliesWithAnotherTagAreDiscardedAndCounted) {
  ScriptedNodeBus bus;
  bus.on_request = [](const hal::CanFrame& req, ScriptedNodeBus& b) {
    const std::uint32_t wrong = can::float_bits(0.9f);
    hal::CanFrame stale_req = req;
    stale_req.data[0] = static_cast<std::uint8_t>((req.data[0] & 0xF0u) | ((req.data[0] - 1u) & 0x0Fu));
    b.reply(param_reply(kNode, stale_req, can::ErrorCode::ok, gamma_x().id, wrong));
    hal::CanFrame other_host = req;
    other_host.data[0] = static_cast<std::uint8_t>(0x20u | (req.data[0] & 0x0Fu));
    b.reply(param_reply(kNode, other_host, can::ErrorCode::ok, gamma_x().id, wrong));
    b.reply(param_reply(kNode, req, can::ErrorCode::ok, gamma_x().id, can::float_bits(0.25f)));
  };
  NodeClient client(bus, kNode);
  EXPECT_EQ(client.get(gamma_x()), 0.25);
  EXPECT_EQ(client.replies_discarded(), 2u);
  EXPECT_EQ(can::host_of_tag(bus.sent.back().data[0]), 1) << "host id 1 by default";
}

TEST(NodeClient, ACommandRefusalNamesTheCodeAndTheState) {
  ScriptedNodeBus bus;
  bus.on_request = [](const hal::CanFrame& req, ScriptedNodeBus& b) {
    constexpr const can::MessageDef& m = message(MessageId::command_ack);
    hal::CanFrame f = can::make_frame(m, kNode);
    can::write_raw(f, field(m, "tag"), req.data[0]);
    can::write_raw(f, field(m, "request"), can::message_of(req.id));
    can::write_raw(f, field(m, "result"), static_cast<std::uint32_t>(can::ErrorCode::busy));
    can::write_raw(f, field(m, "state"), static_cast<std::uint32_t>(fw::MotionState::moving));
    b.reply(f);
  };
  can_host::ClientOptions no_take;
  no_take.take_ownership_when_needed = false;
  NodeClient client(bus, kNode, no_take);
  const std::string e = message_of([&] { client.circle(6.0, 2.0); });
  EXPECT_NE(e.find("refused 'circle radius 6 mm at 2 mm/s': busy (state moving)"), std::string::npos) << e;
}

TEST(NodeClient, AFaultedRefusalNamesTheFaultAndTheAxisOfItsFaultEvent) {
  ScriptedNodeBus bus;
  bus.on_request = [](const hal::CanFrame& req, ScriptedNodeBus& b) {
    constexpr const can::MessageDef& ev = message(MessageId::fault_event);
    hal::CanFrame e = can::make_frame(ev, kNode);
    can::write_raw(e, field(ev, "reason"), static_cast<std::uint32_t>(fw::FaultReason::encoder_error));
    can::write_raw(e, field(ev, "axis"), 1);
    b.reply(e);
    constexpr const can::MessageDef& m = message(MessageId::command_ack);
    hal::CanFrame f = can::make_frame(m, kNode);
    can::write_raw(f, field(m, "tag"), req.data[0]);
    can::write_raw(f, field(m, "request"), can::message_of(req.id));
    can::write_raw(f, field(m, "result"), static_cast<std::uint32_t>(can::ErrorCode::faulted));
    can::write_raw(f, field(m, "state"), static_cast<std::uint32_t>(fw::MotionState::faulted));
    can::write_raw(f, field(m, "fault"), static_cast<std::uint32_t>(fw::FaultReason::encoder_error));
    b.reply(f);
  };
  can_host::ClientOptions no_take;
  no_take.take_ownership_when_needed = false;
  NodeClient client(bus, kNode, no_take);
  const std::string e = message_of([&] { client.circle(6.0, 2.0); });
  EXPECT_NE(e.find("faulted (state faulted, fault encoder_error, axis y)"), std::string::npos) << e;
}

// A node holding `image`, answering uploads; `drop(request, sequence)` loses frames.
struct UploadNode {
  std::vector<std::uint8_t> image;
  std::function<bool(int request, int sequence)> drop = [](int, int) { return false; };
  std::vector<std::pair<std::uint32_t, int>> requests;  // offset, frames

  void operator()(const hal::CanFrame& req, ScriptedNodeBus& b) {
    constexpr const can::MessageDef& control = message(MessageId::capture_control);
    constexpr const can::MessageDef& data = message(MessageId::capture_data);
    const auto offset = can::read_raw(req, field(control, "offset"));
    const auto frames = static_cast<int>(can::read_raw(req, field(control, "frames")));
    const int index = static_cast<int>(requests.size());
    requests.emplace_back(offset, frames);
    for (int s = 0; s < frames; ++s) {
      if (drop(index, s)) continue;
      hal::CanFrame f = can::make_frame(data, kNode);
      can::write_raw(f, field(data, "sequence"), static_cast<std::uint32_t>(s));
      std::array<std::uint8_t, 7> bytes{};
      for (std::size_t i = 0; i < 7; ++i) {
        const std::size_t at = offset + static_cast<std::size_t>(s) * 7 + i;
        bytes[i] = at < image.size() ? image[at] : 0;
      }
      can::write_bytes(f, field(data, "data"), bytes);
      b.reply(f);
    }
  }
};

can_host::CaptureStatus status_for(std::size_t bytes) {
  can_host::CaptureStatus s;
  s.state = can::CaptureState::done;
  s.channels = 2;
  s.decimation = 1;
  s.samples = static_cast<std::uint32_t>(bytes / 8);
  return s;
}

std::vector<std::uint8_t> pattern(std::size_t n) {
  std::vector<std::uint8_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<std::uint8_t>((i * 37 + 11) & 0xFF);
  return v;
}

TEST(NodeClient, UploadReassemblesBlocksAndReRequestsFromADroppedFrame) {
  auto node = std::make_shared<UploadNode>();
  node->image = pattern(8 * 500);  // 500 samples x 2 channels: 4000 bytes, 572 frames, 3 blocks
  node->drop = [](int request, int sequence) { return request == 1 && sequence == 17; };
  ScriptedNodeBus bus;
  bus.on_request = [node](const hal::CanFrame& f, ScriptedNodeBus& b) { (*node)(f, b); };
  NodeClient client(bus, kNode);
  const std::vector<std::uint8_t> got = client.upload(status_for(node->image.size()));
  EXPECT_EQ(got, node->image);
  EXPECT_EQ(client.upload_rerequests(), 1u);
  ASSERT_GE(node->requests.size(), 3u);
  EXPECT_EQ(node->requests[0].first, 0u);
  EXPECT_EQ(node->requests[0].second, 255);
  EXPECT_EQ(node->requests[1].first, 255u * 7);
  EXPECT_EQ(node->requests[2].first, (255u + 17u) * 7) << "re-requested from the first missing frame";
}

TEST(NodeClient, UploadRecoversALostLastFrameAfterTheTimeout) {
  auto node = std::make_shared<UploadNode>();
  node->image = pattern(8 * 50);  // one block of 58 frames
  node->drop = [](int request, int sequence) { return request == 0 && sequence == 57; };
  ScriptedNodeBus bus;
  bus.on_request = [node](const hal::CanFrame& f, ScriptedNodeBus& b) { (*node)(f, b); };
  NodeClient client(bus, kNode);
  EXPECT_EQ(client.upload(status_for(node->image.size())), node->image);
  ASSERT_EQ(node->requests.size(), 2u);
  EXPECT_EQ(node->requests[1].first, 57u * 7);
  EXPECT_EQ(node->requests[1].second, 1);
}

TEST(NodeClient, AnUploadThatNeverProgressesGivesUpNamingTheByte) {
  auto node = std::make_shared<UploadNode>();
  node->image = pattern(8 * 50);
  node->drop = [](int request, int sequence) { return request > 0 || sequence >= 10; };  // stuck at frame 10
  ScriptedNodeBus bus;
  bus.on_request = [node](const hal::CanFrame& f, ScriptedNodeBus& b) { (*node)(f, b); };
  NodeClient client(bus, kNode);
  const std::string e = message_of([&] { client.upload(status_for(node->image.size())); });
  EXPECT_NE(e.find("stalled at byte 70 of 400"), std::string::npos) << e;
  EXPECT_EQ(static_cast<int>(node->requests.size()), 1 + client.options().upload_retries + 1);
}

TEST(NodeClient, AnUploadRefusalIsSurfacedWithItsCode) {
  ScriptedNodeBus bus;
  bus.on_request = [](const hal::CanFrame& req, ScriptedNodeBus& b) {
    constexpr const can::MessageDef& m = message(MessageId::capture_status);
    hal::CanFrame f = can::make_frame(m, kNode);
    can::write_raw(f, field(m, "tag"), req.data[0]);
    can::write_raw(f, field(m, "result"), static_cast<std::uint32_t>(can::ErrorCode::not_ready));
    b.reply(f);
  };
  NodeClient client(bus, kNode);
  const std::string e = message_of([&] { client.upload(status_for(80)); });
  EXPECT_NE(e.find("refused 'capture upload' at byte 0: not_ready"), std::string::npos) << e;
}

TEST(NodeClient, WaitAtRestFollowsTheHeartbeatUntilTheMotionEnds) {
  ScriptedNodeBus bus;
  bus.reply(heartbeat(kNode, fw::MotionState::dwell));
  bus.reply(heartbeat(kNode, fw::MotionState::moving));
  bus.reply(heartbeat(kNode, fw::MotionState::holding));
  NodeClient client(bus, kNode);
  EXPECT_EQ(client.wait_at_rest(can_host::Micros{1'000'000}).state, fw::MotionState::holding);
  const std::string e = message_of([&] { client.wait_at_rest(can_host::Micros{500'000}); });
  EXPECT_NE(e.find("node 3 still moving after 500 ms"), std::string::npos) << e;
}

}  // namespace
}  // namespace tnv
