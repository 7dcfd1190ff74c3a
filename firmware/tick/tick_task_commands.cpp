// TickTask's commands that are not motion: shapers (their state is
// PathShapers', path_shapers.hpp), controller selection, disable, fault
// clearing and the software e-stop.
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw {

CommandStatus TickTask::configure_shaper(hal::Axis axis, const ShaperSpec& spec) noexcept {
  if (hal::index(axis) >= hal::kAxisCount || !validate(spec).ok) return CommandStatus::invalid;
  return configure_shaper(axis, spec, design_shaper(spec, kTickPeriodS));
}

CommandStatus TickTask::configure_shaper(hal::Axis axis, const ShaperSpec& spec, const ShaperDesign& design) noexcept {
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount || !validate(spec).ok || design.period_s != kTickPeriodS) return CommandStatus::invalid;
  return shapers_.configure(a, design) ? CommandStatus::ok : CommandStatus::invalid;
}

CommandStatus TickTask::enable_shaper(hal::Axis axis, bool on) noexcept {
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount) return CommandStatus::invalid;
  return shapers_.enable(a, on) ? CommandStatus::ok : CommandStatus::invalid;
}

double TickTask::shaper_delay_s(hal::Axis axis) const noexcept {
  return shapers_.shaper(hal::index(axis)).delay_samples() * kTickPeriodS;
}

CommandStatus TickTask::select_controller(hal::Axis axis, ControllerKind kind) noexcept {
  if (state_ == MotionState::dwell || state_ == MotionState::moving || state_ == MotionState::holding)
    return CommandStatus::busy;
  if (kind != ControllerKind::pid && kind != ControllerKind::dvsc && kind != ControllerKind::rdvsc)
    return CommandStatus::invalid;
  axis_[hal::index(axis)].select(kind);
  config_.axis[hal::index(axis)].controller = kind;  // config() tells the live selection
  return CommandStatus::ok;
}

CommandStatus TickTask::disable() noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::ok;  // already safe
  // Servo off under a running program, circle or move aborts it.
  if (moving() && source_ != Source::jog && source_ != Source::homing) abort_spindle();
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
