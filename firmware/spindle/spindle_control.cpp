#include "firmware/spindle/spindle_control.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/io/dac_code.hpp"
#include "firmware/timing/m_method_speed.hpp"

namespace tnv::fw {

namespace {

bool is_immediate(SpindleStopCause cause) noexcept {
  return kSpindleStopIsImmediate[static_cast<std::size_t>(cause)];
}

// One step of the command toward `target`, at most `step` (>= 0) away.
double ramp_toward(double command, double target, double step) noexcept {
  if (command < target) return std::min(command + step, target);
  if (command > target) return std::max(command - step, target);
  return command;
}

}  // namespace

double SpindleControl::target_rpm() const noexcept {
  if (!on_) return 0.0;
  return direction_ == SpindleDirection::reverse ? -rpm_ : rpm_;
}

SpindleResult SpindleControl::start(SpindleDirection direction, double rpm) noexcept {
  if (inhibited_) return SpindleResult::inhibited;
  if (!std::isfinite(rpm) || rpm <= 0.0 || rpm > params_.max_rpm) return SpindleResult::bad_speed;
  on_ = true;
  direction_ = direction;
  rpm_ = rpm;
  at_speed_ = false;
  in_window_ticks_ = 0;
  ++starts_;
  return SpindleResult::ok;
}

SpindleResult SpindleControl::set_speed(double rpm) noexcept {
  if (!on_) return SpindleResult::not_running;
  if (!std::isfinite(rpm) || rpm <= 0.0 || rpm > params_.max_rpm) return SpindleResult::bad_speed;
  if (rpm != rpm_) {
    rpm_ = rpm;
    at_speed_ = false;
    in_window_ticks_ = 0;
  }
  return SpindleResult::ok;
}

void SpindleControl::stop(SpindleStopCause cause) noexcept {
  if (!on_ && !outputs_.enable) return;  // already stopped: the record keeps the stop that did it
  on_ = false;
  at_speed_ = false;
  in_window_ticks_ = 0;
  last_stop_ = cause;
  if (is_immediate(cause)) immediate_stop_ = true;
}

void SpindleControl::set_inhibit(bool inhibited, SpindleStopCause cause) noexcept {
  if (inhibited && !inhibited_) stop(cause);
  inhibited_ = inhibited;
}

bool SpindleControl::can_set_params() const noexcept {
  return !active() && std::fabs(last_measured_rpm_) <= params_.standstill_rpm;
}

SpindleResult SpindleControl::set_params(const SpindleParams& p) noexcept {
  if (!can_set_params()) return SpindleResult::busy;
  if (!validate(p).ok) return SpindleResult::invalid;
  params_ = p;
  return SpindleResult::ok;
}

SpindleOutputs SpindleControl::tick(double measured_rpm, double period_s) noexcept {
  last_measured_rpm_ = std::isfinite(measured_rpm) ? measured_rpm : 0.0;
  const double target = target_rpm();
  if (immediate_stop_) {
    immediate_stop_ = false;
    outputs_.command_rpm = 0.0;
    outputs_.enable = false;
  } else {
    // A bad period (0, negative, not finite) holds the command where it is.
    const double step = (std::isfinite(period_s) && period_s > 0.0) ? params_.accel_rpm_s * period_s : 0.0;
    outputs_.command_rpm = ramp_toward(outputs_.command_rpm, target, step);
    if (on_) {
      outputs_.enable = true;
    } else if (outputs_.enable && outputs_.command_rpm == 0.0 &&
               std::fabs(last_measured_rpm_) <= params_.standstill_rpm) {
      outputs_.enable = false;  // a controlled stop ends at standstill
    }
  }
  // The direction output follows the command's sign; at zero, the direction asked for.
  outputs_.reverse = outputs_.command_rpm < 0.0 ||
                     (outputs_.command_rpm == 0.0 && on_ && direction_ == SpindleDirection::reverse);
  outputs_.dac_code = spindle_dac_code(outputs_.enable ? outputs_.command_rpm : 0.0);

  const double window = std::max(params_.at_speed_fraction * std::fabs(target), params_.at_speed_floor_rpm);
  const bool in_window = on_ && outputs_.command_rpm == target && std::fabs(last_measured_rpm_ - target) <= window;
  in_window_ticks_ = in_window ? std::min(in_window_ticks_ + 1, params_.at_speed_ticks) : 0;
  at_speed_ = in_window && in_window_ticks_ >= params_.at_speed_ticks;
  return outputs_;
}

std::uint16_t spindle_dac_code(double command_rpm) noexcept {
  static constexpr DacScale kSpindleDac{12, kSpindleDriveFullScaleRpm};  // the same conversion, in rpm
  return speed_to_dac_code(command_rpm, kSpindleDac);
}

double spindle_rpm(std::int64_t delta_counts, std::uint32_t period_clocks) noexcept {
  // counts * (60 / counts per rev) over seconds: revolutions per minute.
  return m_method_speed_mm_s(delta_counts, 60.0 / kSpindleEncoderCountsPerRev, period_clocks);
}

}  // namespace tnv::fw
