// TickTask's commands that are not motion: shapers, controller
// selection, disable, fault clearing and the software e-stop.
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw {

CommandStatus TickTask::plan_path_shaper(const std::array<AxisShaperChoice, hal::kAxisCount>& axes) noexcept {
  TapSet series;
  if (!path_taps(axes, static_cast<std::uint32_t>(StreamShaper::kRingCapacity), series)) return CommandStatus::invalid;
  path_taps_ = series;
  path_shaping_ = !series.is_identity();
  path_change_pending_ = true;
  return CommandStatus::ok;
}

void TickTask::forward_path_shaper() noexcept {
  for (AxisShaping& s : shaping_) {
    if (path_shaping_) (void)s.shaper.request_taps(path_taps_);  // fits: checked by plan_path_shaper()
    s.shaper.request_enabled(path_shaping_);
  }
  path_change_pending_ = false;
}

CommandStatus TickTask::configure_shaper(hal::Axis axis, const ShaperSpec& spec) noexcept {
  if (hal::index(axis) >= hal::kAxisCount || !validate(spec).ok) return CommandStatus::invalid;
  return configure_shaper(axis, spec, design_shaper(spec, kTickPeriodS));
}

CommandStatus TickTask::configure_shaper(hal::Axis axis, const ShaperSpec& spec, const ShaperDesign& design) noexcept {
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount || !validate(spec).ok || design.period_s != kTickPeriodS) return CommandStatus::invalid;
  std::array<AxisShaperChoice, hal::kAxisCount> axes{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    axes[i] = {i == a ? &design.taps : (shaping_[i].configured ? &shaping_[i].design.taps : nullptr),
               shaping_[i].enabled};
  if (const CommandStatus st = plan_path_shaper(axes); st != CommandStatus::ok) return st;
  shaping_[a].design = design;
  shaping_[a].configured = true;
  return CommandStatus::ok;
}

CommandStatus TickTask::enable_shaper(hal::Axis axis, bool on) noexcept {
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount) return CommandStatus::invalid;
  if (on && !shaping_[a].configured) return CommandStatus::invalid;
  std::array<AxisShaperChoice, hal::kAxisCount> axes{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    axes[i] = {shaping_[i].configured ? &shaping_[i].design.taps : nullptr, i == a ? on : shaping_[i].enabled};
  if (const CommandStatus st = plan_path_shaper(axes); st != CommandStatus::ok) return st;
  shaping_[a].enabled = on;
  return CommandStatus::ok;
}

double TickTask::shaper_delay_s(hal::Axis axis) const noexcept {
  return shaping_[hal::index(axis)].shaper.delay_samples() * kTickPeriodS;
}

CommandStatus TickTask::select_controller(hal::Axis axis, ControllerKind kind) noexcept {
  if (state_ == MotionState::dwell || state_ == MotionState::moving || state_ == MotionState::holding)
    return CommandStatus::busy;
  if (kind != ControllerKind::pid && kind != ControllerKind::dvsc && kind != ControllerKind::rdvsc)
    return CommandStatus::invalid;
  axis_[hal::index(axis)].kind = kind;
  config_.axis[hal::index(axis)].controller = kind;  // config() tells the live selection
  return CommandStatus::ok;
}

CommandStatus TickTask::disable() noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::ok;  // already safe
  state_ = MotionState::disabled;
  return CommandStatus::ok;
}

CommandStatus TickTask::clear_fault() noexcept {
  if (state_ != MotionState::faulted) return CommandStatus::ok;
  // The board's trips are sticky: reset them here, between ticks. This
  // clear still answers cause_present; once a snapshot shows them gone,
  // the next clear succeeds (if the cause is real, they latch again).
  bool board_latched = last_inputs_.watchdog_tripped;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    board_latched = board_latched || last_inputs_.encoder_error[i] || last_inputs_.dac_error[i];
  if (board_latched) (void)board_.clear_latched_faults();
  if (fault_cause_present(last_inputs_)) return CommandStatus::cause_present;
  // The board did not answer the last tick's read: nothing says the cause is gone.
  if (!board_answering_) return CommandStatus::cause_present;
  fault_ = {};
  state_ = MotionState::disabled;
  return CommandStatus::ok;
}

CommandStatus TickTask::estop() noexcept {
  latch_fault({FaultReason::remote_estop, -1, counters_.ticks, 0.0, 0.0});
  return CommandStatus::ok;
}

}  // namespace tnv::fw
