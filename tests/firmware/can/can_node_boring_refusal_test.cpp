// BORE_GAUGE refused, with the planner on and learning under way: every bad
// frame gets BORE_INFEED with the code the protocol prescribes and the
// offending field, echoes the tag, shows the infeeds of the part being cut
// and changes nothing: the learned state, the parameters, the unsaved flag.
#include <gtest/gtest.h>

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "firmware/can/param_image.hpp"
#include "tests/firmware/can/bore_frames.hpp"

namespace tnv::test {
namespace {

using fw::can::BoreOp;
using fw::can::ErrorCode;
using fw::can::MessageId;

// A worker that takes a job and never runs it: a save stays in flight.
class HeldStorageWorker final : public hal::StorageWorker {
 public:
  bool post(hal::StorageJob&) noexcept override { return true; }
  bool done() noexcept override { return false; }
};

struct RefusalCase {
  std::string name;
  hal::CanFrame frame;
  ErrorCode result;
  std::uint32_t detail;
  bool planner_off = false;     // the node's bore.enable is off
  bool save_in_flight = false;  // a save_params waits for the storage worker
  bool fresh = false;           // nothing learned yet: the next part is the start-up part
};

hal::CanFrame with_reading_raw(hal::CanFrame f, const char* field, std::uint16_t raw) {
  set_raw(f, MessageId::bore_gauge, field, raw);
  return f;
}

constexpr int kPartsLearned = 5;

std::vector<RefusalCase> refusal_cases() {
  const hal::CanFrame next = bore_gauge(kNode, BoreOp::record, kPartsLearned + 1, 0.01, -0.02);
  hal::CanFrame short_frame = next;
  short_frame.dlc = 7;
  hal::CanFrame empty = next;
  empty.dlc = 0;
  hal::CanFrame op3 = next;
  set_raw(op3, MessageId::bore_gauge, "op", fw::can::kBoreOpCount);
  hal::CanFrame op255 = next;
  set_raw(op255, MessageId::bore_gauge, "op", 255);
  const auto no_reading = static_cast<std::uint16_t>(fw::can::kBoreNoReading);
  // A start-up bore error whose deflection d0 + delta / (2 cos 60 deg) is -0.0005 mm: no logarithm (eq. (10)).
  const double below_zero = s4_bore_error_mm(-0.0005);
  return {
      {"dlc 7", short_frame, ErrorCode::bad_length, 0},
      {"dlc 0", empty, ErrorCode::bad_length, 0},
      {"op 3", op3, ErrorCode::unknown_command, 1},
      {"op 255", op255, ErrorCode::unknown_command, 1},
      {"top: no reading", with_reading_raw(next, "top", no_reading), ErrorCode::not_finite, 3},
      {"bottom: no reading", with_reading_raw(next, "bottom", no_reading), ErrorCode::not_finite, 4},
      {"the last part again", bore_gauge(kNode, BoreOp::record, kPartsLearned, 0.01, -0.02), ErrorCode::out_of_range, 2},
      {"a part skipped", bore_gauge(kNode, BoreOp::record, kPartsLearned + 2, 0.01, -0.02), ErrorCode::out_of_range, 2},
      {"part 0", bore_gauge(kNode, BoreOp::record, 0, 0.01, -0.02), ErrorCode::out_of_range, 2},
      {"record from host 2", with_tag(next, 0x23), ErrorCode::not_owner, 0},
      {"restart from host 2", with_tag(bore_gauge(kNode, BoreOp::restart), 0x23), ErrorCode::not_owner, 0},
      {"record from host 0", with_tag(next, 0x03), ErrorCode::no_host, 0},
      {"record, planner off", next, ErrorCode::not_ready, 0, true},
      {"restart, planner off", bore_gauge(kNode, BoreOp::restart), ErrorCode::not_ready, 0, true},
      {"record during a save", next, ErrorCode::busy, 0, false, true},
      {"restart during a save", bore_gauge(kNode, BoreOp::restart), ErrorCode::busy, 0, false, true},
      {"start-up deflection below 0 at the bottom", bore_gauge(kNode, BoreOp::record, 1, 0.02, below_zero),
       ErrorCode::invalid, 4, false, false, true},
      {"start-up deflection below 0 at the top", bore_gauge(kNode, BoreOp::record, 1, below_zero, 0.02),
       ErrorCode::invalid, 3, false, false, true},
  };
}

std::vector<std::uint8_t> settings_image(const fw::can::NodeSettings& s) {
  std::vector<std::uint8_t> out(fw::can::kParamImageMaxBytes);
  out.resize(fw::can::encode_image(s, out));
  return out;
}

TEST(CanNodeBoringRefusal, EveryBadFrameIsRefusedWithItsCodeAndFieldAndChangesNothing) {
  for (const RefusalCase& c : refusal_cases()) {
    SCOPED_TRACE(c.name);
    HeldStorageWorker worker;
    NodeBench b(boring_settings(), false, &worker);
    if (!c.fresh) {
      hal::CanFrame q = b.reply(bore_gauge(kNode, BoreOp::query));
      for (int part = 1; part <= kPartsLearned; ++part) {
        const double top = value_of(q, MessageId::bore_infeed, "infeed_top");
        const double bottom = value_of(q, MessageId::bore_infeed, "infeed_bottom");
        q = b.reply(bore_gauge(kNode, BoreOp::record, static_cast<std::uint32_t>(part),
                               s4_bore_error_mm(s4_deflection_mm(part, top, 40.0, 0.02)),
                               s4_bore_error_mm(s4_deflection_mm(part, bottom, 310.0, 0.02))));
        ASSERT_EQ(raw_of(q, MessageId::bore_infeed, "result"), 0u);
      }
    }
    if (c.planner_off) {
      ASSERT_EQ(raw_of(b.reply(param_request(kNode, fw::can::ParamOp::set, id_of("bore.enable"), 0)),
                       MessageId::param_reply, "result"),
                0u);
    }
    if (c.save_in_flight) {
      EXPECT_TRUE(b.request(command(kNode, fw::can::CommandCode::save_params)).empty()) << "answered later";
      ASSERT_TRUE(b.node->storage_in_flight());
    }
    const hal::CanFrame before_query = b.reply(with_tag(bore_gauge(kNode, BoreOp::query), 0x2F));
    const std::vector<std::uint8_t> before = settings_image(b.node->settings());
    const bool unsaved = b.node->params_unsaved();
    const std::uint64_t refused = b.node->counters().requests_refused;

    const std::vector<hal::CanFrame> out = b.request(c.frame);
    ASSERT_EQ(out.size(), 1u);
    const hal::CanFrame& r = out[0];
    ASSERT_TRUE(is(r, MessageId::bore_infeed));
    EXPECT_EQ(r.dlc, 8);
    EXPECT_EQ(raw_of(r, MessageId::bore_infeed, "result"), static_cast<std::uint32_t>(c.result))
        << "got " << fw::can::to_string(static_cast<ErrorCode>(raw_of(r, MessageId::bore_infeed, "result")));
    EXPECT_EQ(raw_of(r, MessageId::bore_infeed, "detail"), c.detail);
    EXPECT_EQ(raw_of(r, MessageId::bore_infeed, "tag"), c.frame.dlc > 0 ? c.frame.data[0] : 0u);
    if (c.result != ErrorCode::not_ready) {
      for (const char* f : {"infeed_top", "infeed_bottom", "flags"})
        EXPECT_EQ(raw_of(r, MessageId::bore_infeed, f), raw_of(before_query, MessageId::bore_infeed, f)) << f;
    }
    EXPECT_EQ(settings_image(b.node->settings()), before) << "the learned state or a parameter changed";
    EXPECT_EQ(b.node->params_unsaved(), unsaved);
    EXPECT_EQ(b.node->counters().requests_refused, refused + 1);
  }
}

TEST(CanNodeBoringRefusal, TheCasesReachTheChecksTheyAreMeantFor) {
  // The refused frames, fixed, are accepted: the refusal came from the field named, not from elsewhere.
  NodeBench b(boring_settings());
  EXPECT_EQ(raw_of(b.reply(bore_gauge(kNode, BoreOp::record, 1, 0.02, 0.02)), MessageId::bore_infeed, "result"), 0u);
  EXPECT_EQ(raw_of(b.reply(bore_gauge(kNode, BoreOp::record, 2, 0.01, -0.02)), MessageId::bore_infeed, "result"), 0u);
  EXPECT_EQ(raw_of(b.reply(bore_gauge(kNode, BoreOp::restart)), MessageId::bore_infeed, "result"), 0u);
  // A reading of -32767 (-3.2767 mm) is a reading, not "none".
  hal::CanFrame f = bore_gauge(kNode, BoreOp::record, 1, 0.02, 0.02);
  set_raw(f, MessageId::bore_gauge, "top", 0x8001u);
  EXPECT_EQ(raw_of(b.reply(f), MessageId::bore_infeed, "result"), static_cast<std::uint32_t>(ErrorCode::invalid))
      << "-3.2767 mm of bore error is a negative start-up deflection: refused by eq. (10), not as no reading";
}

TEST(CanNodeBoringRefusal, BoreParametersAreCheckedLikeEveryOtherAndTheLearningStays) {
  NodeBench b(boring_settings());
  ASSERT_EQ(raw_of(b.reply(bore_gauge(kNode, BoreOp::record, 1, 0.0485, 0.1689)), MessageId::bore_infeed, "result"), 0u);
  const std::vector<std::uint8_t> before = settings_image(b.node->settings());
  struct Bad {
    const char* param;
    std::uint32_t raw;
    ErrorCode result;
  };
  const Bad bad[] = {
      {"bore.d0_mm", f32_raw(std::numeric_limits<float>::quiet_NaN()), ErrorCode::not_finite},
      {"bore.sigma_d_mm", f32_raw(std::numeric_limits<float>::infinity()), ErrorCode::not_finite},
      {"bore.s0_mm_rev", f32_raw(1.5f), ErrorCode::out_of_range},
      {"bore.force_angle_deg", f32_raw(90.0f), ErrorCode::out_of_range},
      {"bore.gain_form", 3, ErrorCode::out_of_range},
      {"bore.reset_after", 0, ErrorCode::out_of_range},
      {"bore.l2_mm", f32_raw(40.5f), ErrorCode::invalid},  // 0.5 mm from L1: eq. (10) needs two overhangs
      {"bore.parts", 7, ErrorCode::read_only},
      {"bore.alpha_hat", f32_raw(0.5f), ErrorCode::read_only},
  };
  for (const Bad& c : bad) {
    const hal::CanFrame r = b.reply(param_request(kNode, fw::can::ParamOp::set, id_of(c.param), c.raw));
    EXPECT_EQ(raw_of(r, MessageId::param_reply, "result"), static_cast<std::uint32_t>(c.result)) << c.param;
    EXPECT_EQ(settings_image(b.node->settings()), before) << c.param << ": something changed";
  }
  // The cross-field refusal names the parameter to blame in a commit.
  b.reply(param_request(kNode, fw::can::ParamOp::stage, id_of("bore.l1_mm"), f32_raw(100.0f)));
  b.reply(param_request(kNode, fw::can::ParamOp::stage, id_of("bore.l2_mm"), f32_raw(100.5f)));
  const hal::CanFrame commit = b.reply(param_request(kNode, fw::can::ParamOp::commit, 0));
  EXPECT_EQ(raw_of(commit, MessageId::param_reply, "result"), static_cast<std::uint32_t>(ErrorCode::invalid));
  EXPECT_EQ(raw_of(commit, MessageId::param_reply, "value"), id_of("bore.l2_mm"));
  EXPECT_EQ(settings_image(b.node->settings()), before);
}

}  // namespace
}  // namespace tnv::test
