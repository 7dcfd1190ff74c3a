// TickTask's part in probe moves (tick_task.hpp "probe moves"): the trip
// position and the outcome report.
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw {

// The snapshot this tick read is latched with the probe input it carried,
// so the measured positions now are where the axes stood when the board
// first saw the change: the latency is the sampling (at most one tick's
// travel at the probe's feed), not the tick's work. Table side: the screw
// compensation's offset off the motor-side measurement, as when servo off.
void TickTask::probe_tick(const motion::MotionReference& r) noexcept {
  if (motion_.probe_tripped_now())
    for (std::size_t i = 0; i < hal::kAxisCount; ++i)
      probe_trip_mm_[i] = record_.axis[i].position_mm - axis_[i].screw_offset_mm();
  const motion::ProbeOutcome outcome = motion_.probe_outcome();
  if (outcome == motion::ProbeOutcome::none) return;
  ProbeReport& p = probe_report_;
  ++p.count;
  p.outcome = outcome;
  p.tag = r.tag;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) p.rest_mm[i] = r.axis[i].next_position_mm;
  p.trip_mm = outcome == motion::ProbeOutcome::tripped ? probe_trip_mm_ : p.rest_mm;
  if (motion::is_error(outcome)) abort_spindle();  // the program stops (the motion core drops the rest)
}

}  // namespace tnv::fw
