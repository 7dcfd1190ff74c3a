#pragma once
// TickTask's feed-override source for a running program (issue 18 and the
// S3 force loop): the operator's override (COMMAND feed_override, 0 .. 1.5)
// and, with config arsc.enabled, the force loop (arsc_feed_source.hpp),
// which sets the override every tick inside the range the operator's scales.
// Each program starts at 1. The task owns one and steps it in the tick,
// after the snapshot and before the motion core, so the override derived
// from this tick's latched force moves this tick's path point.
//
// Bounded work, no allocation, exceptions, locks or logging in tick();
// configure() runs outside the tick (construction, apply_config).
#include "firmware/adaptive/arsc/arsc_feed_source.hpp"
#include "firmware/motion/motion_interpolator.hpp"
#include "firmware/tick/tick_record.hpp"

namespace tnv::fw {

class ProgramFeedOverride {
 public:
  // The force loop's parameters (validated with the config): a new loop.
  void configure(const arsc::ArscSourceParams& params) noexcept { (void)arsc_.configure(params); }
  // Its f* alone, on line (arsc.force_ref_n is live).
  void set_force_ref_n(double force_ref_n) noexcept { (void)arsc_.set_force_ref_n(force_ref_n); }

  // A program starts: the operator's override back at 1 (as the motion core's).
  void program_started() noexcept { operator_override_ = 1.0; }
  // The operator's override (checked by the task): the force loop combines
  // it with its own at the next tick; without the loop it goes to the
  // motion core now (false when the core refuses it).
  bool set_operator_override(double ratio, motion::MotionInterpolator& motion) noexcept;

  // One tick. `program`: a program is moving; the override goes to
  // `motion`, the loop's state into `record` (feed_override, arsc_*).
  void tick(bool program, double force_n_per_volt, motion::MotionInterpolator& motion, TickRecord& record) noexcept;

  double operator_override() const noexcept { return operator_override_; }
  const arsc::ArscFeedSource& force_loop() const noexcept { return arsc_; }

 private:
  arsc::ArscFeedSource arsc_{};
  double operator_override_ = 1.0;  // the program's override, or the force loop's cap
};

}  // namespace tnv::fw
