// TickTask's spindle: its commands, its inhibit and its part of the tick
// (design notes "Spindle"; docs/safety.md "Spindle"). The command logic is
// SpindleControl's; here it meets the board, the fault state and the host.
#include <cstddef>

#include "firmware/tick/tick_task.hpp"

namespace tnv::fw {

void TickTask::update_spindle_inhibit() noexcept {
  const bool estop = last_inputs_.estop || (state_ == MotionState::faulted &&
                                            (fault_.reason == FaultReason::estop ||
                                             fault_.reason == FaultReason::remote_estop));
  if (estop) spindle_.set_inhibit(true, SpindleStopCause::estop);
  else if (state_ == MotionState::faulted) spindle_.set_inhibit(true, SpindleStopCause::fault);
  else if (host_lost_) spindle_.set_inhibit(true, SpindleStopCause::host_timeout);
  else spindle_.set_inhibit(false, SpindleStopCause::none);
}

SpindleResult TickTask::spindle_start(SpindleDirection direction, double rpm) noexcept {
  update_spindle_inhibit();  // a fault latched or a host lost since the last tick refuses it now
  return spindle_.start(direction, rpm);
}

SpindleResult TickTask::spindle_set_speed(double rpm) noexcept { return spindle_.set_speed(rpm); }

void TickTask::spindle_stop() noexcept { spindle_.stop(SpindleStopCause::command); }

void TickTask::set_host_lost(bool lost) noexcept {
  host_lost_ = lost;
  update_spindle_inhibit();
}

void TickTask::abort_spindle() noexcept {
  if (spindle_.commanded_on()) spindle_.stop(SpindleStopCause::abort);
}

void TickTask::program_spindle_change(const motion::Segment& change) noexcept {
  if (change.spindle == motion::SpindleChange::stop) {
    if (spindle_.commanded_on()) spindle_.stop(SpindleStopCause::command);  // M5: a commanded stop
    motion_.spindle_change_done();
    return;
  }
  update_spindle_inhibit();
  const SpindleDirection d =
      change.spindle == motion::SpindleChange::reverse ? SpindleDirection::reverse : SpindleDirection::forward;
  if (spindle_.start(d, change.spindle_rpm) == SpindleResult::ok) motion_.spindle_change_done();
  else stop();  // the program cannot go on as written: a controlled stop on the path, as an abort
}

// After the supervisor: a fault it latched this tick stops the spindle in
// this very tick's outputs. The measured speed is the last period's
// (read_timebase); a snapshot that did not advance keeps it.
void TickTask::spindle_tick() noexcept {
  update_spindle_inhibit();
  const SpindleOutputs out = spindle_.tick(spindle_rpm_, kTickPeriodS);
  board_.set_spindle_code(out.dac_code);
  board_.set_spindle_enable(out.enable);
  board_.set_spindle_reverse(out.reverse);
  SpindleTickRecord& r = record_.spindle;
  r.measured_rpm = spindle_rpm_;
  r.command_rpm = out.command_rpm;
  r.target_rpm = spindle_.target_rpm();
  r.dac_code = out.dac_code;
  r.enabled = out.enable;
  r.reverse = out.reverse;
  r.at_speed = spindle_.at_speed();
  r.feed_gate_waiting = motion_.waiting_for_feed_gate();
}

}  // namespace tnv::fw
