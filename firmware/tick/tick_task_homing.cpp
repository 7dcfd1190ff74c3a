// TickTask's homing: the HOME command and the per-tick step of the cycle
// (homing/homing_cycle.hpp). Bounded work per tick: one cycle step, and at
// the index edge one frame shift.
#include <cstdint>

#include "firmware/tick/tick_task.hpp"

namespace tnv::fw {

// The queued axis that homes after `after` (hal::kHomingOrder); kAxisCount
// for none. after = kAxisCount: the first.
std::size_t TickTask::next_homing_axis(std::size_t after) const noexcept {
  bool past = after >= hal::kAxisCount;
  for (const hal::Axis a : hal::kHomingOrder) {
    const std::size_t i = hal::index(a);
    if (past && homing_queued_[i]) return i;
    if (i == after) past = true;
  }
  return hal::kAxisCount;
}

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
  for (const hal::Axis a : hal::kAxes) homing_queued_[hal::index(a)] = hal::contains(axes, a);
  source_ = Source::homing;
  stop_requested_ = false;
  phase_tick_ = 0;
  motion_ticks_ = 0;
  centred_ = false;
  state_ = MotionState::moving;
  start_homing_axis(next_homing_axis(hal::kAxisCount));
  return CommandStatus::ok;
}

void TickTask::start_homing_axis(std::size_t a) noexcept {
  homing_axis_ = a;
  homed_[a] = false;
  home_result_[a] = HomingResult::running;
  homing_.start(config_.axis[a].homing, config_.axis[a].jog.accel_mm_s2, hold_[a].position_mm, kTickPeriodS);
}

void TickTask::end_homing() noexcept {
  if (homing_.running()) home_result_[homing_axis_] = HomingResult::aborted;
  homing_ = HomingCycle{};
  homing_queued_ = {};
}

void TickTask::shift_frame(std::size_t a, double delta_mm) noexcept {
  origin_mm_[a] += delta_mm;
  hold_[a].position_mm += delta_mm;
  next_[a].position_mm += delta_mm;
  AxisTickRecord& r = record_.axis[a];
  r.position_mm += delta_mm;
  r.reference_mm += delta_mm;
  r.unshaped_reference_mm += delta_mm;
  axis_[a].observer.shift(delta_mm);
}

// The homing axis follows the cycle, the other holds; both unshaped (the
// shapers rest at the hold points and are reset there at the end).
void TickTask::homing_reference() noexcept {
  record_.motion_tick = phase_tick_;
  ++phase_tick_;
  const std::size_t a = homing_axis_;
  const hal::Axis axis = hal::axis_from_index(a);
  const hal::IndexLatch index = board_.index_latch(axis);
  HomingStep step = homing_.step(last_inputs_.home_switch[a], index.edges);
  if (step.index_found) {
    // The index's latched count, extended like the tick's own count.
    const std::int64_t latched_counts = axis_[a].encoder.counts_at(index.count);
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
  home_result_[a] = homing_.result();
  if (homing_.phase() == HomingPhase::done) {
    homed_[a] = true;
    homing_queued_[a] = false;
    if (const std::size_t next = next_homing_axis(a); next < hal::kAxisCount) {
      start_homing_axis(next);
      return;
    }
  }
  const HomingCycle ended = homing_;
  homing_queued_ = {};
  homing_ = HomingCycle{};
  state_ = MotionState::holding;
  stop_requested_ = false;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) shaping_[i].shaper.reset(hold_[i]);
  if (ended.phase() == HomingPhase::failed && ended.result() != HomingResult::aborted) {
    latch_fault({FaultReason::homing_failed, static_cast<std::int8_t>(a), counters_.ticks, ended.failed_travel_mm(),
                 ended.failed_limit_mm()});
  }
}

}  // namespace tnv::fw
