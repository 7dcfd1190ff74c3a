// Tick discipline for every CAN message the node accepts (issue 15), table
// driven: for every to-node message of the protocol table (kMessages) and
// every value of its first enumerated field (every COMMAND code, every
// PARAM_REQUEST and CAPTURE_CONTROL op, every axis, ...) a valid frame is
// built from the field table; on a fresh bench holding position, its
// service() and the 50 ticks + services after it run under the allocation
// guard and, in a forked child, under the seccomp guard. Messages, codes
// and fields added to the table later are covered without touching this
// file: a new numeric field is sent as 0 unless kFieldValues names a value.
// The bench's boring planner is on (bore.enable), so BORE_GAUGE runs the
// planner; a record on a planner that is already learning (the RLS path,
// not the start-up) has its own test below.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/param_image.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/segment_wire.hpp"
#include "tests/hil/can_node_rig.hpp"
#include "tests/tick_alloc/alloc_guard.hpp"
#include "tests/tick_alloc/seccomp_guard.hpp"

namespace tnv::test {
namespace {

namespace can = fw::can;

constexpr int kTicksAfter = 50;

// Physical values for numeric fields, "message.field": what a host would
// send for a request that can be accepted while holding.
const std::map<std::string, double> kFieldValues = {
    {"jog.speed_x", 2.0},      {"jog.speed_y", -1.0},       {"move.speed", 5.0},
    {"move.distance", 2.0},    {"circle.radius", 6.0},      {"circle.feed", 2.0},
    {"shaper.zeta", 0.05},     {"shaper.freq", 30.0},       {"excite.duration", 0.1},
    {"excite.level", 5.0},     {"capture_control.frames", 4}, {"segment.x", 2.0},
    {"segment.y", 1.0},        {"segment_tail.feed", 5.0},
    {"bore_gauge.part", 1},    {"bore_gauge.top", 0.05},    {"bore_gauge.bottom", 0.17},
    {"spindle.rpm", 3000.0}};

// The parameter PARAM_REQUEST addresses, by name (its id and value come from the table).
constexpr const char* kParamName = "x.sliding.gamma";

// The values of an enumerated field ("0=a 1=b"), in order.
std::vector<std::uint32_t> enum_values(const can::FieldDef& f) {
  std::vector<std::uint32_t> out;
  const std::string_view v = f.values;
  for (std::size_t i = 0; i < v.size();) {
    const std::size_t end = v.find(' ', i);
    const std::string_view item = v.substr(i, end == std::string_view::npos ? v.size() - i : end - i);
    if (const std::size_t eq = item.find('='); eq != std::string_view::npos)
      out.push_back(static_cast<std::uint32_t>(std::strtol(std::string(item.substr(0, eq)).c_str(), nullptr, 10)));
    if (end == std::string_view::npos) break;
    i = end + 1;
  }
  return out;
}

struct MessageCase {
  const can::MessageDef* message;
  const can::FieldDef* selector;  // nullptr: the message has no enumerated field
  std::uint32_t selected;
  std::string name;
};

std::ostream& operator<<(std::ostream& os, const MessageCase& c) { return os << c.name; }

std::vector<MessageCase> message_cases() {
  std::vector<MessageCase> out;
  for (const can::MessageDef& m : can::kMessages) {
    if (m.direction != can::Direction::to_node) continue;
    const can::FieldDef* selector = nullptr;
    for (const can::FieldDef& f : m.fields)
      if (!enum_values(f).empty()) {
        selector = &f;
        break;
      }
    if (selector == nullptr) {
      out.push_back({&m, nullptr, 0, m.name});
      continue;
    }
    for (const std::uint32_t v : enum_values(*selector))
      out.push_back({&m, selector, v, std::string(m.name) + "_" + selector->name + "_" + std::to_string(v)});
  }
  return out;
}

hal::CanFrame frame_for(const MessageCase& c, const can::NodeSettings& live) {
  hal::CanFrame frame = can::make_frame(*c.message, kRigNode);
  for (const can::FieldDef& f : c.message->fields) {
    if (std::string_view(f.name) == "tag") {
      // The rig's test host, which holds command ownership (host 0 would be refused before any work).
      can::write_raw(frame, f, kTestTag);
    } else if (&f == c.selector) {
      can::write_raw(frame, f, c.selected);
    } else if (const auto values = enum_values(f); !values.empty()) {
      can::write_raw(frame, f, values.front());
    } else if (const auto it = kFieldValues.find(std::string(c.message->name) + "." + f.name); it != kFieldValues.end()) {
      can::write(frame, f, it->second);
    }
  }
  if (c.message->id == static_cast<std::uint8_t>(can::MessageId::param_request)) {
    const can::ParamDef& p = *can::find_param(kParamName);
    can::write_raw(frame, can::field(can::message(can::MessageId::param_request), "param"), p.id);
    can::write_raw(frame, can::field(can::message(can::MessageId::param_request), "value"), can::to_wire(p, p.get(live)));
  }
  return frame;
}

// A SEGMENT of a line or an arc is answered once its SEGMENT_TAIL (same tag) completes it: the case
// sends both frames.
std::optional<hal::CanFrame> companion_for(const MessageCase& c, const hal::CanFrame& head) {
  if (c.message->id != static_cast<std::uint8_t>(can::MessageId::segment)) return std::nullopt;
  if (!can::wire_kind_has_tail(static_cast<can::WireKind>(c.selected))) return std::nullopt;
  const MessageCase tail{&can::message(can::MessageId::segment_tail), nullptr, 0, "segment_tail"};
  hal::CanFrame f = frame_for(tail, can::NodeSettings{});
  f.data[0] = head.data[0];
  return f;
}

struct MessageBench {
  std::unique_ptr<CanRig> rig;
  hal::CanFrame frame{};
  std::optional<hal::CanFrame> companion;  // sent right after `frame`
  std::uint16_t answered_before = 0;
};

MessageBench holding_message_bench(const MessageCase& c) {
  MessageBench b;
  b.rig = CanRig::make();
  if (!b.rig) return b;
  // The rig's charged-time clock (a thread CPU-time read) is the rig's system call, not the firmware's.
  b.rig->rig->charging.enabled = false;
  b.rig->storage.bytes.reserve(can::kParamImageMaxBytes);  // the double's save then allocates nothing
  b.rig->task().hold_position();
  // The boring planner on: BORE_GAUGE runs it rather than answering not_ready.
  const can::ParamDef& bore = *can::find_param("bore.enable");
  b.rig->request(param_request(kRigNode, can::ParamOp::set, bore.id, can::to_wire(bore, 1.0)));
  for (int i = 0; i < 5; ++i) b.rig->step();
  b.rig->port.drain();
  b.frame = frame_for(c, b.rig->node->settings());
  b.companion = companion_for(c, b.frame);
  b.answered_before = b.rig->node->reply_sequence();
  return b;
}

// The frame, its service() and the ticks after it: what runs under the guards.
void exercise_message(MessageBench& b) noexcept {
  b.rig->port.to_node.push(b.frame);
  if (b.companion) b.rig->port.to_node.push(*b.companion);
  b.rig->node->service();
  for (int i = 0; i < kTicksAfter; ++i) b.rig->step();
}

// The node did something with it: an answer, or (e-stop, never answered) a latched fault.
bool message_handled(const MessageBench& b) noexcept {
  return b.rig->node->reply_sequence() != b.answered_before || b.rig->task().fault().active();
}

class CanMessages : public ::testing::TestWithParam<MessageCase> {};

TEST_P(CanMessages, ServiceAndTicksAllocateNothing) {
  MessageBench b = holding_message_bench(GetParam());
  ASSERT_TRUE(b.rig);
  const long heap_calls = heap_calls_in([&] { exercise_message(b); });
  EXPECT_TRUE(message_handled(b)) << "the node neither answered nor latched a fault";
  EXPECT_EQ(heap_calls, 0) << "heap calls while handling " << GetParam().name;
}

TEST_P(CanMessages, ServiceAndTicksMakeNoSystemCall) {
  if (!kSeccompUsable) GTEST_SKIP() << "the sanitizer runtime makes its own system calls; proven in the plain build";
  MessageBench b = holding_message_bench(GetParam());
  ASSERT_TRUE(b.rig);
  const int result = run_without_syscalls([&] {
    exercise_message(b);
    return message_handled(b) ? 0 : 3;
  });
  if (result == kSeccompUnavailable) GTEST_SKIP() << "seccomp is not available on this kernel";
  EXPECT_EQ(result, 0) << (result < 0 ? "killed by signal " + std::to_string(-result) + ": a system call"
                                      : "the node neither answered nor latched a fault");
}

// A record on a planner that has started: eq. (11), the variance
// perturbation and two RLS updates (eqs. (5), (6)), then eq. (3) twice.
MessageBench learning_planner_bench() {
  MessageCase record{&can::message(can::MessageId::bore_gauge), nullptr, 0, "bore_gauge_record_learning"};
  MessageBench b = holding_message_bench(record);
  if (!b.rig) return b;
  const can::MessageDef& m = can::message(can::MessageId::bore_gauge);
  hal::CanFrame first = b.frame;  // part 1: the start-up, outside the guards
  can::write_raw(first, can::field(m, "op"), static_cast<std::uint32_t>(can::BoreOp::record));
  const std::vector<hal::CanFrame> answer = b.rig->request(first);
  if (answer.size() != 1 || can::read_raw(answer[0], can::field(can::message(can::MessageId::bore_infeed), "result")) != 0)
    return MessageBench{};
  can::write_raw(b.frame, can::field(m, "op"), static_cast<std::uint32_t>(can::BoreOp::record));
  can::write_raw(b.frame, can::field(m, "part"), 2);
  b.answered_before = b.rig->node->reply_sequence();
  return b;
}

TEST(CanMessagesBoring, ARecordOnALearningPlannerAllocatesNothingAndMakesNoSystemCall) {
  MessageBench b = learning_planner_bench();
  ASSERT_TRUE(b.rig) << "the start-up part was not accepted";
  const int parts_before = b.rig->node->settings().bore_state.planner.parts;
  const long heap_calls = heap_calls_in([&] { exercise_message(b); });
  EXPECT_EQ(heap_calls, 0);
  EXPECT_EQ(b.rig->node->settings().bore_state.planner.parts, parts_before + 1) << "the part was recorded (RLS path)";
  if (!kSeccompUsable) GTEST_SKIP() << "the sanitizer runtime makes its own system calls; proven in the plain build";
  MessageBench c = learning_planner_bench();
  ASSERT_TRUE(c.rig);
  const int result = run_without_syscalls([&] {
    exercise_message(c);
    return c.rig->node->settings().bore_state.planner.parts == parts_before + 1 ? 0 : 3;
  });
  if (result == kSeccompUnavailable) GTEST_SKIP() << "seccomp is not available on this kernel";
  EXPECT_EQ(result, 0) << (result < 0 ? "killed by signal " + std::to_string(-result) + ": a system call"
                                      : "the part was not recorded");
}

INSTANTIATE_TEST_SUITE_P(Every, CanMessages, ::testing::ValuesIn(message_cases()),
                         [](const ::testing::TestParamInfo<MessageCase>& p) { return p.param.name; });

// The table really drives the cases: every to-node message is there, every
// COMMAND code among them, and most frames built this way are accepted.
TEST(CanMessagesTable, EveryToNodeMessageAndCommandCodeHasACase) {
  const std::vector<MessageCase> all = message_cases();
  for (const can::MessageDef& m : can::kMessages) {
    if (m.direction != can::Direction::to_node) continue;
    bool found = false;
    for (const MessageCase& c : all) found = found || c.message == &m;
    EXPECT_TRUE(found) << m.name;
  }
  int commands = 0;
  for (const MessageCase& c : all) commands += c.message->id == static_cast<std::uint8_t>(can::MessageId::command) ? 1 : 0;
  EXPECT_EQ(commands, can::kCommandCodeCount);
}

TEST(CanMessagesTable, TheBuiltFramesAreValidRequests) {
  // Each case's answer: a valid frame is refused only for a reason of state
  // (busy, faulted, not ready, cause present), never as malformed.
  for (const MessageCase& c : message_cases()) {
    if (c.message->id == static_cast<std::uint8_t>(can::MessageId::estop)) continue;
    MessageBench b = holding_message_bench(c);
    ASSERT_TRUE(b.rig);
    if (b.companion) {
      b.rig->port.send(b.frame);
      b.frame = *b.companion;
    }
    const std::vector<hal::CanFrame> out = b.rig->request_and_wait(b.frame);  // save/load answer later
    ASSERT_FALSE(out.empty()) << c.name << ": no answer";
    const can::MessageDef* reply = can::classify(out.front());
    ASSERT_NE(reply, nullptr) << c.name;
    auto result = can::ErrorCode::ok;  // answers without a result field (CAPTURE_DATA) carry no refusal
    for (const can::FieldDef& f : reply->fields)
      if (std::string_view(f.name) == "result") result = static_cast<can::ErrorCode>(can::read_raw(out.front(), f));
    EXPECT_NE(result, can::ErrorCode::bad_length) << c.name;
    EXPECT_NE(result, can::ErrorCode::unknown_command) << c.name;
    EXPECT_NE(result, can::ErrorCode::invalid) << c.name;
    EXPECT_NE(result, can::ErrorCode::out_of_range) << c.name;
    EXPECT_NE(result, can::ErrorCode::no_host) << c.name << ": refused before the handler ran";
    EXPECT_NE(result, can::ErrorCode::not_owner) << c.name << ": refused before the handler ran";
  }
}

}  // namespace
}  // namespace tnv::test
