// TickTask's motion commands: every motion is a producer of segments for
// the motion core (tick_task.hpp); the task checks the state and starts it.
#include <algorithm>
#include <cmath>

#include "firmware/motion/profiled_producers.hpp"
#include "firmware/tick/tick_task.hpp"

namespace tnv::fw {

CommandStatus TickTask::start_profiled(const motion::Segment& segment,
                                       const std::array<AxisSample, hal::kAxisCount>& start, double dwell_s,
                                       Source source) noexcept {
  motion_.reset_at(positions_mm(start));
  if (motion_.push(segment) != motion::SegmentRefusal::none) return CommandStatus::invalid;
  motion_.end_program();
  source_ = source;
  stop_requested_ = false;
  dwell_ticks_ = ticks_for(dwell_s);
  phase_tick_ = 0;
  hold_ = start;
  state_ = dwell_ticks_ > 0 ? MotionState::dwell : MotionState::moving;
  return CommandStatus::ok;
}

namespace {
// What the circle and programs move (and need homed): the XY plane.
constexpr hal::AxisSet kPlaneAxes = hal::axis_bit(hal::kPlaneFirst) | hal::axis_bit(hal::kPlaneSecond);

// The axes beyond the XY plane a line or arc from `start_mm` moves (Z: a plunge, a retract, a helix;
// an arc in G18 or G19 moves both axes of its plane, whether or not its end differs on them).
hal::AxisSet moved_beyond_plane(const motion::Segment& s, const motion::PlanePoint& start_mm) noexcept {
  hal::AxisSet out = 0;
  if (s.kind == motion::SegmentKind::dwell) return out;
  const bool arc = s.kind == motion::SegmentKind::arc_cw || s.kind == motion::SegmentKind::arc_ccw;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    if (s.end_mm[i] != start_mm[i] || (arc && motion::in_plane(motion::plane_axes(s.plane), i)))
      out |= hal::axis_bit(hal::axis_from_index(i));
  return out & static_cast<hal::AxisSet>(~kPlaneAxes);
}
}  // namespace

CommandStatus TickTask::start_circle(const CircleSpec& spec) noexcept { return start_circle(spec, 0.0, 0.0); }

CommandStatus TickTask::start_circle(const CircleSpec& spec, double centre_x_mm, double centre_y_mm) noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (state_ == MotionState::dwell || state_ == MotionState::moving) return CommandStatus::busy;
  if (validate(spec)[0] != '\0') return CommandStatus::invalid;
  if (!std::isfinite(centre_x_mm) || !std::isfinite(centre_y_mm)) return CommandStatus::invalid;
  if (homing_missing(kPlaneAxes)) return CommandStatus::not_homed;
  // A circle in the XY plane, at the height where the head stands.
  motion::PlanePoint centre{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) centre[i] = record_.axis[i].position_mm;
  centre[hal::index(hal::kPlaneFirst)] = centre_x_mm;
  centre[hal::index(hal::kPlaneSecond)] = centre_y_mm;
  const motion::PlanePoint start_mm = motion::circle_start_mm(spec, centre);
  // The table must already stand at the start point (within the following-error floor).
  std::array<AxisSample, hal::kAxisCount> start{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const double error_mm = start_mm[i] - record_.axis[i].position_mm;
    if (!(std::fabs(error_mm) < config_.supervisor.axis[i].following.floor_mm)) return CommandStatus::invalid;
    start[i] = {start_mm[i], 0.0};
  }
  if (const CommandStatus st = start_profiled(motion::circle_segment(spec, centre), start, spec.dwell_s, Source::circle);
      st != CommandStatus::ok)
    return st;
  centred_ = centre_x_mm != 0.0 || centre_y_mm != 0.0;
  centre_mm_ = centre;
  motion_ticks_ = static_cast<std::int64_t>(std::ceil(CircleTrajectory(spec).duration_s() / kTickPeriodS - 1e-9));
  reset_controllers();
  return CommandStatus::ok;
}

void TickTask::reset_controllers() noexcept {
  for (AxisLoop& loop : axis_) loop.reset_controllers();
}

CommandStatus TickTask::start_move(const MoveSpec& spec) noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (state_ == MotionState::dwell || state_ == MotionState::moving) return CommandStatus::busy;
  if (validate(spec)[0] != '\0') return CommandStatus::invalid;
  const std::size_t a = hal::index(spec.axis);
  if (homing_missing(hal::axis_bit(spec.axis))) return CommandStatus::not_homed;
  const bool was_on = state_ == MotionState::holding;
  // From a servo-off start the table's position is the start (bumpless).
  std::array<AxisSample, hal::kAxisCount> start = hold_;
  if (!was_on)
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) start[i] = {record_.axis[i].position_mm, 0.0};
  const double end_mm = start[a].position_mm + spec.distance_mm;
  const AxisLimits& lim = config_.supervisor.axis[a];
  if (!(end_mm >= lim.position_min_mm && end_mm <= lim.position_max_mm)) return CommandStatus::invalid;
  const motion::Segment segment = motion::move_segment(spec, positions_mm(start));
  if (const CommandStatus st = start_profiled(segment, start, spec.dwell_s, Source::move); st != CommandStatus::ok)
    return st;
  motion_ticks_ = static_cast<std::int64_t>(
      std::ceil(PointToPointMove(spec, start[a].position_mm).duration_s() / kTickPeriodS - 1e-9));
  if (!was_on) reset_controllers();
  return CommandStatus::ok;
}

CommandStatus TickTask::hold_position() noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (state_ != MotionState::disabled) return state_ == MotionState::holding ? CommandStatus::ok : CommandStatus::busy;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) hold_[i] = {record_.axis[i].position_mm, 0.0};
  reset_controllers();
  state_ = MotionState::holding;
  return CommandStatus::ok;
}

CommandStatus TickTask::jog(hal::Axis axis, double speed_mm_s) noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  const bool jogging = state_ == MotionState::moving && source_ == Source::jog;
  if (state_ != MotionState::holding && !jogging) return CommandStatus::busy;
  if (jogging && stop_requested_) return CommandStatus::busy;  // a controlled stop wins until the jog rests
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount) return CommandStatus::invalid;
  if (!jogging && speed_mm_s == 0.0) return CommandStatus::ok;  // standing still already
  if (!jogging) {
    // Validate before starting anything: nothing is half-applied.
    const JogLimits& lim = config_.axis[a].jog;
    if (!std::isfinite(speed_mm_s) || std::fabs(speed_mm_s) > lim.speed_max_mm_s) return CommandStatus::invalid;
    std::array<JogLimits, hal::kAxisCount> jog_limits{};
    double accel_cap = config_.axis[0].jog.accel_mm_s2;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      jog_limits[i] = config_.axis[i].jog;
      accel_cap = std::min(accel_cap, jog_limits[i].accel_mm_s2);
    }
    motion_.reset_at(held_point(), accel_cap);
    jog_.start(jog_limits);
    source_ = Source::jog;
    stop_requested_ = false;
    phase_tick_ = 0;
    motion_ticks_ = 0;
    state_ = MotionState::moving;
  }
  return jog_.command(a, speed_mm_s) ? CommandStatus::ok : CommandStatus::invalid;
}

CommandStatus TickTask::push_segment(const motion::Segment& segment, motion::SegmentRefusal& why) noexcept {
  why = motion::SegmentRefusal::none;
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  const bool running = program_running();
  if (!running && state_ != MotionState::holding) return CommandStatus::busy;
  if (running && stop_requested_) return CommandStatus::busy;
  if (!running && homing_missing(kPlaneAxes)) return CommandStatus::not_homed;
  if (homing_missing(moved_beyond_plane(segment, next_segment_start_mm()))) return CommandStatus::not_homed;  // a Z move needs Z homed
  if (segment.profiled()) {  // the circle and move producers' elements; a program is planned
    why = motion::SegmentRefusal::bad_ramp;
    return CommandStatus::invalid;
  }
  if ((segment.spindle == motion::SpindleChange::forward || segment.spindle == motion::SpindleChange::reverse) &&
      segment.spindle_rpm > spindle_.params().max_rpm) {
    why = motion::SegmentRefusal::bad_spindle;  // the spindle would refuse it when the program reaches it
    return CommandStatus::invalid;
  }
  if (!running) motion_.reset_at(held_point());  // a refused first segment leaves the task holding
  // Every coordinate is a target: the wire fills what an element does not
  // carry with where it starts (segment_wire.hpp), so Z moves only when asked.
  why = motion_.push(segment);
  if (why != motion::SegmentRefusal::none) return CommandStatus::invalid;
  if (!running) {
    source_ = Source::program;
    feed_.program_started();  // reset_at() put the motion core's override at 1
    stop_requested_ = false;
    phase_tick_ = 0;
    motion_ticks_ = 0;
    centred_ = false;
    state_ = MotionState::moving;
  }
  return CommandStatus::ok;
}

CommandStatus TickTask::end_program() noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (!program_running()) return CommandStatus::busy;
  motion_.end_program();
  return CommandStatus::ok;
}

CommandStatus TickTask::feed_hold(bool hold) noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (!program_running()) return CommandStatus::busy;
  if (hold) motion_.hold();
  else motion_.resume();
  return CommandStatus::ok;
}

CommandStatus TickTask::cycle_start() noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (!program_running()) return CommandStatus::busy;
  return motion_.release_pause() ? CommandStatus::ok : CommandStatus::not_paused;
}

CommandStatus TickTask::set_feed_override(double ratio) noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (!std::isfinite(ratio) || ratio < 0.0 || ratio > motion::kMaxFeedOverride) return CommandStatus::invalid;
  if (!program_running()) return CommandStatus::busy;
  return feed_.set_operator_override(ratio, motion_) ? CommandStatus::ok : CommandStatus::invalid;
}

std::uint32_t TickTask::jog_deadman_stops() const noexcept { return jog_.deadman_stops(); }

CommandStatus TickTask::stop() noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (state_ == MotionState::dwell) {
    if (source_ != Source::homing) abort_spindle();
    state_ = MotionState::holding;  // the reference never left hold_
    return CommandStatus::ok;
  }
  if (state_ != MotionState::moving || stopping()) return CommandStatus::ok;
  if (source_ != Source::jog && source_ != Source::homing) abort_spindle();  // the program, circle or move is aborted
  if (source_ == Source::jog) {
    jog_.release();
    stop_requested_ = true;
  } else if (source_ == Source::homing) {
    homing_.abort();  // brakes to rest, then holds, not homed
    stop_requested_ = true;
  } else {
    motion_.stop();
  }
  return CommandStatus::ok;
}

CommandStatus TickTask::zero(hal::Axis axis, double position_mm) noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (moving()) return CommandStatus::busy;
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount || !std::isfinite(position_mm)) return CommandStatus::invalid;
  const AxisLimits& lim = config_.supervisor.axis[a];
  if (!(position_mm >= lim.position_min_mm && position_mm <= lim.position_max_mm)) return CommandStatus::invalid;
  // Measurement and reference shift together: the following error is unchanged.
  shift_frame(a, position_mm - record_.axis[a].position_mm);
  shapers_.reset(a, hold_[a]);  // at rest: its history is the old frame's rest point
  homing_.unhome(a);            // the frame is the operator's now, not the index's
  return CommandStatus::ok;
}

CommandStatus TickTask::start_excitation(hal::Axis axis, const ExcitationSpec& spec) noexcept {
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount || !validate(spec).ok) return CommandStatus::invalid;
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (state_ != MotionState::holding || exciting()) return CommandStatus::busy;
  if (!carrier_travel_fits(axis, spec)) return CommandStatus::invalid;
  excite_.start(a, spec, axis_[a].counts());
  return CommandStatus::ok;
}

bool TickTask::carrier_travel_fits(hal::Axis axis, const ExcitationSpec& spec) const noexcept {
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount) return false;
  return AxisExcitations::carrier_travel_fits(config_.supervisor.axis[a], standing_mm(axis), spec);
}

double TickTask::standing_mm(hal::Axis axis) const noexcept {
  const std::size_t a = hal::index(axis);
  return state_ == MotionState::holding ? hold_[a].position_mm : record_.axis[a].position_mm;
}

}  // namespace tnv::fw
