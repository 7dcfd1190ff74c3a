#include "drivers/linux/linux_io_board.hpp"

namespace tnv::drivers {

hal::HalStatus LinuxIoBoard::read_inputs() noexcept {
  const hal::HalStatus status = board_.read_inputs();
  if (lines_ != nullptr) {
    gpio_failed_ = !lines_->read_inputs(levels_);
    if (gpio_failed_) gpio_read_failures_.fetch_add(1, std::memory_order_relaxed);
  }
  return status;
}

hal::DiscreteInputs LinuxIoBoard::inputs() const noexcept {
  hal::DiscreteInputs in = board_.inputs();
  if (lines_ == nullptr) return in;
  auto level = [&](InputLine line) {
    const auto i = static_cast<std::size_t>(line);
    return levels_.present[i] && levels_.asserted[i];
  };
  in.estop = in.estop || level(InputLine::estop) || gpio_failed_;
  in.servo_alarm[0] = in.servo_alarm[0] || level(InputLine::alarm_x);
  in.servo_alarm[1] = in.servo_alarm[1] || level(InputLine::alarm_y);
  in.limit_positive[0] = in.limit_positive[0] || level(InputLine::limit_x_pos);
  in.limit_negative[0] = in.limit_negative[0] || level(InputLine::limit_x_neg);
  in.limit_positive[1] = in.limit_positive[1] || level(InputLine::limit_y_pos);
  in.limit_negative[1] = in.limit_negative[1] || level(InputLine::limit_y_neg);
  return in;
}

void LinuxIoBoard::set_servo_enable(hal::Axis axis, bool enabled) noexcept {
  enables_[hal::index(axis)] = enabled;
  board_.set_servo_enable(axis, enabled);
}

hal::HalStatus LinuxIoBoard::write_outputs() noexcept {
  const hal::HalStatus status = board_.write_outputs();
  if (lines_ != nullptr && !lines_->write_enables(enables_[0], enables_[1])) {
    gpio_write_failures_.fetch_add(1, std::memory_order_relaxed);
    // The drive may not have seen the enable change: the tick latches a fault.
    if (status == hal::HalStatus::ok) return hal::HalStatus::output_failed;
  }
  return status;
}

hal::HalStatus LinuxIoBoard::force_safe_outputs() noexcept {
  const auto mid = static_cast<std::uint16_t>(1u << (board_.dac_bits() - 1));
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const hal::Axis axis = hal::axis_from_index(i);
    set_code(axis, mid);
    set_servo_enable(axis, false);
  }
  set_spindle_code(mid);
  set_spindle_enable(false);
  set_spindle_reverse(false);
  return write_outputs();
}

}  // namespace tnv::drivers
