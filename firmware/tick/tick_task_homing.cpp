// TickTask's homing: the HOME command and the per-tick reference of the
// homing axis. The axes' sequence, their cycles and what homing left are
// HomingSequence's (homing_sequence.hpp); the frame shift at the index and
// the end of the motion are the task's. Bounded work per tick: one cycle
// step, and at the index edge one frame shift.
#include <cstdint>

#include "firmware/tick/tick_task.hpp"

namespace tnv::fw {

CommandStatus TickTask::home(hal::AxisSet axes) noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (moving()) return CommandStatus::busy;
  if ((axes & hal::kEveryAxis) == 0 || (axes & ~hal::kEveryAxis) != 0) return CommandStatus::invalid;
  const bool was_on = state_ == MotionState::holding;
  if (!was_on) {
    // Servo on where the table stands (bumpless), as hold_position().
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) hold_[i] = {record_.axis[i].position_mm, 0.0};
    reset_controllers();
  }
  source_ = Source::homing;
  stop_requested_ = false;
  phase_tick_ = 0;
  motion_ticks_ = 0;
  centred_ = false;
  state_ = MotionState::moving;
  homing_.begin(axes, config_, hold_, kTickPeriodS);
  return CommandStatus::ok;
}

void TickTask::shift_frame(std::size_t a, double delta_mm) noexcept {
  origin_mm_[a] += delta_mm;
  hold_[a].position_mm += delta_mm;
  next_[a].position_mm += delta_mm;
  AxisTickRecord& r = record_.axis[a];
  r.position_mm += delta_mm;
  r.reference_mm += delta_mm;
  r.unshaped_reference_mm += delta_mm;
  axis_[a].shift_frame(delta_mm);
}

// The homing axis follows the cycle, the other holds; both unshaped (the
// shapers rest at the hold points and are reset there at the end).
void TickTask::homing_reference() noexcept {
  record_.motion_tick = phase_tick_;
  ++phase_tick_;
  const std::size_t a = homing_.axis();
  const hal::Axis axis = hal::axis_from_index(a);
  const hal::IndexLatch index = board_.index_latch(axis);
  HomingStep step = homing_.step(last_inputs_.home_switch[a], index.edges);
  if (step.index_found) {
    // The index's latched count, extended like the tick's own count.
    const std::int64_t latched_counts = axis_[a].counts_at(index.count);
    const double origin_mm = config_.axis[a].homing.position_mm - static_cast<double>(latched_counts) * config_.axis[a].count_mm;
    const double delta_mm = origin_mm - origin_mm_[a];
    shift_frame(a, delta_mm);
    homing_.shift(delta_mm);
    step.now.position_mm += delta_mm;
    step.next.position_mm += delta_mm;
  }
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const AxisSample now = i == a ? AxisSample{step.now.position_mm, step.now.speed_mm_s} : hold_[i];
    const AxisSample next = i == a ? AxisSample{step.next.position_mm, step.next.speed_mm_s} : hold_[i];
    record_.axis[i].unshaped_reference_mm = now.position_mm;
    set_reference(i, now, next);
  }
  if (homing_.running()) return;
  hold_[a] = {step.next.position_mm, 0.0};
  if (homing_.next_axis(config_, hold_, kTickPeriodS)) return;  // homed: the next queued axis starts
  const HomingCycle ended = homing_.finish();
  state_ = MotionState::holding;
  stop_requested_ = false;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) shapers_.reset(i, hold_[i]);
  if (ended.phase() == HomingPhase::failed && ended.result() != HomingResult::aborted) {
    latch_fault({FaultReason::homing_failed, static_cast<std::int8_t>(a), counters_.ticks, ended.failed_travel_mm(),
                 ended.failed_limit_mm()});
  }
}

}  // namespace tnv::fw
