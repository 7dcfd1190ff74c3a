#pragma once
// The 1 ms control tick (design notes "The tick"): read the latched
// snapshot -> M-method speed over the measured period -> the motion core's
// reference (firmware/motion/: segment queue, look-ahead planner,
// interpolator) -> per-axis input shaper -> axis controllers -> DAC codes
// -> supervisor -> write outputs -> kick the watchdog. Fixed cost: no
// allocation, no exceptions, no locks, no system calls. Commands are
// accepted between ticks only.
//
// The task sequences (disabled, dwell, moving, holding, faulted); it does
// not plan. The circle, the point-to-point move, the operator's jog and a
// streamed program are all producers of segments for one MotionInterpolator
// (motion/profiled_producers.hpp, motion/jog_producer.hpp).
//
// Input shaping: the reference source runs one tick ahead; its sample
// x_{k+1} goes through the axis' StreamShaper, so the controllers get the
// shaped y_k (last tick's output) and y_{k+1}. The supervisor checks the
// following error against this shaped reference, the one the loop is told
// to follow, and scales its limit with the shaped speed: the shaper's
// delay (shaper_delay_s) is then not following error at all, and the
// limit needs no delay term. (Measured against the unshaped command the
// error would grow by delay x speed.) With the shaper disabled (default)
// the unshaped reference is passed through untouched, bit for bit.
//
// Parts (docs/architecture.md "One tick"): the task sequences and owns its
// parts, each a class with its own state and a small interface, stepped in
// the tick: HomingSequence (the HOME command's axes, their cycles, homed and
// the results), PathShapers (each axis' shaper design and on/off, the
// path's series and its hand-over once quiet), AxisExcitations (each axis'
// excitation generator and its start count, what it does to the hold point
// and the command), AxisLoop per axis (count and speed, observer,
// controllers, screw compensator, stall and plausibility monitors:
// measure, control, output), ProgramFeedOverride (the operator's override and the S3
// force loop) and SpindleControl (the
// spindle's start, ramp, at-speed and stop causes, firmware/spindle/;
// tick_task_spindle.cpp wires it). The tick's rules hold for each.
#include <array>
#include <cstdint>

#include "firmware/adaptive/arsc/arsc_feed_source.hpp"
#include "firmware/compensation/excitation.hpp"
#include "firmware/control/pid_controller.hpp"
#include "firmware/control/rdvsc_controller.hpp"
#include "firmware/control/speed_observer.hpp"
#include "firmware/homing/homing_cycle.hpp"
#include "firmware/shaper/shaper_design.hpp"
#include "firmware/shaper/stream_shaper.hpp"
#include "firmware/spindle/spindle_control.hpp"
#include "firmware/tick/axis_excitations.hpp"
#include "firmware/tick/axis_loop.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/homing_sequence.hpp"
#include "firmware/tick/path_shapers.hpp"
#include "firmware/tick/probe_report.hpp"
#include "firmware/tick/program_feed_override.hpp"
#include "firmware/motion/jog_producer.hpp"
#include "firmware/motion/motion_interpolator.hpp"
#include "firmware/motion/spindle_synced_feed.hpp"
#include "firmware/tick/tick_record.hpp"
#include "firmware/timing/encoder_position.hpp"
#include "firmware/trajectory/circle_trajectory.hpp"
#include "firmware/trajectory/point_to_point_move.hpp"
#include "hal/io_board.hpp"

namespace tnv::fw {

enum class CommandStatus : std::uint8_t {
  ok = 0,
  busy,     // not allowed in the current motion state (e.g. while moving)
  faulted,  // a fault is latched: clear it first
  invalid,  // a parameter is out of range or non-finite
  cause_present,  // clear_fault refused: the fault's cause is still asserted
  not_homed,      // config homing_required and an axis the motion moves is not homed
  spindle_running,  // apply_config: new spindle parameters while the spindle turns (stop it, let it come to rest)
  not_paused,       // cycle_start: the program is not at rest at a pause
};

constexpr const char* to_string(CommandStatus s) noexcept {
  switch (s) {
    case CommandStatus::ok: return "ok";
    case CommandStatus::busy: return "busy";
    case CommandStatus::faulted: return "faulted";
    case CommandStatus::invalid: return "invalid";
    case CommandStatus::cause_present: return "cause_present";
    case CommandStatus::not_homed: return "not_homed";
    case CommandStatus::spindle_running: return "spindle_running";
    case CommandStatus::not_paused: return "not_paused";
  }
  return "?";
}

class TickTask {
 public:
  // config must have passed validate(config); the task keeps a copy.
  TickTask(hal::IoBoard& board, const FirmwareConfig& config) noexcept;
  TickTask(const TickTask&) = delete;
  TickTask& operator=(const TickTask&) = delete;

  void tick() noexcept;

  // --- commands (between ticks)
  CommandStatus start_circle(const CircleSpec& spec) noexcept;
  // One axis from where it stands (holding) or where the table is
  // (disabled) by spec.distance_mm; the other axis holds. busy while
  // moving; invalid for a bad spec or an end beyond the soft limits.
  CommandStatus start_move(const MoveSpec& spec) noexcept;
  // Servo on, holding where the table stands (disabled -> holding).
  CommandStatus hold_position() noexcept;
  // The operator's jog stream: target speed for one axis, to be repeated
  // at least every jog deadman_s. Accepted while holding (starts the jog)
  // or jogging; the jog ends (holding) when every axis is back at rest.
  CommandStatus jog(hal::Axis axis, double speed_mm_s) noexcept;
  // A program (G-code, a CAN stream): segments pushed in order, run by the
  // look-ahead planner. From holding the first push starts the program
  // (moving); further pushes are accepted while it runs, also when the
  // queue has run dry (an underrun is a controlled stop on the path, not a
  // fault). invalid (with `why`) when the queue refuses the segment, which
  // then changes nothing; busy while another motion runs or the servo is off.
  CommandStatus push_segment(const motion::Segment& segment, motion::SegmentRefusal& why) noexcept;
  // The producer has sent its last segment: running dry is then the end (holding).
  CommandStatus end_program() noexcept;
  // Feed hold (brake on the path, keep the queue) and resume; 0 .. 1.5 feed
  // override (invalid outside). Only while a program runs (busy otherwise).
  // With the force loop on (config arsc.enabled) the override given here
  // scales the loop's range (arsc_feed_source.hpp); each program starts at 1.
  CommandStatus feed_hold(bool hold) noexcept;
  // The program goes on from the pause it rests at (a Segment::pause: M0,
  // M1, M6). The spindle was left as it was; a feed move after the pause
  // waits for it as every feed move does. busy without a program,
  // not_paused while it is not at rest at a pause (still braking for it,
  // held, stopping).
  CommandStatus cycle_start() noexcept;
  CommandStatus set_feed_override(double ratio) noexcept;
  double operator_feed_override() const noexcept { return feed_.operator_override(); }
  // The S3 force loop as the programs' feed-override source (config arsc):
  // it runs inside the tick, between the snapshot and the motion core.
  const arsc::ArscFeedSource& feed_source() const noexcept { return feed_.force_loop(); }
  // The motion core: queue, planner state, counts (free slots, underruns).
  const motion::MotionInterpolator& motion() const noexcept { return motion_; }
  // The boring planner's infeeds for the part being cut (the CAN node's, set
  // between ticks): what a feed per revolution along the depth runs at
  // (MotionInterpolator::set_depth_infeed).
  void set_depth_infeed(const InfeedAlongOverhang& schedule) noexcept { motion_.set_depth_infeed(schedule); }
  bool program_running() const noexcept { return moving() && source_ == Source::program; }
  // Where the next pushed program segment starts: the queue's end while a
  // program runs, else where the table is held (the first push starts there).
  motion::PlanePoint next_segment_start_mm() const noexcept {
    return program_running() ? motion_.queue_end_mm() : held_point();
  }
  // Input shaper per axis: the design and, separately, on/off. Every axis
  // of the path runs the enabled axes' shapers in series (path_taps.hpp), so
  // shaped axes stay in step; the new series is applied to all axes at once
  // when every axis' reference is quiet (StreamShaper), so it never makes a
  // jump. Enabling an axis that was never configured is invalid, and so is
  // a combination whose series does not fit (nothing changes then).
  // Accepted in every state.
  CommandStatus configure_shaper(hal::Axis axis, const ShaperSpec& spec) noexcept;
  // The same with the design made beforehand (design_shaper(spec,
  // kTickPeriodS), e.g. off the real-time thread): no design work here.
  CommandStatus configure_shaper(hal::Axis axis, const ShaperSpec& spec, const ShaperDesign& design) noexcept;
  static constexpr double kTickPeriodS = 1e-3;  // the control tick, and the grid shaper designs are made on
  CommandStatus enable_shaper(hal::Axis axis, bool on) noexcept;
  CommandStatus select_controller(hal::Axis axis, ControllerKind kind) noexcept;
  // Plant identification (issue 7): the axis' speed command comes from an
  // open-loop excitation (excitation.hpp) instead of its controller; its
  // reference follows the measured position, the other axis holds. A
  // sweep or multisine (issue 17) is added to the controller's command
  // instead, the controller holding the axis where it stands. Only
  // while holding with no excitation running (busy otherwise), invalid for a
  // bad spec. Ends by itself (the axis then holds where it came to rest);
  // leaving holding (a motion, disable, fault) cancels it.
  // A sweep / multisine on a carrier moves the holding reference at
  // spec.carrier_mm_s through the drive phase, then holds where it ended;
  // invalid when that travel would end outside the axis' soft limits.
  CommandStatus start_excitation(hal::Axis axis, const ExcitationSpec& spec) noexcept;
  // The carrier's travel (carrier x duration from where the axis stands) ends
  // inside the soft limits (always, without a carrier).
  bool carrier_travel_fits(hal::Axis axis, const ExcitationSpec& spec) const noexcept;
  bool exciting() const noexcept { return excite_.running(); }
  CommandStatus disable() noexcept;
  // Clears a latched fault once its cause is gone (cause_present while
  // it is not). Board trips (encoder, DAC, watchdog) are sticky: a clear
  // resets them on the board and answers cause_present; the next clear
  // after a tick succeeds if they stayed clear.
  CommandStatus clear_fault() noexcept;

  // --- commands for the CAN node (between ticks)
  // A whole new config, validated first and applied whole or not at all
  // (invalid: validate(config) failed; busy: see below). Controller gains
  // go through the controllers' bumpless set_params(); limits, DAC scale and
  // jog limits are copied (a running jog keeps the limits it started with);
  // a new encoder count is re-based so the position reading does not jump;
  // a new model rebuilds that axis' controllers (reset); a new controller
  // kind is selected (reset first when the servo is on). home_position_mm
  // is not applied: zero() moves the frame. New force-loop parameters build
  // a new loop (at rest); its f* alone is taken on line. While moving (dwell
  // or moving, jog and controlled stop included) only the live-tunable part
  // may differ: sliding.*, pid.kp / ki / kd / u_max_mm_s, the force sensor's
  // scale and arsc.force_ref_n; anything else -> busy. New spindle
  // parameters apply only while the spindle is stopped and still
  // (spindle_running otherwise).
  CommandStatus apply_config(const FirmwareConfig& config) noexcept;
  // True when `to` differs from `from` only in what apply_config() takes
  // while moving.
  static bool live_tunable_only(const FirmwareConfig& from, const FirmwareConfig& to) noexcept;
  // The S1 circle about (centre_x_mm, centre_y_mm) instead of the origin:
  // the table must stand at centre + (radius, 0). start_circle(spec) is
  // this with the origin, bit for bit.
  CommandStatus start_circle(const CircleSpec& spec, double centre_x_mm, double centre_y_mm) noexcept;
  // Controlled stop. Circle / move: the profiled element's time warp (its
  // rate falls from 1 to 0 along a raised cosine over the motion's own
  // ramp time), so the reference decelerates smoothly along the path, then
  // holds where it stopped. Program: the planner brakes on the path and
  // drops the queue. Jog: every target 0, a controlled stop on the path.
  // Dwell: holding at once. At rest: ok, nothing to do. faulted when a
  // fault is latched.
  CommandStatus stop() noexcept;
  // Assigns position_mm to where the axis stands (disabled or holding; busy
  // while moving, faulted when faulted, invalid when not finite or outside
  // the soft limits). Reference and measurement move together: bumpless.
  // The axis is no longer homed (its frame is not the index's).
  CommandStatus zero(hal::Axis axis, double position_mm) noexcept;
  // Software e-stop: latches FaultReason::remote_estop (outputs safe from
  // the next tick on). Always ok; the first latched reason wins.
  CommandStatus estop() noexcept;
  // Homing cycle (homing/homing_cycle.hpp) of the axes in `axes` (one
  // after the other in hal::kHomingOrder: X first, then Y), from holding or
  // disabled (servo on where the table stands). The other axes hold. At
  // the index edge the axis' frame moves so the latched count reads config
  // axis.homing.position_mm; the axis then
  // brakes to rest and is homed. Soft limits are off for the homing axis
  // while it homes. A cycle that runs out of travel brakes to rest and
  // latches FaultReason::homing_failed; stop() ends it (not homed). busy
  // while moving, faulted when faulted, invalid when no axis (or no
  // axis of the machine) is named.
  CommandStatus home(hal::AxisSet axes) noexcept;
  bool homed(hal::Axis axis) const noexcept { return homing_.homed(hal::index(axis)); }
  HomingResult homing_result(hal::Axis axis) const noexcept { return homing_.result(hal::index(axis)); }
  bool homing() const noexcept { return moving() && source_ == Source::homing; }

  // --- the spindle (tick_task_spindle.cpp; docs/safety.md "Spindle")
  // Every tick reads its encoder speed, sets its inhibit (a latched fault,
  // the e-stop input, a lost host) and writes its DAC code, enable and
  // direction. It stops at the program's end (cause program_end) and when a
  // program, circle or move is stopped or the servo is switched off while
  // one runs (abort), and turns only on a new start. While it is commanded
  // on and not at speed, feed moves of programs, circles and moves wait
  // (MotionInterpolator::set_feed_gate); a jog and rapids do not.
  // Between ticks, like every command. Refusals change nothing.
  SpindleResult spindle_start(SpindleDirection direction, double rpm) noexcept;
  SpindleResult spindle_set_speed(double rpm) noexcept;
  void spindle_stop() noexcept;  // cause command
  // Its parameters are the config's spindle member (apply_config(): only
  // while the spindle is stopped and still, spindle_running otherwise).
  // The CAN node's host timeout: true when the owning host went silent,
  // false once a host holds command ownership again. Its rising edge stops
  // the spindle (cause host_timeout); its falling edge does not start it.
  void set_host_lost(bool lost) noexcept;
  bool host_lost() const noexcept { return host_lost_; }
  const SpindleControl& spindle() const noexcept { return spindle_; }
  double spindle_measured_rpm() const noexcept { return spindle_rpm_; }  // signed, M-method over the last period

  // --- probe moves of programs (Segment::probe, G38.2-G38.5): the touch
  // probe input (hal::DiscreteInputs::probe) of each tick's snapshot goes to
  // the motion core; the measured position is latched in the tick that sees
  // the trip. An error outcome (failed, already_tripped) stops the program
  // as an abort (the spindle stops). Homing as any program segment.
  const ProbeReport& probe_report() const noexcept { return probe_report_; }

  // --- status
  const TickRecord& last_record() const noexcept { return record_; }
  const FaultRecord& fault() const noexcept { return fault_; }
  const TickCounters& counters() const noexcept { return counters_; }
  MotionState state() const noexcept { return state_; }
  ControllerKind controller(hal::Axis axis) const noexcept { return axis_[hal::index(axis)].kind(); }
  const FirmwareConfig& config() const noexcept { return config_; }
  // Ticks from the start of motion to the end of the trajectory (inclusive),
  // unshaped; a shaped axis keeps moving for up to its shaper's span after.
  std::int64_t motion_ticks() const noexcept { return motion_ticks_; }
  // The active shaper's delay (centroid of its taps), 0 when it is off:
  // what multi-axis synchronisation and host-side comparisons shift by.
  double shaper_delay_s(hal::Axis axis) const noexcept;
  const StreamShaper& shaper(hal::Axis axis) const noexcept { return shapers_.shaper(hal::index(axis)); }
  // This axis' own shaper is on and the path shaper that includes it is active.
  bool shaper_active(hal::Axis axis) const noexcept { return shapers_.active(hal::index(axis)); }
  const ShaperDesign& shaper_design(hal::Axis axis) const noexcept { return shapers_.design(hal::index(axis)); }
  std::uint32_t jog_deadman_stops() const noexcept;
  // Servo on and the reference in motion: dwell or moving (jog and
  // controlled stop included).
  bool moving() const noexcept { return state_ == MotionState::dwell || state_ == MotionState::moving; }
  bool jogging() const noexcept { return state_ == MotionState::moving && source_ == Source::jog; }
  bool stopping() const noexcept { return moving() && (stop_requested_ || motion_.state() == motion::MotionState::stopping); }
  // The last motion started (running or finished) was a circle, and its
  // centre (the origin for start_circle(spec)).
  bool circle_motion() const noexcept { return source_ == Source::circle; }
  double circle_centre_mm(hal::Axis axis) const noexcept { return centre_mm_[hal::index(axis)]; }
  // Where the axis stands: the held reference when holding, else the
  // measured position of the last tick.
  double standing_mm(hal::Axis axis) const noexcept;
  // What the controllers run with now (the sliding set of both DVSC+DDC and
  // R-DVSC+DDC; DVSC+DDC applies it with gamma = 0).
  const SlidingModeParams& sliding_params(hal::Axis axis) const noexcept { return axis_[hal::index(axis)].sliding_params(); }
  const PidParams& pid_params(hal::Axis axis) const noexcept { return axis_[hal::index(axis)].pid_params(); }
  // The model the controllers were formed with, and the speed observer's gains.
  const AxisModel& controller_model(hal::Axis axis) const noexcept { return axis_[hal::index(axis)].controller_model(); }
  const SpeedObserverParams& observer_params(hal::Axis axis) const noexcept {
    return axis_[hal::index(axis)].observer_params();
  }

 private:
  enum class Source : std::uint8_t { circle, move, jog, program, homing };
  static std::int64_t ticks_for(double seconds) noexcept;

  void read_timebase(bool bus_ok, std::uint32_t& ticks_missed, bool& advanced) noexcept;
  void update_reference() noexcept;
  void set_reference(std::size_t i, const AxisSample& now, const AxisSample& next) noexcept;
  void shape_reference(std::size_t i, const AxisSample& now, const AxisSample& next) noexcept;
  void moving_reference() noexcept;
  void homing_reference() noexcept;            // tick_task_homing.cpp
  // tick_task_spindle.cpp: the inhibit from the fault, e-stop and host
  // state now; the spindle's tick and outputs (after the supervisor).
  void update_spindle_inhibit() noexcept;
  void spindle_tick() noexcept;
  // A running program, circle or move ends early (stop, disable): the spindle stops (abort).
  void abort_spindle() noexcept;
  // After the motion core's tick: latch the trip position, publish an outcome (tick_task_probe.cpp).
  void probe_tick(const motion::MotionReference& r) noexcept;
  // A program's spindle command the motion core rests at (Segment::spindle):
  // carried out now; a start the spindle refuses (inhibited) stops the program.
  void program_spindle_change(const motion::Segment& change) noexcept;
  // Moves axis a's frame by delta_mm: measurement and reference together (bumpless).
  void shift_frame(std::size_t a, double delta_mm) noexcept;
  // config homing_required and one of the axes is not homed.
  bool homing_missing(hal::AxisSet axes) const noexcept {
    if (!config_.homing_required) return false;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i)
      if (hal::contains(axes, hal::axis_from_index(i)) && !homing_.homed(i)) return true;
    return false;
  }
  void reset_controllers() noexcept;
  bool servo_on() const noexcept;
  void latch_fault(const FaultRecord& f) noexcept;
  // Starts a profiled producer's segment from `start` (the circle, the move).
  CommandStatus start_profiled(const motion::Segment& segment, const std::array<AxisSample, hal::kAxisCount>& start,
                               double dwell_s, Source source) noexcept;
  // Each axis' position in `samples`, as a point of the motion core.
  static motion::PlanePoint positions_mm(const std::array<AxisSample, hal::kAxisCount>& samples) noexcept {
    motion::PlanePoint p{};
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) p[i] = samples[i].position_mm;
    return p;
  }
  motion::PlanePoint held_point() const noexcept { return positions_mm(hold_); }

  hal::IoBoard& board_;
  FirmwareConfig config_;
  bool config_validated_ = false;  // config_ passed validate() (apply_config): a change re-checks only what differs
  // One loop per axis, each from its own config (axis_loop.hpp): count,
  // speed, observer, controllers, screw compensator, stall and plausibility.
  static std::array<AxisLoop, hal::kAxisCount> make_axis_loops(const FirmwareConfig& config,
                                                               unsigned counter_bits) noexcept;
  std::array<AxisLoop, hal::kAxisCount> axis_;
  motion::MotionInterpolator motion_{};
  motion::JogProducer jog_{};
  ProgramFeedOverride feed_{};  // the operator's override and the force loop (program_feed_override.hpp)
  Source source_ = Source::circle;
  std::int64_t dwell_ticks_ = 0;
  std::int64_t motion_ticks_ = 0;
  std::int64_t phase_tick_ = 0;  // ticks into the current dwell / motion phase
  std::array<AxisSample, hal::kAxisCount> hold_{};  // reference while dwelling / holding
  std::array<AxisSample, hal::kAxisCount> next_{};  // x_ref,k+1
  MotionState state_ = MotionState::disabled;
  FaultRecord fault_{};
  TickCounters counters_{};
  TickRecord record_{};
  hal::DiscreteInputs last_inputs_{};
  bool first_tick_ = true;
  std::uint32_t last_sequence_ = 0;
  std::uint32_t last_clock_ = 0;
  bool stop_requested_ = false;                      // stop() of a jog, until it rests
  bool centred_ = false;                             // circle about centre_mm_, not the origin
  std::array<double, hal::kAxisCount> centre_mm_{};  // circle centre
  std::array<double, hal::kAxisCount> origin_mm_{};  // position of encoder count 0 (home, moved by zero())
  // Kept after the hot per-tick state (the shapers' ring buffers are large).
  PathShapers shapers_{};
  AxisExcitations excite_{};  // each axis' excitation and its start count (axis_excitations.hpp)
  bool one_nominal_period_ = false;
  bool board_answering_ = true;  // the last tick's batched read succeeded (clear_fault refuses otherwise)
  HomingSequence homing_{};  // the HOME command's axes, their cycles, homed and the results
  SpindleControl spindle_{};  // the spindle's command logic (firmware/spindle/spindle_control.hpp)
  EncoderPosition spindle_encoder_{};
  double spindle_rpm_ = 0.0;  // measured (signed)
  motion::SpindleSyncedFeed spindle_sync_{};  // the speed a feed per revolution runs at (spindle_synced_feed.hpp)
  bool host_lost_ = false;
  std::array<double, hal::kAxisCount> probe_trip_mm_{};  // latched at the trip, published with the outcome
  ProbeReport probe_report_{};
};

}  // namespace tnv::fw
