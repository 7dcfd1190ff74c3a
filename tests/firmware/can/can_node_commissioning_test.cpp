// Commissioning mode: safety parameters change only in it; it is entered
// only while disabled (and locally permitted), shown in the heartbeat, and
// left on leave, enable, motion and a fault. docs/safety.md "Commissioning".
#include <gtest/gtest.h>

#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::ErrorCode;
using fw::can::MessageId;
using fw::can::ParamOp;

ErrorCode commission_ack(const hal::CanFrame& r) {
  EXPECT_TRUE(is(r, MessageId::command_ack));
  return static_cast<ErrorCode>(raw_of(r, MessageId::command_ack, "result"));
}
ErrorCode commission_reply(const hal::CanFrame& r) {
  EXPECT_TRUE(is(r, MessageId::param_reply));
  return static_cast<ErrorCode>(raw_of(r, MessageId::param_reply, "result"));
}
bool mode_bit(const NodeBench& b) { return (b.node->heartbeat_errors() & fw::can::kHbCommissioning) != 0; }

hal::CanFrame f32_set(const char* name, float value) {
  return param_request(kNode, ParamOp::set, id_of(name), f32_raw(value));
}

// The issue's abuse, one value per safety function it defeated.
struct SafetyAbuse {
  const char* name;
  double value;
};
constexpr SafetyAbuse kSafetyAbuse[] = {{"x.limits.following_floor_mm", 1.5},  // in range, but a safety parameter
                            {"x.limits.following_lag_s", 0.2},
                            {"y.limits.position_max_mm", 900.0},
                            {"supervisor.max_missed_ticks", 8},
                            {"can.host_timeout_ms", 4000},
                            {"x.limits.stall_ticks", 50},
                            {"y.hw.count_mm", 0.001},
                            {"x.hw.dac_full_scale_mm_s", 300.0},
                            {"x.jog.deadman_s", 0.5}};

hal::CanFrame safety_write(ParamOp op, const SafetyAbuse& a) {
  const fw::can::ParamDef& p = NodeBench::find(a.name);
  return param_request(kNode, op, p.id, fw::can::to_wire(p, a.value));
}

TEST(CanNodeCommissioning, EverySafetyParameterIsRefusedOutsideTheModeAndNothingChanges) {
  NodeBench b;
  const fw::can::NodeSettings before = b.node->settings();
  for (const SafetyAbuse& a : kSafetyAbuse) {
    SCOPED_TRACE(a.name);
    const fw::can::ParamDef& p = NodeBench::find(a.name);
    ASSERT_TRUE(fw::can::safety_param(p));
    const hal::CanFrame r = b.reply(safety_write(ParamOp::set, a));
    EXPECT_EQ(commission_reply(r), ErrorCode::commissioning_required);
    EXPECT_EQ(raw_of(r, MessageId::param_reply, "value"), fw::can::to_wire(p, p.get(before))) << "the unchanged value";
    EXPECT_EQ(p.get(b.node->settings()), p.get(before));
  }
  EXPECT_EQ(b.task.config().supervisor.axis[0].following.floor_mm, before.firmware.supervisor.axis[0].following.floor_mm);
  EXPECT_FALSE(b.node->params_unsaved());
  // Writing back the value it has is no change, and allowed.
  const fw::can::ParamDef& floor = NodeBench::find("x.limits.following_floor_mm");
  EXPECT_EQ(commission_reply(b.reply(param_request(kNode, ParamOp::set, floor.id, fw::can::to_wire(floor, floor.get(before))))),
            ErrorCode::ok);
}

TEST(CanNodeCommissioning, TheIssuesAbuseIsOutOfRangeEvenInTheMode) {
  NodeBench b;
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  EXPECT_EQ(commission_reply(b.reply(f32_set("x.limits.following_floor_mm", 100.0f))), ErrorCode::out_of_range);
  EXPECT_EQ(commission_reply(b.reply(f32_set("x.limits.following_lag_s", 10.0f))), ErrorCode::out_of_range);
  EXPECT_EQ(commission_reply(b.reply(f32_set("x.limits.position_min_mm", -10000.0f))), ErrorCode::out_of_range);
  EXPECT_EQ(commission_reply(b.reply(f32_set("x.limits.position_max_mm", 10000.0f))), ErrorCode::out_of_range);
  EXPECT_EQ(commission_reply(b.reply(param_request(kNode, ParamOp::set, id_of("supervisor.max_missed_ticks"), 1000))),
            ErrorCode::out_of_range);
  EXPECT_EQ(b.param("x.limits.following_floor_mm"), quiet_settings().firmware.supervisor.axis[0].following.floor_mm);
}

TEST(CanNodeCommissioning, InTheModeEverySafetyParameterChangesAndReachesTheTask) {
  NodeBench b;
  EXPECT_FALSE(mode_bit(b));
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  EXPECT_TRUE(b.node->commissioning());
  EXPECT_TRUE(mode_bit(b)) << "shown in the heartbeat";
  for (const SafetyAbuse& a : kSafetyAbuse) {
    SCOPED_TRACE(a.name);
    EXPECT_EQ(commission_reply(b.reply(safety_write(ParamOp::set, a))), ErrorCode::ok);
    const fw::can::ParamDef& p = NodeBench::find(a.name);
    EXPECT_EQ(fw::can::to_wire(p, p.get(b.node->settings())), fw::can::to_wire(p, a.value));
  }
  EXPECT_NEAR(b.task.config().supervisor.axis[0].following.floor_mm, 1.5, 1e-6) << "the task runs it";
  EXPECT_EQ(b.task.config().supervisor.max_consecutive_missed_ticks, 8u);
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::leave_commissioning))), ErrorCode::ok);
  EXPECT_FALSE(mode_bit(b));
  EXPECT_EQ(commission_reply(b.reply(f32_set("x.limits.following_floor_mm", 0.05f))), ErrorCode::commissioning_required);
}

TEST(CanNodeCommissioning, StagingASafetyParameterIsRefusedOutsideTheMode) {
  NodeBench b;
  EXPECT_EQ(commission_reply(b.reply(safety_write(ParamOp::stage, kSafetyAbuse[0]))), ErrorCode::commissioning_required);
  EXPECT_EQ(b.node->staged_count(), 0u);
  // Refused before the range check: the issue's floor of 100 mm names commissioning, not the range.
  EXPECT_EQ(commission_reply(b.reply(f32_set("x.limits.following_floor_mm", 100.0f))), ErrorCode::commissioning_required);
}

TEST(CanNodeCommissioning, ASetStagedInTheModeIsRefusedWholeAtCommitAfterLeavingNamingTheParameter) {
  NodeBench b;
  const double kp0 = b.param("x.pid.kp");
  EXPECT_EQ(commission_reply(b.reply(param_request(kNode, ParamOp::stage, id_of("x.pid.kp"), f32_raw(400.0f)))),
            ErrorCode::ok);
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  EXPECT_EQ(commission_reply(b.reply(safety_write(ParamOp::stage, kSafetyAbuse[0]))), ErrorCode::ok);
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::leave_commissioning))), ErrorCode::ok);
  const hal::CanFrame c = b.reply(param_request(kNode, ParamOp::commit, 0));
  EXPECT_EQ(commission_reply(c), ErrorCode::commissioning_required);
  EXPECT_EQ(raw_of(c, MessageId::param_reply, "value"), id_of(kSafetyAbuse[0].name)) << "names the parameter";
  EXPECT_EQ(b.param("x.pid.kp"), kp0) << "refused whole";
  EXPECT_EQ(b.node->staged_count(), 2u) << "kept for a fix or a discard";
  // Back in the mode the same pending set commits.
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  EXPECT_EQ(commission_reply(b.reply(param_request(kNode, ParamOp::commit, 0))), ErrorCode::ok);
  EXPECT_EQ(b.param("x.pid.kp"), static_cast<double>(400.0f));
  EXPECT_NEAR(b.param("x.limits.following_floor_mm"), 1.5, 1e-6);
}

TEST(CanNodeCommissioning, EnteredOnlyWhileDisabledAndLeftOnEnable) {
  NodeBench b;
  b.reply(command(kNode, CommandCode::enable));
  EXPECT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::busy) << "holding";
  EXPECT_FALSE(b.node->commissioning());
  b.reply(command(kNode, CommandCode::disable));
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  b.reply(command(kNode, CommandCode::enable));
  EXPECT_FALSE(b.node->commissioning()) << "enable leaves it";
  b.reply(command(kNode, CommandCode::disable));
  b.step(2);
  EXPECT_FALSE(b.node->commissioning()) << "and it does not come back by disabling";
  EXPECT_EQ(commission_reply(b.reply(safety_write(ParamOp::set, kSafetyAbuse[0]))), ErrorCode::commissioning_required);
}

TEST(CanNodeCommissioning, LeftOnMotionAndOnAFault) {
  NodeBench b;
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  EXPECT_EQ(commission_ack(b.reply(circle(kNode, 6.0, 2.0))), ErrorCode::ok);  // starts with a servo-on dwell
  EXPECT_FALSE(b.node->commissioning()) << "motion leaves it";
  b.reply(command(kNode, CommandCode::stop));
  b.step(5);
  b.reply(command(kNode, CommandCode::disable));
  b.step();

  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  b.request(frame_to(MessageId::estop, kNode));
  b.step();
  EXPECT_FALSE(b.node->commissioning()) << "a fault leaves it";
  EXPECT_FALSE(mode_bit(b));
  EXPECT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::faulted);
  EXPECT_EQ(commission_ack(b.reply(command(kNode, CommandCode::clear_faults))), ErrorCode::ok);
  EXPECT_FALSE(b.node->commissioning()) << "clearing the fault does not bring it back";
  EXPECT_EQ(commission_reply(b.reply(safety_write(ParamOp::set, kSafetyAbuse[0]))), ErrorCode::commissioning_required);
}

TEST(CanNodeCommissioning, WithoutTheLocalPermissionEnterIsNotPermitted) {
  NodeBench b;
  b.node->allow_commissioning(false);
  EXPECT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::not_permitted);
  EXPECT_FALSE(b.node->commissioning());
  EXPECT_EQ(commission_reply(b.reply(safety_write(ParamOp::set, kSafetyAbuse[0]))), ErrorCode::commissioning_required);
  EXPECT_EQ(commission_ack(b.reply(command(kNode, CommandCode::leave_commissioning))), ErrorCode::ok) << "always fine";
}

TEST(CanNodeCommissioning, RestoreDefaultsKeepsTheSafetyParametersOutsideTheMode) {
  NodeBench b;
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  ASSERT_EQ(commission_reply(b.reply(safety_write(ParamOp::set, kSafetyAbuse[0]))), ErrorCode::ok);
  ASSERT_EQ(commission_reply(b.reply(f32_set("x.pid.kp", 400.0f))), ErrorCode::ok);
  b.reply(command(kNode, CommandCode::leave_commissioning));
  EXPECT_EQ(commission_ack(b.reply(command(kNode, CommandCode::restore_defaults))), ErrorCode::ok);
  const fw::can::NodeSettings d = quiet_settings();
  EXPECT_EQ(b.param("x.pid.kp"), d.firmware.axis[0].pid.kp) << "tuning restored";
  EXPECT_NEAR(b.param("x.limits.following_floor_mm"), 1.5, 1e-6) << "the commissioned limit kept";
  // In the mode the defaults include the limits.
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  EXPECT_EQ(commission_ack(b.reply(command(kNode, CommandCode::restore_defaults))), ErrorCode::ok);
  EXPECT_EQ(b.param("x.limits.following_floor_mm"), d.firmware.supervisor.axis[0].following.floor_mm);
}

TEST(CanNodeCommissioning, LoadingAStoredSetWithOtherSafetyValuesNeedsTheMode) {
  NodeBench b;
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  ASSERT_EQ(commission_reply(b.reply(safety_write(ParamOp::set, kSafetyAbuse[0]))), ErrorCode::ok);
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::save_params))), ErrorCode::ok);
  ASSERT_EQ(commission_reply(b.reply(f32_set("x.limits.following_floor_mm", 0.05f))), ErrorCode::ok);
  b.reply(command(kNode, CommandCode::leave_commissioning));
  EXPECT_EQ(commission_ack(b.reply(command(kNode, CommandCode::load_params))), ErrorCode::commissioning_required);
  EXPECT_NEAR(b.param("x.limits.following_floor_mm"), 0.05, 1e-6) << "nothing loaded";
  ASSERT_EQ(commission_ack(b.reply(command(kNode, CommandCode::enter_commissioning))), ErrorCode::ok);
  EXPECT_EQ(commission_ack(b.reply(command(kNode, CommandCode::load_params))), ErrorCode::ok);
  EXPECT_NEAR(b.param("x.limits.following_floor_mm"), 1.5, 1e-6);
}

}  // namespace
}  // namespace tnv::test
