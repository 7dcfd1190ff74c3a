#include "tools/hil/program_feeder.hpp"

namespace tnv::hil {

bool ProgramFeeder::feed(fw::TickTask& task) noexcept {
  while (next_ < segments_->size() && task.motion().free_slots() > 0) {
    fw::motion::SegmentRefusal why = fw::motion::SegmentRefusal::none;
    status_ = task.push_segment((*segments_)[next_], why);
    if (status_ != fw::CommandStatus::ok) {
      ++refused_;
      why_ = why;
      return false;
    }
    ++next_;
  }
  if (all_pushed() && !closed_ && !more_to_come_) closed_ = task.end_program() == fw::CommandStatus::ok;
  return true;
}

}  // namespace tnv::hil
