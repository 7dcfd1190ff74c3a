// The force loop's parameters (arsc.*, 0x0060..0x006F) and TLM_ARSC over
// CAN: refused out of range or inconsistent with nothing changed, applied
// between two ticks (f* live, the rest at rest), and the telemetry the
// operator tunes with.
#include <gtest/gtest.h>

#include <limits>
#include <string_view>

#include "firmware/io/force_code.hpp"
#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

using fw::can::ErrorCode;
using fw::can::MessageId;
using fw::can::ParamOp;

ErrorCode arsc_result_of(const hal::CanFrame& r) {
  return static_cast<ErrorCode>(raw_of(r, MessageId::param_reply, "result"));
}

hal::CanFrame set_f32(std::uint8_t node, const char* name, float v, ParamOp op = ParamOp::set) {
  return param_request(node, op, id_of(name), f32_raw(v));
}

// A program along +X from where the table stands (the fake board does not move: keep it short).
void start_program(NodeBench& b) {
  fw::motion::SegmentRefusal why{};
  ASSERT_EQ(b.task.hold_position(), fw::CommandStatus::ok);
  b.step();
  const double x = b.task.last_record().axis[0].position_mm;
  ASSERT_EQ(b.task.push_segment(fw::motion::line_to({x + 50.0, 0.0}, 20.0), why), fw::CommandStatus::ok);
  b.step();
  ASSERT_TRUE(b.task.program_running());
}

TEST(CanNodeArsc, TheParametersAreInTheirIdBlock) {
  int count = 0;
  for (const fw::can::ParamDef& p : fw::can::param_table()) {
    const bool arsc = std::string_view(p.name).starts_with("arsc.") || std::string_view(p.name) == "tlm.arsc_ms";
    if (!arsc) continue;
    ++count;
    EXPECT_GE(p.id, 0x0060) << p.name;
    EXPECT_LE(p.id, 0x006F) << p.name;
    EXPECT_FALSE(fw::can::safety_param(p)) << p.name << ": the loop only sets a feed override";
  }
  EXPECT_EQ(count, 16);
}

TEST(CanNodeArsc, OutOfRangeValuesAreRefusedAndNothingChanges) {
  NodeBench b;
  const fw::arsc::ArscSourceParams before = b.task.config().arsc;
  struct Case {
    const char* name;
    hal::CanFrame frame;
  };
  const Case cases[] = {
      {"arsc.period_ticks", param_request(kNode, ParamOp::set, id_of("arsc.period_ticks"), 0)},
      {"arsc.period_ticks", param_request(kNode, ParamOp::set, id_of("arsc.period_ticks"), 501)},
      {"arsc.pole_re_rad_s", set_f32(kNode, "arsc.pole_re_rad_s", 1.0f)},
      {"arsc.pole_im_rad_s", set_f32(kNode, "arsc.pole_im_rad_s", -2.0f)},
      {"arsc.override_max", set_f32(kNode, "arsc.override_max", 1.6f)},
      {"arsc.override_min", set_f32(kNode, "arsc.override_min", -0.1f)},
      {"arsc.force_ref_n", set_f32(kNode, "arsc.force_ref_n", -5.0f)},
      {"arsc.gain_min_ratio", set_f32(kNode, "arsc.gain_min_ratio", 2.0f)},
      {"arsc.enable", param_request(kNode, ParamOp::set, id_of("arsc.enable"), 2)},
      {"tlm.arsc_ms", param_request(kNode, ParamOp::set, id_of("tlm.arsc_ms"), 60001)},
  };
  for (const Case& c : cases) {
    const double was = b.param(c.name);
    const hal::CanFrame r = b.reply(c.frame);
    EXPECT_EQ(arsc_result_of(r), ErrorCode::out_of_range) << c.name;
    EXPECT_EQ(b.param(c.name), was) << c.name;
  }
  const hal::CanFrame nan = set_f32(kNode, "arsc.memory_s", std::numeric_limits<float>::quiet_NaN());
  EXPECT_EQ(arsc_result_of(b.reply(nan)), ErrorCode::not_finite);
  const fw::arsc::ArscSourceParams after = b.task.config().arsc;
  EXPECT_EQ(after.period_ticks, before.period_ticks);
  EXPECT_EQ(after.pole_re_rad_s, before.pole_re_rad_s);
  EXPECT_EQ(after.override_max, before.override_max);
  EXPECT_FALSE(b.node->params_unsaved()) << "nothing was applied";
}

TEST(CanNodeArsc, AnInconsistentSetIsRefusedWholeAndTheParameterToBlameIsNamed) {
  NodeBench b;
  b.reply(set_f32(kNode, "arsc.override_min", 1.0f, ParamOp::stage));
  b.reply(set_f32(kNode, "arsc.override_max", 0.8f, ParamOp::stage));
  const hal::CanFrame c = b.reply(param_request(kNode, ParamOp::commit, 0));
  EXPECT_EQ(arsc_result_of(c), ErrorCode::invalid);
  EXPECT_EQ(raw_of(c, MessageId::param_reply, "value"), id_of("arsc.override_min"));
  EXPECT_EQ(b.task.config().arsc.override_min, 0.0) << "nothing applied";
  EXPECT_EQ(b.task.config().arsc.override_max, 1.5);
  b.reply(param_request(kNode, ParamOp::discard, 0));
  // Poles the loop cannot place at its model and 1 ms: no gains within the bound.
  const hal::CanFrame fast = b.reply(set_f32(kNode, "arsc.pole_re_rad_s", -5000.0f));
  EXPECT_EQ(arsc_result_of(fast), ErrorCode::invalid);
  EXPECT_EQ(b.task.config().arsc.pole_re_rad_s, -41.6);
}

TEST(CanNodeArsc, TheReferenceIsLiveTheRestWaitsForRest) {
  NodeBench b;
  EXPECT_EQ(arsc_result_of(b.reply(param_request(kNode, ParamOp::set, id_of("arsc.enable"), 1))), ErrorCode::ok);
  EXPECT_TRUE(b.task.feed_source().enabled());
  start_program(b);
  EXPECT_EQ(arsc_result_of(b.reply(set_f32(kNode, "arsc.force_ref_n", 120.0f))), ErrorCode::ok);
  EXPECT_EQ(b.task.feed_source().params().force_ref_n, 120.0) << "taken between two ticks, while cutting";
  EXPECT_EQ(arsc_result_of(b.reply(param_request(kNode, ParamOp::set, id_of("arsc.period_ticks"), 10))), ErrorCode::busy);
  EXPECT_EQ(arsc_result_of(b.reply(param_request(kNode, ParamOp::set, id_of("arsc.enable"), 0))), ErrorCode::busy);
  EXPECT_EQ(b.task.config().arsc.period_ticks, 1u);
  EXPECT_TRUE(b.task.feed_source().running());
}

TEST(CanNodeArsc, TlmArscCarriesForceReferenceOverrideAndEstimate) {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry.arsc_ms = 5;
  s.firmware.arsc.enabled = true;
  NodeBench b(s);
  b.board.force_code = 2048;  // about 150 N at 1/30 V per N
  start_program(b);
  b.port.drain();
  std::vector<hal::CanFrame> tlm;
  int ticks = 0;
  while (tlm.size() < 8 && ticks < 60) {  // up to the tick of the 8th frame: it carries that tick's record
    b.step();
    ++ticks;
    for (const hal::CanFrame& f : only(b.port.drain(), MessageId::tlm_arsc)) tlm.push_back(f);
  }
  ASSERT_EQ(tlm.size(), 8u);
  EXPECT_GE(ticks, 36) << "every 5 ticks";
  EXPECT_LE(ticks, 40) << "every 5 ticks";
  ASSERT_TRUE(b.task.program_running()) << fw::to_string(b.task.state()) << " " << fw::to_string(b.task.fault().reason);
  const hal::CanFrame& f = tlm.back();
  const fw::TickRecord& r = b.task.last_record();
  EXPECT_NEAR(value_of(f, MessageId::tlm_arsc, "force"), fw::force_code_to_n(2048, 30.0), 0.05);
  EXPECT_NEAR(value_of(f, MessageId::tlm_arsc, "force_ref"), r.arsc_force_ref_n, 0.05);
  EXPECT_GT(value_of(f, MessageId::tlm_arsc, "force_ref"), 0.0) << "the soft start has begun";
  EXPECT_NEAR(value_of(f, MessageId::tlm_arsc, "feed_override"), r.feed_override, 1e-4);
  EXPECT_NEAR(value_of(f, MessageId::tlm_arsc, "cutting_gain"), b.task.feed_source().status().cutting_gain_n_per_mm_s,
              1e-3);
  EXPECT_GT(value_of(f, MessageId::tlm_arsc, "cutting_gain"), 0.0);
}

TEST(CanNodeArsc, TlmArscIsZeroWhenTheLoopDoesNotRun) {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry.arsc_ms = 1;
  NodeBench b(s);
  b.step();
  const std::vector<hal::CanFrame> tlm = only(b.port.drain(), MessageId::tlm_arsc);
  ASSERT_EQ(tlm.size(), 1u);
  EXPECT_EQ(value_of(tlm[0], MessageId::tlm_arsc, "force_ref"), 0.0);
  EXPECT_EQ(value_of(tlm[0], MessageId::tlm_arsc, "cutting_gain"), 0.0);
  EXPECT_EQ(value_of(tlm[0], MessageId::tlm_arsc, "feed_override"), 1.0);
}

}  // namespace
}  // namespace tnv::test
