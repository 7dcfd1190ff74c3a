// HomingSequence: the axes of one HOME command, one cycle after the other.
#include "firmware/tick/homing_sequence.hpp"

namespace tnv::fw {

std::size_t HomingSequence::next_queued(std::size_t after) const noexcept {
  bool past = after >= hal::kAxisCount;
  for (const hal::Axis a : hal::kHomingOrder) {
    const std::size_t i = hal::index(a);
    if (past && queued_[i]) return i;
    if (i == after) past = true;
  }
  return hal::kAxisCount;
}

void HomingSequence::start(std::size_t a, const FirmwareConfig& config, const HoldPoints& hold, double tick_s) noexcept {
  axis_ = a;
  homed_[a] = false;
  result_[a] = HomingResult::running;
  cycle_.start(config.axis[a].homing, config.axis[a].jog.accel_mm_s2, hold[a].position_mm, tick_s);
}

void HomingSequence::begin(hal::AxisSet axes, const FirmwareConfig& config, const HoldPoints& hold,
                           double tick_s) noexcept {
  for (const hal::Axis a : hal::kAxes) queued_[hal::index(a)] = hal::contains(axes, a);
  start(next_queued(hal::kAxisCount), config, hold, tick_s);
}

bool HomingSequence::next_axis(const FirmwareConfig& config, const HoldPoints& hold, double tick_s) noexcept {
  const std::size_t a = axis_;
  result_[a] = cycle_.result();
  if (cycle_.phase() != HomingPhase::done) return false;
  homed_[a] = true;
  queued_[a] = false;
  const std::size_t next = next_queued(a);
  if (next >= hal::kAxisCount) return false;
  start(next, config, hold, tick_s);
  return true;
}

HomingCycle HomingSequence::finish() noexcept {
  const HomingCycle ended = cycle_;
  queued_ = {};
  cycle_ = HomingCycle{};
  return ended;
}

void HomingSequence::cancel() noexcept {
  if (cycle_.running()) result_[axis_] = HomingResult::aborted;
  cycle_ = HomingCycle{};
  queued_ = {};
}

}  // namespace tnv::fw
