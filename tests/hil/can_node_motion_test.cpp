// The CAN node on the emulated TNV-40 while it moves: busy refusal of
// parameters that are not live-tunable, live tuning, atomic commit (no
// tick ever runs with half a parameter set), controlled stop, host
// timeout and the jog stream's dead man.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/hil/can_node_rig.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::ErrorCode;
using fw::can::MessageId;
using fw::can::ParamOp;

constexpr auto kBusy = static_cast<std::uint32_t>(ErrorCode::busy);
constexpr auto kCommissioningRequired = static_cast<std::uint32_t>(ErrorCode::commissioning_required);
constexpr auto kInvalid = static_cast<std::uint32_t>(ErrorCode::invalid);

// A rig with the scenario's circle running (past the dwell).
std::unique_ptr<CanRig> circling(int ticks_into_motion = 200) {
  auto r = CanRig::make();
  if (!r) return nullptr;
  if (r->result(circle(kRigNode, r->scenario.circle.radius_mm, r->scenario.circle.feed_mm_s)) != kOk) return nullptr;
  if (!r->run_until(fw::MotionState::moving, 1000)) return nullptr;
  for (int k = 0; k < ticks_into_motion; ++k) r->step();
  return r;
}

TEST(CanNodeMoving, IdleParametersAreRefusedBusyWhileACircleRunsAndLiveOnesApply) {
  auto r = circling();
  ASSERT_TRUE(r);
  ASSERT_EQ(r->task().state(), fw::MotionState::moving);
  const fw::FirmwareConfig before = r->task().config();
  const fw::can::NodeSettings settings_before = r->node->settings();
  struct Idle {
    const char* name;
    std::uint32_t raw;
  };
  for (const Idle& p : {Idle{"x.limits.speed_max_mm_s", f32_raw(120.0f)}, Idle{"y.pid.derivative_filter_tf_s", f32_raw(0.002f)},
                        Idle{"x.model.b2", f32_raw(0.17f)}, Idle{"y.jog.accel_mm_s2", f32_raw(500.0f)},
                        Idle{"x.controller", 0}, Idle{"supervisor.max_missed_ticks", 3}}) {
    SCOPED_TRACE(p.name);
    const fw::can::ParamDef& def = *fw::can::find_param(p.name);
    ASSERT_EQ(def.apply, fw::can::Apply::idle);
    const std::vector<hal::CanFrame> out = r->request(param_request(kRigNode, ParamOp::set, def.id, p.raw));
    ASSERT_EQ(out.size(), 1u);
    // A safety parameter is refused before the apply rule: commissioning mode needs a disabled servo.
    EXPECT_EQ(raw_of(out[0], MessageId::param_reply, "result"),
              fw::can::safety_param(def) ? kCommissioningRequired : kBusy);
    EXPECT_EQ(raw_of(out[0], MessageId::param_reply, "value"), fw::can::to_wire(def, def.get(settings_before)))
        << "the unchanged value read back";
    r->step();
  }
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::select_controller, 0, 0)), kBusy);
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::save_params)), kBusy);
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::load_params)), kBusy);
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::restore_defaults)), kBusy);
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::zero, 0, 0, 0.0)), kBusy);
  // A staged idle parameter makes the whole commit busy, the live one in it included.
  r->request(param_request(kRigNode, ParamOp::stage, param_id("x.sliding.gamma"), f32_raw(0.3f)));
  r->request(param_request(kRigNode, ParamOp::stage, param_id("y.pid.derivative_filter_tf_s"), f32_raw(0.002f)));
  EXPECT_EQ(r->result(param_request(kRigNode, ParamOp::commit, 0)), kBusy);
  EXPECT_EQ(r->task().sliding_params(hal::Axis::x).gamma, before.axis[0].sliding.gamma);
  r->request(param_request(kRigNode, ParamOp::discard, 0));
  const fw::FirmwareConfig after = r->task().config();
  EXPECT_EQ(after.supervisor.axis[0].speed_max_mm_s, before.supervisor.axis[0].speed_max_mm_s);
  EXPECT_EQ(after.axis[1].pid.derivative_filter_tf_s, before.axis[1].pid.derivative_filter_tf_s);
  EXPECT_EQ(after.axis[0].model.B(1), before.axis[0].model.B(1));
  EXPECT_EQ(r->task().controller(hal::Axis::x), fw::ControllerKind::rdvsc);
  EXPECT_FALSE(r->node->params_unsaved());

  // Live: gamma while moving (S1 eq. (5)), read back exactly.
  const std::vector<hal::CanFrame> live =
      r->request(param_request(kRigNode, ParamOp::set, param_id("x.sliding.gamma"), f32_raw(0.3f)));
  ASSERT_EQ(live.size(), 1u);
  EXPECT_EQ(raw_of(live[0], MessageId::param_reply, "result"), kOk);
  EXPECT_EQ(raw_of(live[0], MessageId::param_reply, "value"), f32_raw(0.3f));
  EXPECT_EQ(r->task().sliding_params(hal::Axis::x).gamma, static_cast<double>(0.3f));
  EXPECT_EQ(r->task().state(), fw::MotionState::moving);
  ASSERT_TRUE(r->run_until(fw::MotionState::holding, 25'000)) << "the circle finishes, no fault: "
                                                               << fw::to_string(r->task().fault().reason);
  // At rest the idle one is accepted; the safety one after disable, in commissioning mode.
  EXPECT_EQ(r->result(param_request(kRigNode, ParamOp::set, param_id("y.jog.accel_mm_s2"), f32_raw(500.0f))), kOk);
  EXPECT_EQ(r->task().config().axis[1].jog.accel_mm_s2, 500.0);
  EXPECT_EQ(r->result(param_request(kRigNode, ParamOp::set, param_id("x.limits.speed_max_mm_s"), f32_raw(120.0f))),
            kCommissioningRequired);
  ASSERT_EQ(r->result(command(kRigNode, CommandCode::disable)), kOk);
  ASSERT_EQ(r->result(command(kRigNode, CommandCode::enter_commissioning)), kOk);
  EXPECT_EQ(r->result(param_request(kRigNode, ParamOp::set, param_id("x.limits.speed_max_mm_s"), f32_raw(120.0f))), kOk);
  EXPECT_EQ(r->task().config().supervisor.axis[0].speed_max_mm_s, 120.0);
}

// What the task's TickTask::apply_config() lets through while moving is
// exactly what the parameter table calls live.
TEST(CanNodeMoving, TheTasksLiveRuleAgreesWithTheParameterTable) {
  const fw::can::NodeSettings base = fw::can::default_node_settings();
  int idle = 0;
  for (const fw::can::ParamDef& p : fw::can::param_table()) {
    if (p.access != fw::can::Access::read_write) continue;
    fw::can::NodeSettings changed = base;
    const double v = p.get(base);
    p.set(changed, p.type == fw::can::ParamType::boolean ? 1.0 - v : v + 1.0);
    const bool task_refuses = !fw::TickTask::live_tunable_only(base.firmware, changed.firmware);
    if (p.apply == fw::can::Apply::idle) {
      ++idle;
      EXPECT_TRUE(task_refuses) << p.name << " is idle in the table, live in the task";
    } else {
      EXPECT_FALSE(task_refuses) << p.name << " is " << fw::can::to_string(p.apply) << " in the table, idle in the task";
    }
  }
  EXPECT_GT(idle, 20);
}

TEST(CanNodeMoving, ACommittedGainSetLandsBetweenTwoTicksWholeAndAnInvalidOneNotAtAll) {
  auto r = circling(100);
  ASSERT_TRUE(r);
  const fw::SlidingModeParams old_s = r->task().sliding_params(hal::Axis::x);
  const fw::PidParams old_p = r->task().pid_params(hal::Axis::x);
  // The new set: every sliding gain and the PID gains of x, each different (and consistent:
  // phi > eta / (q + 1), gamma < min(1 - g, q)).
  struct Staged {
    const char* name;
    float value;
  };
  const Staged set[] = {{"x.sliding.G_position_1_s", 250.0f}, {"x.sliding.eta_mm_s", 0.25f}, {"x.sliding.phi_mm_s", 1.5f},
                        {"x.sliding.q", 0.85f},               {"x.sliding.g", 0.12f},       {"x.sliding.gamma", 0.35f},
                        {"x.pid.kp", 500.0f},                 {"x.pid.ki", 30000.0f},       {"x.pid.kd", 2.0f}};
  // Staged one per tick: a tick runs between every two of them.
  for (const Staged& s : set) {
    ASSERT_EQ(r->result(param_request(kRigNode, ParamOp::stage, param_id(s.name), f32_raw(s.value))), kOk) << s.name;
    r->step();
  }
  const auto all_old = [&] {
    const fw::SlidingModeParams& s = r->task().sliding_params(hal::Axis::x);
    const fw::PidParams& p = r->task().pid_params(hal::Axis::x);
    return s.G_position_1_s == old_s.G_position_1_s && s.eta_mm_s == old_s.eta_mm_s && s.phi_mm_s == old_s.phi_mm_s &&
           s.q == old_s.q && s.g == old_s.g && s.gamma == old_s.gamma && p.kp == old_p.kp && p.ki == old_p.ki &&
           p.kd == old_p.kd;
  };
  const auto all_new = [&] {
    const fw::SlidingModeParams& s = r->task().sliding_params(hal::Axis::x);
    const fw::PidParams& p = r->task().pid_params(hal::Axis::x);
    const auto f = [](float v) { return static_cast<double>(v); };
    return s.G_position_1_s == f(250.0f) && s.eta_mm_s == f(0.25f) && s.phi_mm_s == f(1.5f) && s.q == f(0.85f) &&
           s.g == f(0.12f) && s.gamma == f(0.35f) && p.kp == f(500.0f) && p.ki == f(30000.0f) && p.kd == f(2.0f);
  };
  EXPECT_TRUE(all_old()) << "staging applies nothing";

  // An invalid stage on top (phi below eta / (q + 1)) makes the whole commit invalid.
  ASSERT_EQ(r->result(param_request(kRigNode, ParamOp::stage, param_id("x.sliding.phi_mm_s"), f32_raw(0.1f))), kOk);
  const std::vector<hal::CanFrame> refused = r->request(param_request(kRigNode, ParamOp::commit, 0));
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_EQ(raw_of(refused[0], MessageId::param_reply, "result"), kInvalid);
  r->step();
  EXPECT_TRUE(all_old()) << "an invalid set applies nothing";
  ASSERT_EQ(r->result(param_request(kRigNode, ParamOp::stage, param_id("x.sliding.phi_mm_s"), f32_raw(1.5f))), kOk);

  // Commit in the middle of the motion; observe every tick before and after.
  int ticks_old = 0;
  int ticks_new = 0;
  bool committed = false;
  for (int k = 0; k < 400; ++k) {
    if (k == 200) {
      const std::vector<hal::CanFrame> ok = r->request(param_request(kRigNode, ParamOp::commit, 0));
      ASSERT_EQ(ok.size(), 1u);
      EXPECT_EQ(raw_of(ok[0], MessageId::param_reply, "result"), kOk);
      EXPECT_EQ(raw_of(ok[0], MessageId::param_reply, "param"), std::size(set));
      committed = true;
    }
    r->step();
    const bool o = all_old();
    const bool n = all_new();
    ASSERT_TRUE(o != n) << "tick " << k << " ran with a mix of old and new gains";
    ASSERT_EQ(n, committed) << "tick " << k;
    (o ? ticks_old : ticks_new) += 1;
    ASSERT_EQ(r->task().state(), fw::MotionState::moving);
  }
  EXPECT_EQ(ticks_old, 200);
  EXPECT_EQ(ticks_new, 200);
  EXPECT_TRUE(r->run_until(fw::MotionState::holding, 25'000)) << fw::to_string(r->task().fault().reason);
}

TEST(CanNodeMoving, ControlledStopOfACircleDeceleratesAlongThePathAndHolds) {
  auto r = circling(1000);
  ASSERT_TRUE(r);
  const double radius_mm = r->scenario.circle.radius_mm;
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::stop)), kOk);
  double last_speed = 1e9;
  int ticks = 0;
  while (r->task().state() == fw::MotionState::moving && ticks < 1000) {
    r->step();
    ++ticks;
    const fw::TickRecord& rec = r->task().last_record();
    const double speed = std::hypot(rec.axis[0].reference_speed_mm_s, rec.axis[1].reference_speed_mm_s);
    EXPECT_LE(speed, last_speed + 1e-12) << "tick " << ticks << ": the path speed only falls";
    last_speed = speed;
    EXPECT_NEAR(std::hypot(rec.axis[0].reference_mm, rec.axis[1].reference_mm), radius_mm, 1e-9) << "on the circle";
  }
  EXPECT_EQ(r->task().state(), fw::MotionState::holding);
  const int ramp_ticks = static_cast<int>(std::lround(r->node->settings().motion.circle_ramp_s * 1000.0));
  EXPECT_NEAR(ticks, ramp_ticks, 2) << "stopped over the circle's own ramp";
  for (int k = 0; k < 200; ++k) r->step();
  EXPECT_EQ(r->task().state(), fw::MotionState::holding);
  EXPECT_FALSE(r->task().fault().active());
}

TEST(CanNodeMoving, StopEndsAMoveAndAJogAndDwellStopsAtOnce) {
  auto r = CanRig::make();
  ASSERT_TRUE(r);
  ASSERT_EQ(r->result(command(kRigNode, CommandCode::enable)), kOk);
  r->step();
  ASSERT_EQ(r->result(move(kRigNode, 1, 20.0, 5.0)), kOk);
  for (int k = 0; k < 100; ++k) r->step();
  ASSERT_EQ(r->task().state(), fw::MotionState::moving);
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::stop)), kOk);
  EXPECT_TRUE(r->run_until(fw::MotionState::holding, 100));
  EXPECT_LT(r->task().last_record().axis[1].reference_mm, 5.0) << "stopped short of the end";

  ASSERT_EQ(r->result(jog(kRigNode, 0, 5.0)), kOk);
  for (int k = 0; k < 50; ++k) {
    r->step();
    if (k % 20 == 0) r->request(jog(kRigNode, 0, 5.0));
  }
  ASSERT_TRUE(r->task().jogging());
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::stop)), kOk);
  EXPECT_EQ(r->result(jog(kRigNode, 0, 5.0)), kBusy) << "the stop wins over the stream";
  EXPECT_TRUE(r->run_until(fw::MotionState::holding, 100));
  EXPECT_EQ(r->node->heartbeat_errors() & fw::can::kHbJogDeadman, 0) << "stopped by command, not by the dead man";

  ASSERT_EQ(r->result(command(kRigNode, CommandCode::disable)), kOk);
  r->step();
  ASSERT_EQ(r->result(command(kRigNode, CommandCode::zero, 0, 0, r->scenario.circle.radius_mm)), kOk);
  ASSERT_EQ(r->result(command(kRigNode, CommandCode::zero, 1, 0, 0.0)), kOk);
  ASSERT_EQ(r->result(circle(kRigNode, 1.0, 2.0)), kOk);
  r->step();
  ASSERT_EQ(r->task().state(), fw::MotionState::dwell);
  EXPECT_EQ(r->result(command(kRigNode, CommandCode::stop)), kOk);
  EXPECT_EQ(r->task().state(), fw::MotionState::holding);
  EXPECT_FALSE(r->task().fault().active());
}

TEST(CanNodeMoving, AJogStreamThatGoesSilentStopsByItsDeadMan) {
  auto r = CanRig::make();
  ASSERT_TRUE(r);
  ASSERT_EQ(r->result(command(kRigNode, CommandCode::enable)), kOk);
  r->step();
  const double x0 = r->task().last_record().axis[0].position_mm;
  for (int k = 0; k < 300; ++k) {
    if (k % 50 == 0) {
      ASSERT_EQ(r->result(jog(kRigNode, 0, -4.0)), kOk);  // within the 0.1 s dead man
    }
    r->step();
  }
  EXPECT_TRUE(r->task().jogging());
  EXPECT_TRUE(r->run_until(fw::MotionState::holding, 400)) << "silent: the dead man stops it";
  EXPECT_NE(r->node->heartbeat_errors() & fw::can::kHbJogDeadman, 0);
  EXPECT_LT(r->task().last_record().axis[0].position_mm, x0 - 1.0) << "it moved about 1.2 mm in -x";
  ASSERT_EQ(r->result(jog(kRigNode, 1, 2.0)), kOk);
  EXPECT_EQ(r->node->heartbeat_errors() & fw::can::kHbJogDeadman, 0) << "cleared by the next accepted motion";
}

TEST(CanNodeMoving, ASilentHostStopsTheMotionWhenItsTimeoutIsSet) {
  auto r = CanRig::make();
  ASSERT_TRUE(r);
  ASSERT_EQ(r->result(command(kRigNode, CommandCode::enter_commissioning)), kOk);  // a safety parameter
  ASSERT_EQ(r->result(param_request(kRigNode, ParamOp::set, param_id("can.host_timeout_ms"), 300)), kOk);
  ASSERT_EQ(r->result(circle(kRigNode, r->scenario.circle.radius_mm, r->scenario.circle.feed_mm_s)), kOk);
  // The dwell is 500 ms: the host's silence runs out during it.
  int moving_ticks = 0;
  for (int k = 0; k < 1000 && r->task().state() != fw::MotionState::holding; ++k) {
    r->step();
    moving_ticks += r->task().state() == fw::MotionState::moving ? 1 : 0;
  }
  EXPECT_EQ(r->task().state(), fw::MotionState::holding);
  EXPECT_EQ(moving_ticks, 0) << "stopped in the dwell, before the circle began";
  EXPECT_NE(r->node->heartbeat_errors() & fw::can::kHbHostTimeout, 0);
  EXPECT_FALSE(r->task().fault().active());
}

}  // namespace
}  // namespace tnv::test
