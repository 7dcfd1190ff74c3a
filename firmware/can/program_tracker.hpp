#pragma once
// The state of the program a host streams (SEGMENT / SEGMENT_TAIL), as
// PROGRAM_STATUS reports it: derived from the tick task after every tick
// and every accepted element, with the counts taken relative to the
// program's start (underruns, elements done).
#include <cstdint>

#include "firmware/can/protocol_enums.hpp"
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw::can {

// ProgramState, its names and its value list: protocol_enums.hpp.

constexpr bool active(ProgramState s) noexcept {
  return s == ProgramState::running || s == ProgramState::holding || s == ProgramState::stopping ||
         s == ProgramState::starved || s == ProgramState::paused;
}

class ProgramTracker {
 public:
  // The first element of a new program was accepted: counts restart.
  void started(const TickTask& task) noexcept {
    const motion::MotionStats stats = task.motion().stats();
    underruns_base_ = stats.underruns;
    done_base_ = stats.segments_done;
    accepted_ = 0;
    ended_ = false;
    aborting_ = false;
    state_ = ProgramState::running;
  }
  void accepted() noexcept { ++accepted_; }
  void ended() noexcept { ended_ = true; }
  // A stop of the running program was asked for (abort, stop, host timeout).
  void aborting() noexcept {
    if (active(state_)) aborting_ = true;
  }
  // Follows the task; true when the state changed.
  bool update(const TickTask& task) noexcept {
    if (!active(state_)) return false;
    ProgramState next = state_;
    if (task.program_running()) {
      switch (task.motion().state()) {
        case motion::MotionState::holding: next = ProgramState::holding; break;
        case motion::MotionState::stopping: next = ProgramState::stopping; break;
        case motion::MotionState::starved: next = ProgramState::starved; break;
        case motion::MotionState::paused: next = ProgramState::paused; break;
        case motion::MotionState::idle:
        case motion::MotionState::running: next = ProgramState::running; break;
      }
    } else {
      const bool clean = ended_ && !aborting_ && task.state() == MotionState::holding;
      next = clean ? ProgramState::done : ProgramState::aborted;
    }
    const bool changed = next != state_;
    state_ = next;
    return changed;
  }

  ProgramState state() const noexcept { return state_; }
  // Number (1-based, in the order accepted) of the element being run; the
  // last accepted once the program is over, 0 before the first.
  std::uint32_t element(const TickTask& task) const noexcept {
    if (!active(state_)) return accepted_;
    const std::uint64_t done = task.motion().stats().segments_done - done_base_;
    return static_cast<std::uint32_t>(done + 1 < accepted_ ? done + 1 : accepted_);
  }
  std::uint64_t underruns(const TickTask& task) const noexcept {
    return state_ == ProgramState::none ? 0 : task.motion().stats().underruns - underruns_base_;
  }
  // The number the next accepted element gets.
  std::uint32_t next_element() const noexcept { return accepted_ + 1; }

 private:
  ProgramState state_ = ProgramState::none;
  std::uint64_t underruns_base_ = 0;
  std::uint64_t done_base_ = 0;
  std::uint32_t accepted_ = 0;
  bool ended_ = false;
  bool aborting_ = false;
};

}  // namespace tnv::fw::can
