// ProgramFeedOverride: the operator's override and the S3 force loop
// (arsc_feed_source.hpp) setting the override of a running program.
#include "firmware/tick/program_feed_override.hpp"

#include <cstddef>

#include "firmware/io/force_code.hpp"
#include "hal/axis.hpp"

namespace tnv::fw {

bool ProgramFeedOverride::set_operator_override(double ratio, motion::MotionInterpolator& motion) noexcept {
  operator_override_ = ratio;
  // The force loop combines it with its own at the next tick (it scales the loop's range).
  if (arsc_.running()) return true;
  return motion.set_feed_override(ratio);
}

void ProgramFeedOverride::tick(bool program, double force_n_per_volt, motion::MotionInterpolator& motion,
                               TickRecord& record) noexcept {
  if (program && arsc_.enabled()) {
    // The cut runs in the XY plane.
    if (!arsc_.running())
      arsc_.start({record.axis[hal::index(hal::kPlaneFirst)].position_mm,
                   record.axis[hal::index(hal::kPlaneSecond)].position_mm});
    arsc::ArscFeedInput in;
    in.force_n = force_code_to_n(record.force_code, force_n_per_volt);
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      in.position_mm[i] = record.axis[i].position_mm;
      in.speed_mm_s[i] = record.axis[i].speed_mm_s;
    }
    in.programmed_feed_mm_s = motion.running_feed_mm_s();
    in.operator_override = operator_override_;
    (void)motion.set_feed_override(arsc_.tick(in));  // within 0 .. 1.5 by construction
  } else if (arsc_.running()) {
    arsc_.stop();  // the program ended, faulted or was stopped; the next one starts afresh
  }
  const arsc::ArscSourceStatus& st = arsc_.status();
  record.feed_override = motion.feed_override();
  record.arsc_force_ref_n = arsc_.running() ? st.force_ref_n : 0.0;
  record.arsc_cutting_gain_n_per_mm_s = arsc_.running() ? st.cutting_gain_n_per_mm_s : 0.0;
}

}  // namespace tnv::fw
