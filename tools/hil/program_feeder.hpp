#pragma once
// Keeps a tick task's motion queue fed from a list of segments as a host
// (G-code, a CAN stream) would: before every tick, as many segments as the
// queue has free slots, and end_program() once everything is pushed (again
// each tick until the task takes it). Used by `tnv-hil path` and the force
// loop's study.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "firmware/motion/segment.hpp"
#include "firmware/tick/tick_task.hpp"

namespace tnv::hil {

class ProgramFeeder {
 public:
  explicit ProgramFeeder(const std::vector<fw::motion::Segment>& segments) : segments_(&segments) {}
  // A program still being read (it waits at a probe move for the outcome):
  // the list grows and the program is not ended until more_to_come is false;
  // `segments` may be another list that starts with the same segments.
  void follow(const std::vector<fw::motion::Segment>& segments, bool more_to_come) noexcept {
    segments_ = &segments;
    more_to_come_ = more_to_come;
  }
  // Pushes while the queue has room; false if a segment was refused (its
  // index next_index(), the status and the queue's reason kept).
  bool feed(fw::TickTask& task) noexcept;
  bool all_pushed() const noexcept { return next_ == segments_->size(); }
  bool closed() const noexcept { return closed_; }  // end_program() was taken
  std::size_t next_index() const noexcept { return next_; }  // segments pushed so far
  std::uint32_t refused() const noexcept { return refused_; }
  fw::CommandStatus last_status() const noexcept { return status_; }
  fw::motion::SegmentRefusal last_refusal() const noexcept { return why_; }

 private:
  const std::vector<fw::motion::Segment>* segments_;
  bool more_to_come_ = false;
  std::size_t next_ = 0;
  bool closed_ = false;
  std::uint32_t refused_ = 0;
  fw::CommandStatus status_ = fw::CommandStatus::ok;
  fw::motion::SegmentRefusal why_ = fw::motion::SegmentRefusal::none;
};

}  // namespace tnv::hil
