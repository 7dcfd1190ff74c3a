#pragma once
// One axis' closed loop inside TickTask (docs/architecture.md "One tick"):
// its encoder count and M-method speed, the speed observer, the three
// controllers and which one is active, the screw compensator, the stall and
// plausibility monitors. The task steps it in three calls per tick:
//   measure()  the snapshot's count -> the record's position and speed, the
//              observer, the monitors (against the last tick's outputs);
//   control()  the reference -> the speed command and the supervisor's input;
//   output()   the command -> the DAC code (or mid-scale with outputs off).
// The task owns the frame (the origin of count 0), the reference, the
// excitations and the shapers and passes what a step needs; the loop keeps
// nothing of them. Everything it reads of the config comes in as arguments.
//
// Bounded work, no allocation, exceptions, locks or logging. The record and
// the supervisor input are filled field by field in place (no struct
// temporaries per tick: docs/performance.md).
#include <cstddef>
#include <cstdint>

#include "firmware/compensation/screw_compensation.hpp"
#include "firmware/control/pid_controller.hpp"
#include "firmware/control/rdvsc_controller.hpp"
#include "firmware/control/speed_observer.hpp"
#include "firmware/supervisor/supervisor.hpp"
#include "firmware/tick/axis_excitations.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_record.hpp"
#include "firmware/timing/encoder_position.hpp"
#include "firmware/trajectory/plane_reference.hpp"

namespace tnv::fw {

class AxisLoop {
 public:
  // From the axis' config; the encoder counter is `counter_bits` wide.
  AxisLoop(const AxisConfig& config, unsigned counter_bits) noexcept;

  // --- the count, from the snapshot's timebase
  // Power-up: the latched count `raw` is count 0's reading; no speed yet.
  void restart_count(std::uint32_t raw) noexcept { encoder_.reset(raw); }
  // One advanced snapshot: the count extended by `raw`, the speed over
  // period_clocks (M-method).
  void count(std::uint32_t raw, double count_mm, std::uint32_t period_clocks) noexcept;
  std::int64_t counts() const noexcept { return encoder_.counts(); }
  // The extended count a latched reading `raw` (e.g. the index) stands for.
  std::int64_t counts_at(std::uint32_t raw) const noexcept { return encoder_.counts_at(raw); }

  // --- the tick
  // The measured state into r (position from origin_mm, speed, the observer)
  // and the monitors; r still holds the last tick's outputs, which acted
  // over the interval this snapshot ends. `advanced`, `ticks_missed` and
  // `one_nominal_period` tell the snapshot's timing.
  void measure(double origin_mm, const AxisConfig& config, const AxisLimits& limits, bool advanced,
               std::uint32_t ticks_missed, bool one_nominal_period, AxisTickRecord& r) noexcept;
  // The speed command for r's reference (y_k) and next (y_{k+1}), tick_s
  // apart, into r
  // (command, excitation, s, d_hat) and the supervisor's input `check`
  // (all but soft_limits, the homing's). Servo off (`on` false): 0. An
  // excitation of axis `a` in `excite` replaces the controller (open loop)
  // or adds to it. True when an open-loop excitation ended this tick: the
  // controller is reset, and the task rests the axis' shaper at its hold point.
  bool control(bool on, const AxisConfig& config, const AxisSample& next, double tick_s, AxisExcitations& excite,
               std::size_t a, AxisTickRecord& r, AxisCheckInput& check) noexcept;
  // r's command as a DAC code into r (mid-scale and not enabled when the
  // outputs are not live); the code to write.
  static std::uint16_t output(bool outputs_live, const DacScale& dac, AxisTickRecord& r) noexcept;

  // --- between ticks
  // A new config `to` over `from` (validated and allowed by the task): gains
  // bumpless, a new model rebuilds the controllers, a new observer restarts
  // from position_mm, the plausibility history restarts when its basis
  // changes, a new controller kind is selected (reset when servo_on).
  void apply(const AxisConfig& from, const AxisConfig& to, bool servo_on, double position_mm) noexcept;
  void select(ControllerKind kind) noexcept { kind_ = kind; }
  void reset_controllers() noexcept;
  // The frame moved by delta_mm (homing, zero): the observer moves with it.
  void shift_frame(double delta_mm) noexcept { observer_.shift(delta_mm); }

  ControllerKind kind() const noexcept { return kind_; }
  const PidParams& pid_params() const noexcept { return pid_.params(); }
  const SlidingModeParams& sliding_params() const noexcept { return rdvsc_.params(); }
  const AxisModel& controller_model() const noexcept { return rdvsc_.model(); }
  const SpeedObserverParams& observer_params() const noexcept { return observer_.params(); }
  // The screw compensation's offset at the reference's next sample: the
  // measured (motor-side) position less this is the table's.
  double screw_offset_mm() const noexcept { return screw_.next_offset_mm(); }
  const StallMonitor& stall() const noexcept { return stall_; }
  const PlausibilityVerdict& plausibility() const noexcept { return plausibility_; }

 private:
  AxisController& active() noexcept;

  PidController pid_;
  RdvscController dvsc_;
  RdvscController rdvsc_;
  ControllerKind kind_;
  EncoderPosition encoder_;
  double speed_mm_s_ = 0.0;  // M-method over the last period
  SpeedObserver observer_{};  // config.observer (issue 7); untouched while off
  StallMonitor stall_{};      // encoder_stall (supervisor.hpp)
  ScrewCompensator screw_{};  // table-side reference -> motor-side
  MotionPlausibility plausibility_monitor_{};  // encoder_implausible, runaway
  PlausibilityVerdict plausibility_{};         // this tick's verdict
};

}  // namespace tnv::fw
