// TickTask's feed-override source: the S3 force loop (arsc_feed_source.hpp)
// sets the override of a running program, inside the tick, before the
// motion core steps, so the override it derives from this tick's latched
// force moves this tick's path point.
#include "firmware/io/force_code.hpp"
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw {

void TickTask::run_feed_source() noexcept {
  const bool program = state_ == MotionState::moving && source_ == Source::program;
  if (program && arsc_.enabled()) {
    // The cut runs in the XY plane.
    if (!arsc_.running())
      arsc_.start({record_.axis[hal::index(hal::kPlaneFirst)].position_mm,
                   record_.axis[hal::index(hal::kPlaneSecond)].position_mm});
    arsc::ArscFeedInput in;
    in.force_n = force_code_to_n(record_.force_code, config_.force_sensor.n_per_volt);
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      in.position_mm[i] = record_.axis[i].position_mm;
      in.speed_mm_s[i] = record_.axis[i].speed_mm_s;
    }
    in.programmed_feed_mm_s = motion_.running_feed_mm_s();
    in.operator_override = operator_override_;
    (void)motion_.set_feed_override(arsc_.tick(in));  // within 0 .. 1.5 by construction
  } else if (arsc_.running()) {
    arsc_.stop();  // the program ended, faulted or was stopped; the next one starts afresh
  }
  const arsc::ArscSourceStatus& st = arsc_.status();
  record_.feed_override = motion_.feed_override();
  record_.arsc_force_ref_n = arsc_.running() ? st.force_ref_n : 0.0;
  record_.arsc_cutting_gain_n_per_mm_s = arsc_.running() ? st.cutting_gain_n_per_mm_s : 0.0;
}

}  // namespace tnv::fw
