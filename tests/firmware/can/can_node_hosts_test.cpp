// Hosts on one node: request tags echoed, a staged set per host, command
// ownership taken, refused, released and lost on the owner's silence.
#include <gtest/gtest.h>

#include "firmware/can/request_tag.hpp"
#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::ErrorCode;
using fw::can::MessageId;
using fw::can::ParamOp;

constexpr std::uint8_t kHostA = 0x11;  // host 1 (holds ownership in the bench), sequence 1
constexpr std::uint8_t kHostB = 0x21;  // host 2

ErrorCode reply_result(const hal::CanFrame& r, MessageId id) { return static_cast<ErrorCode>(raw_of(r, id, "result")); }

hal::CanFrame stage(std::uint8_t tag, const char* name, double value) {
  const fw::can::ParamDef& p = *fw::can::find_param(name);
  return with_tag(param_request(kNode, ParamOp::stage, p.id, fw::can::to_wire(p, value)), tag);
}

TEST(CanNodeHosts, EachHostCommitsAndDiscardsOnlyItsOwnStagedSet) {
  NodeBench b;
  const double a_value = 0.3;
  const double b_value = 0.4;
  EXPECT_EQ(reply_result(b.reply(stage(kHostA, "x.sliding.gamma", a_value)), MessageId::param_reply), ErrorCode::ok);
  EXPECT_EQ(reply_result(b.reply(stage(kHostB, "y.sliding.gamma", b_value)), MessageId::param_reply), ErrorCode::ok);
  EXPECT_EQ(reply_result(b.reply(stage(kHostB, "x.sliding.g", 0.5)), MessageId::param_reply), ErrorCode::ok);
  EXPECT_EQ(b.node->staged_count(1), 1u);
  EXPECT_EQ(b.node->staged_count(2), 2u);
  // Host A (the owner) commits: its one parameter, not B's two.
  const hal::CanFrame commit = b.reply(with_tag(param_request(kNode, ParamOp::commit, 0), 0x1A));
  EXPECT_EQ(reply_result(commit, MessageId::param_reply), ErrorCode::ok);
  EXPECT_EQ(raw_of(commit, MessageId::param_reply, "param"), 1u) << "applied count";
  EXPECT_EQ(raw_of(commit, MessageId::param_reply, "tag"), 0x1Au);
  EXPECT_EQ(b.param("x.sliding.gamma"), static_cast<double>(static_cast<float>(a_value)));
  EXPECT_NE(b.param("y.sliding.gamma"), static_cast<double>(static_cast<float>(b_value))) << "B's stage applied";
  EXPECT_EQ(b.node->staged_count(2), 2u) << "B's set is untouched";
  // B discards: two dropped; A's commit now applies nothing and says so.
  const hal::CanFrame dropped = b.reply(with_tag(param_request(kNode, ParamOp::discard, 0), kHostB));
  EXPECT_EQ(raw_of(dropped, MessageId::param_reply, "param"), 2u);
  EXPECT_EQ(raw_of(b.reply(with_tag(param_request(kNode, ParamOp::commit, 0), kHostA)), MessageId::param_reply, "param"),
            0u);
  EXPECT_EQ(b.node->staged_count(), 0u);
}

TEST(CanNodeHosts, AFifthStagingHostIsBusyUntilASetIsFreed) {
  NodeBench b;
  for (std::uint8_t host = 1; host <= fw::can::kMaxStagingHosts; ++host)
    ASSERT_EQ(reply_result(b.reply(stage(fw::can::make_tag(host, 1), "x.sliding.gamma", 0.3)), MessageId::param_reply),
              ErrorCode::ok);
  const hal::CanFrame fifth = stage(fw::can::make_tag(5, 1), "x.sliding.gamma", 0.3);
  EXPECT_EQ(reply_result(b.reply(fifth), MessageId::param_reply), ErrorCode::busy);
  b.reply(with_tag(param_request(kNode, ParamOp::discard, 0), fw::can::make_tag(3, 2)));
  EXPECT_EQ(reply_result(b.reply(fifth), MessageId::param_reply), ErrorCode::ok);
}

TEST(CanNodeHosts, OwnershipIsTakenReleasedAndRefusedToOthers) {
  NodeBench b;  // host 1 holds it
  EXPECT_EQ(b.node->owner(), 1);
  EXPECT_EQ(reply_result(b.reply(with_tag(command(kNode, CommandCode::enable), kHostB)), MessageId::command_ack),
            ErrorCode::not_owner);
  EXPECT_EQ(b.task.state(), fw::MotionState::disabled) << "a refused command changed the state";
  EXPECT_EQ(reply_result(b.reply(with_tag(command(kNode, CommandCode::take_ownership), kHostB)), MessageId::command_ack),
            ErrorCode::not_owner);
  EXPECT_EQ(reply_result(b.reply(with_tag(command(kNode, CommandCode::release_ownership), kHostB)),
                      MessageId::command_ack),
            ErrorCode::not_owner);
  // Reads stay open to every host.
  EXPECT_EQ(reply_result(b.reply(with_tag(param_request(kNode, ParamOp::get, id_of("x.sliding.gamma")), kHostB)),
                      MessageId::param_reply),
            ErrorCode::ok);
  const hal::CanFrame released = b.reply(command(kNode, CommandCode::release_ownership));
  EXPECT_EQ(reply_result(released, MessageId::command_ack), ErrorCode::ok);
  EXPECT_EQ(raw_of(released, MessageId::command_ack, "owner"), 0u);
  EXPECT_EQ(reply_result(b.reply(command(kNode, CommandCode::enable)), MessageId::command_ack), ErrorCode::not_owner)
      << "nobody holds it: nobody may command";
  const hal::CanFrame taken = b.reply(with_tag(command(kNode, CommandCode::take_ownership), kHostB));
  EXPECT_EQ(reply_result(taken, MessageId::command_ack), ErrorCode::ok);
  EXPECT_EQ(raw_of(taken, MessageId::command_ack, "owner"), 2u);
  EXPECT_EQ(reply_result(b.reply(with_tag(command(kNode, CommandCode::enable), kHostB)), MessageId::command_ack),
            ErrorCode::ok);
}

TEST(CanNodeHosts, TheBroadcastStopNeedsNoOwnerAndNoHostId) {
  NodeBench b;
  b.reply(command(kNode, CommandCode::enable));
  b.reply(command(kNode, CommandCode::release_ownership));
  const hal::CanFrame stop = with_tag(command(fw::can::kBroadcastNode, CommandCode::stop), 0x00);
  const std::vector<hal::CanFrame> out = b.request(stop);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(reply_result(out[0], MessageId::command_ack), ErrorCode::ok);
}

TEST(CanNodeHosts, TheOwnerLosesOwnershipWhenSilentForTheHostTimeout) {
  fw::can::NodeSettings s = quiet_settings();
  s.can.host_timeout_ms = 50;
  NodeBench b(s);
  EXPECT_EQ(b.node->owner(), 1);
  b.step(30);
  b.reply(with_tag(param_request(kNode, ParamOp::get, id_of("x.sliding.gamma")), kHostB));  // B's frames don't count
  b.step(25);
  EXPECT_EQ(b.node->owner(), 0) << "host 1 was silent for 55 ms";
  EXPECT_EQ(reply_result(b.reply(command(kNode, CommandCode::enable)), MessageId::command_ack), ErrorCode::not_owner);
  EXPECT_EQ(reply_result(b.reply(with_tag(command(kNode, CommandCode::take_ownership), kHostB)), MessageId::command_ack),
            ErrorCode::ok);
}

}  // namespace
}  // namespace tnv::test
