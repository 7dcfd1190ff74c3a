// PARAM_REQUEST get / set / stage / commit / discard on a node at rest.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

using fw::can::ErrorCode;
using fw::can::MessageId;
using fw::can::ParamOp;

ErrorCode result_of(const hal::CanFrame& r) { return static_cast<ErrorCode>(raw_of(r, MessageId::param_reply, "result")); }
std::uint32_t value_of_reply(const hal::CanFrame& r) { return raw_of(r, MessageId::param_reply, "value"); }

TEST(CanNodeParams, GetReadsBackEveryParameterOfTheTable) {
  NodeBench b;
  for (const fw::can::ParamDef& p : fw::can::param_table()) {
    const hal::CanFrame r = b.reply(param_request(kNode, ParamOp::get, p.id));
    ASSERT_TRUE(is(r, MessageId::param_reply)) << p.name;
    EXPECT_EQ(result_of(r), ErrorCode::ok) << p.name;
    EXPECT_EQ(raw_of(r, MessageId::param_reply, "param"), p.id);
    EXPECT_EQ(value_of_reply(r), fw::can::to_wire(p, p.get(b.node->settings()))) << p.name;
  }
  const hal::CanFrame v = b.reply(param_request(kNode, ParamOp::get, id_of("sys.protocol_version")));
  EXPECT_EQ(value_of_reply(v), fw::can::kProtocolVersion);
}

// The commit of the source tree, as `git rev-parse --short=8 HEAD` prints
// it; nullopt where git cannot tell (no git, not a checkout).
std::optional<std::uint32_t> source_commit() {
  // Built up in place: GCC 12 at -O1 takes `std::string(...) + TNV_SOURCE_DIR + ...`
  // for an out-of-bounds copy (-Warray-bounds, a known false positive).
  std::string command = "git -C '";
  command.append(TNV_SOURCE_DIR).append("' rev-parse --short=8 HEAD 2>/dev/null");
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return std::nullopt;
  char text[64] = {};
  const bool read = std::fgets(text, sizeof text, pipe) != nullptr;
  ::pclose(pipe);
  char* end = nullptr;
  const unsigned long value = read ? std::strtoul(text, &end, 16) : 0;
  if (!read || end != text + 8) return std::nullopt;
  return static_cast<std::uint32_t>(value);
}

TEST(CanNodeParams, ReportsItsFirmwareVersionAndTheCommitItWasBuiltFrom) {
  NodeBench b;
  const hal::CanFrame version = b.reply(param_request(kNode, ParamOp::get, id_of("sys.firmware_version")));
  EXPECT_EQ(result_of(version), ErrorCode::ok);
  EXPECT_EQ(value_of_reply(version), std::uint32_t{TNV_EXPECTED_FIRMWARE_VERSION}) << "the project's version";
  const hal::CanFrame build = b.reply(param_request(kNode, ParamOp::get, id_of("sys.build_id")));
  EXPECT_EQ(result_of(build), ErrorCode::ok);
  // The build read the commit of the tree it compiled; this test reads the
  // same tree's now (equal unless a commit happened since the build).
  if (const std::optional<std::uint32_t> commit = source_commit()) {
    EXPECT_EQ(value_of_reply(build), *commit);
  }
  // Read-only: a set is refused and changes nothing.
  const hal::CanFrame set = b.reply(param_request(kNode, ParamOp::set, id_of("sys.build_id"), 7));
  EXPECT_EQ(result_of(set), ErrorCode::read_only);
  EXPECT_EQ(value_of_reply(b.reply(param_request(kNode, ParamOp::get, id_of("sys.build_id")))), value_of_reply(build));
}

TEST(CanNodeParams, SetStoresExactlyTheFloatThatArrivedAndTheControllerGetsIt) {
  NodeBench b;
  const float gamma = 0.3141f;
  const hal::CanFrame r = b.reply(param_request(kNode, ParamOp::set, id_of("x.sliding.gamma"), f32_raw(gamma)));
  EXPECT_EQ(result_of(r), ErrorCode::ok);
  EXPECT_EQ(value_of_reply(r), f32_raw(gamma));
  EXPECT_EQ(b.node->settings().firmware.axis[0].sliding.gamma, static_cast<double>(gamma));
  EXPECT_EQ(b.task.config().axis[0].sliding.gamma, static_cast<double>(gamma));
  EXPECT_EQ(b.task.sliding_params(hal::Axis::x).gamma, static_cast<double>(gamma)) << "the controller itself";
  EXPECT_TRUE(b.node->params_unsaved());
  EXPECT_NE(b.node->heartbeat_errors() & fw::can::kHbParamsUnsaved, 0);
}

TEST(CanNodeParams, IntegerAndEnumerationParametersTravelAsIntegers) {
  NodeBench b;
  EXPECT_EQ(result_of(b.reply(param_request(kNode, ParamOp::set, id_of("tlm.position_ms"), 25))), ErrorCode::ok);
  EXPECT_EQ(b.node->settings().telemetry.position_ms, 25u);
  EXPECT_EQ(result_of(b.reply(param_request(kNode, ParamOp::set, id_of("y.controller"), 0))), ErrorCode::ok);
  EXPECT_EQ(b.task.controller(hal::Axis::y), fw::ControllerKind::pid) << "selected at rest";
  EXPECT_EQ(b.task.controller(hal::Axis::x), fw::ControllerKind::rdvsc);
}

TEST(CanNodeParams, RestartParametersAreStoredButTheNodeKeepsItsIdUntilTheNextStart) {
  NodeBench b;
  const hal::CanFrame r = b.reply(param_request(kNode, ParamOp::set, id_of("can.node_id"), 9));
  EXPECT_EQ(result_of(r), ErrorCode::ok);
  EXPECT_EQ(b.node->settings().can.node_id, 9u);
  EXPECT_EQ(b.node->node_id(), kNode);
  EXPECT_TRUE(is(b.reply(param_request(kNode, ParamOp::get, id_of("can.node_id"))), MessageId::param_reply))
      << "still answers on the old id";
  EXPECT_TRUE(b.request(param_request(9, ParamOp::get, id_of("can.node_id"))).empty());
}

TEST(CanNodeParams, StagedValuesApplyOnlyAtCommitAndTheReplyCountsThem) {
  NodeBench b;
  const double kp0 = b.param("x.pid.kp");
  const hal::CanFrame s1 = b.reply(param_request(kNode, ParamOp::stage, id_of("x.pid.kp"), f32_raw(400.0f)));
  EXPECT_EQ(result_of(s1), ErrorCode::ok);
  EXPECT_EQ(value_of_reply(s1), f32_raw(400.0f)) << "the staged value read back";
  b.reply(param_request(kNode, ParamOp::stage, id_of("x.pid.kp"), f32_raw(450.0f)));  // overwrites
  b.reply(param_request(kNode, ParamOp::stage, id_of("x.pid.kd"), f32_raw(2.0f)));
  b.step(3);
  EXPECT_EQ(b.param("x.pid.kp"), kp0) << "nothing applied before commit";
  EXPECT_EQ(b.node->staged_count(), 2u);
  EXPECT_NE(b.node->heartbeat_errors() & fw::can::kHbParamsStaged, 0);
  const hal::CanFrame c = b.reply(param_request(kNode, ParamOp::commit, 0));
  EXPECT_EQ(result_of(c), ErrorCode::ok);
  EXPECT_EQ(raw_of(c, MessageId::param_reply, "param"), 2u);
  EXPECT_EQ(b.task.pid_params(hal::Axis::x).kp, 450.0);
  EXPECT_EQ(b.task.pid_params(hal::Axis::x).kd, 2.0);
  EXPECT_EQ(b.node->staged_count(), 0u);
  EXPECT_EQ(b.node->heartbeat_errors() & fw::can::kHbParamsStaged, 0);
}

TEST(CanNodeParams, AnInvalidStagedSetIsRefusedWholeAndStaysPendingUntilDiscarded) {
  NodeBench b;
  const fw::SlidingModeParams before = b.task.sliding_params(hal::Axis::x);
  // Each in range; together phi < eta / (q + 1) (S1 Theorem 2).
  b.reply(param_request(kNode, ParamOp::stage, id_of("x.sliding.gamma"), f32_raw(0.05f)));
  b.reply(param_request(kNode, ParamOp::stage, id_of("x.sliding.eta_mm_s"), f32_raw(2.0f)));
  b.reply(param_request(kNode, ParamOp::stage, id_of("x.sliding.phi_mm_s"), f32_raw(0.5f)));
  const hal::CanFrame c = b.reply(param_request(kNode, ParamOp::commit, 0));
  EXPECT_EQ(result_of(c), ErrorCode::invalid);
  EXPECT_EQ(raw_of(c, MessageId::param_reply, "param"), 3u);
  EXPECT_EQ(value_of_reply(c), id_of("x.sliding.phi_mm_s")) << "the parameter to blame";
  const fw::SlidingModeParams after = b.task.sliding_params(hal::Axis::x);
  EXPECT_EQ(after.gamma, before.gamma) << "the valid part was not applied either";
  EXPECT_EQ(after.eta_mm_s, before.eta_mm_s);
  EXPECT_EQ(b.node->settings().firmware.axis[0].sliding.gamma, before.gamma);
  EXPECT_EQ(b.node->staged_count(), 3u);
  const hal::CanFrame d = b.reply(param_request(kNode, ParamOp::discard, 0));
  EXPECT_EQ(result_of(d), ErrorCode::ok);
  EXPECT_EQ(raw_of(d, MessageId::param_reply, "param"), 3u);
  EXPECT_EQ(b.node->staged_count(), 0u);
  EXPECT_FALSE(b.node->params_unsaved());
}

TEST(CanNodeParams, CaptureSettingsAreBusyWhileACaptureIsArmed) {
  NodeBench b;
  b.reply(capture_control(kNode, fw::can::CaptureOp::arm));
  ASSERT_EQ(b.node->capture_state(), fw::can::CaptureState::armed);
  const hal::CanFrame r = b.reply(param_request(kNode, ParamOp::set, id_of("capture.decimation"), 4));
  EXPECT_EQ(result_of(r), ErrorCode::busy);
  EXPECT_EQ(value_of_reply(r), 1u) << "unchanged value read back";
  b.reply(capture_control(kNode, fw::can::CaptureOp::abort));
  EXPECT_EQ(result_of(b.reply(param_request(kNode, ParamOp::set, id_of("capture.decimation"), 4))), ErrorCode::ok);
}

TEST(CanNodeParams, ShaperParametersConfigureTheTasksShaper) {
  NodeBench b;
  EXPECT_EQ(result_of(b.reply(param_request(kNode, ParamOp::set, id_of("x.shaper.freq_hz"), f32_raw(40.0f)))), ErrorCode::ok);
  EXPECT_EQ(result_of(b.reply(param_request(kNode, ParamOp::set, id_of("x.shaper.enable"), 1))), ErrorCode::ok);
  b.step(2);
  EXPECT_TRUE(b.task.shaper(hal::Axis::x).shaping());
  EXPECT_NEAR(b.task.shaper_delay_s(hal::Axis::x), 0.5 / 40.0, 1e-3) << "ZVD at 40 Hz delays by half a period";
  EXPECT_NE(b.node->heartbeat_axes() & fw::can::hb_shaper_bit(hal::Axis::x), 0);
  // Shaped axes stay in step: y runs x's shaper too, but its own is off.
  EXPECT_TRUE(b.task.shaper(hal::Axis::y).shaping());
  EXPECT_EQ(b.task.shaper_delay_s(hal::Axis::y), b.task.shaper_delay_s(hal::Axis::x));
  EXPECT_FALSE(b.task.shaper_active(hal::Axis::y));
  EXPECT_EQ(b.node->heartbeat_axes() & fw::can::hb_shaper_bit(hal::Axis::y), 0);
}

}  // namespace
}  // namespace tnv::test
