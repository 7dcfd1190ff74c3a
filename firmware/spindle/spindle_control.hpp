#pragma once
// The spindle's command logic (design notes "Spindle"): it turns only on an
// explicit start, stops on every fault, e-stop and host loss, and never
// starts again by itself after any of them. The one way from "off" to "on"
// is start(): no event, no clearing of a cause, no parameter change and no
// tick sets it, so "never starts by itself" is a property of this class's
// shape, and tests/firmware/spindle/ checks it over random event sequences.
//
// Feed moves ask feed_permitted(): while the spindle is commanded on, a
// feed move may start only once it is at speed (the firmware cannot know
// where the stock is; the rule is on the spindle's state).
//
// Tick path: noexcept, no heap, fixed work.
#include <cstddef>
#include <cstdint>

#include "firmware/spindle/spindle_params.hpp"
#include "hal/listed_enum.hpp"

namespace tnv::fw {

// The direction asked for, in wire order (SPINDLE.direction).
#define TNV_SPINDLE_DIRECTIONS(X) \
  X(forward)  /* M3, clockwise seen from above */ \
  X(reverse)  /* M4 */

TNV_LISTED_ENUM(SpindleDirection, TNV_SPINDLE_DIRECTIONS)

// Why the spindle was last stopped, with how: an immediate stop drops the
// enable and zeroes the command at once (the drive coasts or brakes on its
// own, as the e-stop chain requires); a controlled one ramps the command
// down at accel_rpm_s with the enable held, then drops it at standstill.
// The one list: enum, names and kind.
#define TNV_SPINDLE_STOP_CAUSES(X)                                          \
  X(none, false)          /* never stopped since power-up */                \
  X(command, false)       /* an explicit stop (M5, CAN) */                  \
  X(program_end, false)   /* M2/M30, or the program's stream ended */       \
  X(abort, false)         /* the program or motion was aborted */           \
  X(host_timeout, false)  /* the owning host went silent */                 \
  X(fault, true)          /* a fault was latched */                         \
  X(estop, true)          /* the e-stop input */

TNV_LISTED_ENUM(SpindleStopCause, TNV_SPINDLE_STOP_CAUSES)

inline constexpr bool kSpindleStopIsImmediate[] = {
#define TNV_IMMEDIATE(name, immediate) immediate,
    TNV_SPINDLE_STOP_CAUSES(TNV_IMMEDIATE)
#undef TNV_IMMEDIATE
};

// Answer to a start, a speed change or a parameter change. Nothing changes
// unless it is ok.
enum class SpindleResult : std::uint8_t {
  ok,
  inhibited,    // a fault, e-stop or host loss is present: clear it, then start again
  bad_speed,    // not finite, not above zero or above max_rpm
  not_running,  // a speed change while the spindle is not commanded on (start names its speed)
  busy,         // parameters change only while the spindle is stopped and still
  invalid,      // the parameter set is out of range (validate())
};

struct SpindleOutputs {
  bool enable = false;        // the drive's enable output
  bool reverse = false;       // the direction output (true: M4)
  double command_rpm = 0.0;   // signed: what the DAC is written with (negative: reverse)
  std::uint16_t dac_code = 2048;  // the command as the spindle DAC's code (mid-scale: 0 V)
};

class SpindleControl {
 public:
  SpindleControl() noexcept = default;

  // Commands, between ticks.
  SpindleResult start(SpindleDirection direction, double rpm) noexcept;
  SpindleResult set_speed(double rpm) noexcept;
  void stop(SpindleStopCause cause) noexcept;
  SpindleResult set_params(const SpindleParams& p) noexcept;
  // set_params() would not answer busy: stopped and still.
  bool can_set_params() const noexcept;

  // Once per tick, first: whether a cause that forbids turning is present
  // (a latched fault, the e-stop input, no owning host). Its rising edge
  // stops the spindle (fault and e-stop at once); its falling edge does
  // nothing: the spindle stays off until the next start().
  void set_inhibit(bool inhibited, SpindleStopCause cause) noexcept;

  // One tick: the spindle's measured speed (signed rpm, from its encoder)
  // and the tick's period in seconds. Ramps the command, judges at-speed.
  SpindleOutputs tick(double measured_rpm, double period_s) noexcept;

  bool commanded_on() const noexcept { return on_; }
  bool at_speed() const noexcept { return on_ && at_speed_; }
  // A feed move may start: the spindle is commanded off, or on and at speed.
  bool feed_permitted() const noexcept { return !on_ || at_speed_; }
  // Turning or still enabled (a controlled stop in progress counts).
  bool active() const noexcept { return on_ || outputs_.enable; }
  SpindleStopCause last_stop_cause() const noexcept { return last_stop_; }
  bool inhibited() const noexcept { return inhibited_; }  // a start would be refused
  double target_rpm() const noexcept;  // signed; 0 when commanded off
  const SpindleOutputs& outputs() const noexcept { return outputs_; }
  const SpindleParams& params() const noexcept { return params_; }
  std::uint32_t starts() const noexcept { return starts_; }  // accepted start() calls

 private:
  SpindleParams params_{};
  SpindleOutputs outputs_{};
  bool on_ = false;
  bool inhibited_ = false;
  bool at_speed_ = false;
  bool immediate_stop_ = false;  // the next tick zeroes at once
  SpindleDirection direction_ = SpindleDirection::forward;
  double rpm_ = 0.0;             // commanded magnitude while on
  double last_measured_rpm_ = 0.0;
  std::uint32_t in_window_ticks_ = 0;
  std::uint32_t starts_ = 0;
  SpindleStopCause last_stop_ = SpindleStopCause::none;
};

// Signed spindle rpm -> the spindle DAC's offset-binary code (12 bit,
// +-10 V = +-12,000 rpm), rounded and saturated.
std::uint16_t spindle_dac_code(double command_rpm) noexcept;

// M-method spindle speed: encoder counts over the measured period.
double spindle_rpm(std::int64_t delta_counts, std::uint32_t period_clocks) noexcept;

}  // namespace tnv::fw
