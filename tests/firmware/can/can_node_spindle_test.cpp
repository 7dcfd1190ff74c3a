// SPINDLE over CAN (docs/safety.md "Spindle"): the owner check, the
// refusals (each names its field and changes nothing), spindle.*
// parameters only while the spindle is stopped, the host timeout stopping
// it, and its state in TLM_SPINDLE.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "firmware/can/param_table.hpp"
#include "tests/firmware/can/node_bench.hpp"

namespace tnv::test {
namespace {

using fw::can::CommandCode;
using fw::can::ErrorCode;
using fw::can::MessageId;
using fw::can::ParamOp;
using fw::can::SpindleOp;

constexpr std::uint8_t kOtherHost = 0x21;  // host 2; the bench's host 1 holds ownership

hal::CanFrame spindle(SpindleOp op, double rpm = 0.0, std::uint32_t direction = 0) {
  hal::CanFrame f = frame_to(MessageId::spindle, kNode);
  set_raw(f, MessageId::spindle, "op", static_cast<std::uint32_t>(op));
  set_raw(f, MessageId::spindle, "direction", direction);
  set_value(f, MessageId::spindle, "rpm", rpm);
  return f;
}

std::uint8_t field_index(const char* name) {
  const fw::can::MessageDef& m = msg(MessageId::spindle);
  for (std::size_t i = 0; i < m.fields.size(); ++i)
    if (std::string_view(m.fields[i].name) == name) return static_cast<std::uint8_t>(i);
  return 0xFF;
}

hal::CanFrame set_param(const char* name, double value) {
  const fw::can::ParamDef& p = *fw::can::find_param(name);
  return param_request(kNode, ParamOp::set, p.id, fw::can::to_wire(p, value));
}

TEST(CanNodeSpindle, AStartFromAHostWithoutOwnershipIsRefusedAndChangesNothing) {
  NodeBench b;
  const hal::CanFrame r = b.reply(with_tag(spindle(SpindleOp::start, 3000.0), kOtherHost));
  ASSERT_TRUE(is(r, MessageId::command_ack));
  EXPECT_EQ(raw_of(r, MessageId::command_ack, "request"), static_cast<std::uint32_t>(MessageId::spindle));
  EXPECT_EQ(ack_result(r), ErrorCode::not_owner);
  b.step(20);
  EXPECT_FALSE(b.task.spindle().commanded_on());
  EXPECT_FALSE(b.board.spindle_enable);
  EXPECT_EQ(b.board.spindle_code, 2048u);
}

TEST(CanNodeSpindle, TheOwnerStartsItReversedChangesItsSpeedAndStopsIt) {
  NodeBench b;
  const hal::CanFrame r = b.reply(spindle(SpindleOp::start, 3000.0, 1));
  EXPECT_EQ(ack_result(r), ErrorCode::ok);
  EXPECT_EQ(raw_of(r, MessageId::command_ack, "code"), static_cast<std::uint32_t>(SpindleOp::start));
  EXPECT_EQ(raw_of(r, MessageId::command_ack, "tag"), kTestTag);
  b.step(10);
  EXPECT_TRUE(b.task.spindle().commanded_on());
  EXPECT_EQ(b.task.spindle().target_rpm(), -3000.0);
  EXPECT_TRUE(b.board.spindle_enable);
  EXPECT_TRUE(b.board.spindle_reverse);
  EXPECT_LT(b.board.spindle_code, 2048u) << "a reverse command is below mid-scale";
  EXPECT_EQ(ack_result(b.reply(spindle(SpindleOp::speed, 2000.0))), ErrorCode::ok);
  EXPECT_EQ(b.task.spindle().target_rpm(), -2000.0);
  EXPECT_EQ(ack_result(b.reply(spindle(SpindleOp::stop))), ErrorCode::ok);
  EXPECT_FALSE(b.task.spindle().commanded_on());
  EXPECT_EQ(b.task.spindle().last_stop_cause(), fw::SpindleStopCause::command);
}

TEST(CanNodeSpindle, BadRequestsNameTheirFieldAndChangeNothing) {
  NodeBench b;
  struct BadRequest {
    hal::CanFrame frame;
    ErrorCode result;
    std::uint8_t detail;
  };
  const BadRequest cases[] = {
      {spindle(static_cast<SpindleOp>(7), 3000.0), ErrorCode::unknown_command, field_index("op")},
      {spindle(SpindleOp::start, 3000.0, 2), ErrorCode::out_of_range, field_index("direction")},
      {spindle(SpindleOp::start, std::numeric_limits<double>::quiet_NaN()), ErrorCode::not_finite, field_index("rpm")},
      {spindle(SpindleOp::start, 20000.0), ErrorCode::out_of_range, field_index("rpm")},
      {spindle(SpindleOp::start, -100.0), ErrorCode::out_of_range, field_index("rpm")},
      {spindle(SpindleOp::speed, 1000.0), ErrorCode::not_ready, 0},  // not turning: a start names its speed
  };
  for (const BadRequest& c : cases) {
    const hal::CanFrame r = b.reply(c.frame);
    EXPECT_EQ(ack_result(r), c.result);
    EXPECT_EQ(ack_detail(r), c.detail);
    b.step(3);
    EXPECT_FALSE(b.task.spindle().commanded_on());
    EXPECT_FALSE(b.board.spindle_enable);
  }
  EXPECT_EQ(b.task.spindle().starts(), 0u);
}

TEST(CanNodeSpindle, ParametersAreRefusedWhileItTurnsAndApplyOnceItIsStill) {
  NodeBench b;
  const double before = b.param("spindle.accel_rpm_s");
  ASSERT_EQ(ack_result(b.reply(spindle(SpindleOp::start, 3000.0))), ErrorCode::ok);
  b.step(10);
  const hal::CanFrame refused = b.reply(set_param("spindle.accel_rpm_s", 2000.0));
  EXPECT_EQ(static_cast<ErrorCode>(raw_of(refused, MessageId::param_reply, "result")), ErrorCode::spindle_running);
  EXPECT_EQ(b.param("spindle.accel_rpm_s"), before);
  EXPECT_EQ(b.task.spindle().params().accel_rpm_s, before);
  EXPECT_EQ(b.task.config().spindle.accel_rpm_s, before);
  ASSERT_EQ(ack_result(b.reply(spindle(SpindleOp::stop))), ErrorCode::ok);
  b.step(2);  // the controlled stop ramps the command down (50 rpm: 10 ticks) with the enable held
  EXPECT_TRUE(b.board.spindle_enable);
  EXPECT_EQ(static_cast<ErrorCode>(raw_of(b.reply(set_param("spindle.accel_rpm_s", 2000.0)), MessageId::param_reply,
                                          "result")),
            ErrorCode::spindle_running);
  b.step(20);  // the fake board's spindle never turned: at 0 rpm the enable drops
  ASSERT_FALSE(b.board.spindle_enable);
  const hal::CanFrame applied = b.reply(set_param("spindle.accel_rpm_s", 2000.0));
  EXPECT_EQ(static_cast<ErrorCode>(raw_of(applied, MessageId::param_reply, "result")), ErrorCode::ok);
  EXPECT_EQ(b.task.spindle().params().accel_rpm_s, 2000.0);
  // Out of the drive's range: refused by the table, whatever the spindle does.
  const hal::CanFrame too_fast = b.reply(set_param("spindle.accel_rpm_s", 7000.0));
  EXPECT_EQ(static_cast<ErrorCode>(raw_of(too_fast, MessageId::param_reply, "result")), ErrorCode::out_of_range);
  EXPECT_FALSE(b.task.spindle().commanded_on()) << "a parameter change never starts it";
}

TEST(CanNodeSpindle, TheOwnersSilenceStopsItAndANewOwnerDoesNotStartIt) {
  fw::can::NodeSettings s = quiet_settings();
  s.can.host_timeout_ms = 50;
  NodeBench b(s);
  ASSERT_EQ(ack_result(b.reply(spindle(SpindleOp::start, 3000.0))), ErrorCode::ok);
  b.step(60);
  b.port.drain();
  EXPECT_TRUE(b.task.host_lost());
  EXPECT_FALSE(b.task.spindle().commanded_on());
  EXPECT_EQ(b.task.spindle().last_stop_cause(), fw::SpindleStopCause::host_timeout);
  b.step(100);  // the controlled stop's ramp (from 250 rpm at 5000 rpm/s: 50 ticks)
  b.port.drain();
  EXPECT_FALSE(b.board.spindle_enable);
  ASSERT_EQ(ack_result(b.reply(command(kNode, CommandCode::take_ownership))), ErrorCode::ok);
  EXPECT_FALSE(b.task.host_lost());
  b.step(20);
  EXPECT_FALSE(b.task.spindle().commanded_on());
  EXPECT_FALSE(b.board.spindle_enable);
  EXPECT_EQ(ack_result(b.reply(spindle(SpindleOp::start, 3000.0))), ErrorCode::ok);
}

TEST(CanNodeSpindle, AStartWhileFaultedIsRefused) {
  NodeBench b;
  b.board.in.estop = true;
  b.step(2);
  ASSERT_EQ(b.task.state(), fw::MotionState::faulted);
  b.port.drain();  // the FAULT_EVENT
  const hal::CanFrame r = b.reply(spindle(SpindleOp::start, 3000.0));
  ASSERT_TRUE(is(r, MessageId::command_ack));
  EXPECT_EQ(ack_result(r), ErrorCode::faulted);
  EXPECT_EQ(b.task.spindle().starts(), 0u);
  b.step(5);
  EXPECT_FALSE(b.board.spindle_enable);
}

TEST(CanNodeSpindle, TelemetryCarriesItsSpeedsFlagsAndLastStopCause) {
  fw::can::NodeSettings s = quiet_settings();
  s.telemetry.spindle_ms = 1;
  NodeBench b(s);
  ASSERT_EQ(ack_result(b.reply(spindle(SpindleOp::start, 3000.0))), ErrorCode::ok);
  b.port.drain();
  b.step(10);
  const std::vector<hal::CanFrame> frames = only(b.port.drain(), MessageId::tlm_spindle);
  ASSERT_FALSE(frames.empty());
  const hal::CanFrame& f = frames.back();
  EXPECT_EQ(value_of(f, MessageId::tlm_spindle, "target"), 3000.0);
  EXPECT_NEAR(value_of(f, MessageId::tlm_spindle, "command"), 50.0, 1.0) << "10 ticks of the 5000 rpm/s ramp";
  const std::uint32_t flags = raw_of(f, MessageId::tlm_spindle, "flags");
  EXPECT_NE(flags & fw::can::kSpindleOn, 0u);
  EXPECT_NE(flags & fw::can::kSpindleEnabled, 0u);
  EXPECT_EQ(flags & fw::can::kSpindleAtSpeed, 0u);
  EXPECT_EQ(raw_of(f, MessageId::tlm_spindle, "stop_cause"), static_cast<std::uint32_t>(fw::SpindleStopCause::none));
  ASSERT_EQ(ack_result(b.reply(spindle(SpindleOp::stop))), ErrorCode::ok);
  b.port.drain();
  b.step(3);
  const std::vector<hal::CanFrame> after = only(b.port.drain(), MessageId::tlm_spindle);
  ASSERT_FALSE(after.empty());
  EXPECT_EQ(raw_of(after.back(), MessageId::tlm_spindle, "stop_cause"),
            static_cast<std::uint32_t>(fw::SpindleStopCause::command));
}

}  // namespace
}  // namespace tnv::test
