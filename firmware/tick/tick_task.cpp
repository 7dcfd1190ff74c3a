#include "firmware/tick/tick_task.hpp"

#include <cmath>

#include "firmware/io/dac_code.hpp"
#include "firmware/supervisor/supervisor.hpp"
#include "firmware/timing/m_method_speed.hpp"

namespace tnv::fw {

namespace {
constexpr double kTickPeriodS = 1e-3;
constexpr std::uint32_t kNominalPeriodClocks = 10'000;
constexpr std::uint32_t kLateToleranceClocks = 500;  // 5% of a period

std::int64_t ticks_for(double seconds) noexcept {
  return static_cast<std::int64_t>(std::llround(seconds / kTickPeriodS));
}
}  // namespace

TickTask::AxisLoop::AxisLoop(const AxisConfig& config) noexcept
    : pid(config.model, config.pid),
      dvsc(ControllerKind::dvsc, config.model, config.sliding),
      rdvsc(ControllerKind::rdvsc, config.model, config.sliding),
      kind(config.controller) {}

AxisController& TickTask::AxisLoop::active() noexcept {
  switch (kind) {
    case ControllerKind::pid: return pid;
    case ControllerKind::dvsc: return dvsc;
    case ControllerKind::rdvsc: break;
  }
  return rdvsc;
}

TickTask::TickTask(hal::IoBoard& board, const FirmwareConfig& config) noexcept
    : board_(board), config_(config), axis_{AxisLoop(config.axis[0]), AxisLoop(config.axis[1])} {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    axis_[i].encoder = EncoderPosition(board_.counter_bits());
    hold_[i] = {config_.axis[i].home_position_mm, 0.0};
    next_[i] = hold_[i];
  }
}

bool TickTask::servo_on() const noexcept {
  return state_ == MotionState::dwell || state_ == MotionState::moving || state_ == MotionState::holding;
}

void TickTask::latch_fault(const FaultRecord& f) noexcept {
  if (state_ == MotionState::faulted) return;  // the first reason wins
  fault_ = f;
  state_ = MotionState::faulted;
}

void TickTask::read_timebase(bool bus_ok, std::uint32_t& ticks_missed, bool& advanced) noexcept {
  ticks_missed = 0;
  advanced = bus_ok;
  if (!bus_ok) return;
  const hal::TickLatch latch = board_.latched_tick();
  if (first_tick_) {
    // Power-up: this position is home; no period measured yet.
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) axis_[i].encoder.reset(board_.latched_count(hal::axis_from_index(i)));
    last_sequence_ = latch.sequence;
    last_clock_ = latch.clock_10mhz;
    record_.period_clocks = kNominalPeriodClocks;
    first_tick_ = false;
    return;
  }
  const std::uint32_t sequence_step = latch.sequence - last_sequence_;
  const std::uint32_t period_clocks = elapsed_clocks(last_clock_, latch.clock_10mhz);
  if (sequence_step == 0 || period_clocks == 0) {
    advanced = false;  // the board did not tick: never reuse stale data silently
    return;
  }
  ticks_missed = sequence_step - 1;
  counters_.missed_ticks += ticks_missed;
  const std::uint32_t expected = kNominalPeriodClocks * sequence_step;
  const std::uint32_t deviation = period_clocks > expected ? period_clocks - expected : expected - period_clocks;
  if (deviation > kLateToleranceClocks) ++counters_.late_ticks;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    AxisLoop& loop = axis_[i];
    const std::int64_t delta = loop.encoder.update(board_.latched_count(hal::axis_from_index(i)));
    loop.speed_mm_s = m_method_speed_mm_s(delta, config_.axis[i].count_mm, period_clocks);
  }
  last_sequence_ = latch.sequence;
  last_clock_ = latch.clock_10mhz;
  record_.period_clocks = period_clocks;
}

void TickTask::set_reference(std::size_t i, const AxisSample& now, const AxisSample& next) noexcept {
  record_.axis[i].reference_mm = now.position_mm;
  record_.axis[i].reference_speed_mm_s = now.speed_mm_s;
  next_[i] = next;
}

// The source's x_k and x_{k+1} through the axis' shaper: the controllers
// get y_k (the shaper's previous output) and y_{k+1} = shaper(x_{k+1}).
void TickTask::shape_reference(std::size_t i, const AxisSample& now, const AxisSample& next) noexcept {
  record_.axis[i].unshaped_reference_mm = now.position_mm;
  StreamShaper& shaper = shaping_[i].shaper;
  if (!shaper.shaping() && !shaper.change_pending()) {
    shaper.step(next);            // the identity; it only notes whether the stream rests
    set_reference(i, now, next);  // off: the unshaped path, bit for bit
    return;
  }
  const bool was_shaping = shaper.shaping();
  const AxisSample shaped_now = shaper.output();
  const AxisSample shaped_next = shaper.step(next);
  if (!was_shaping && !shaper.shaping()) {
    set_reference(i, now, next);  // off: the unshaped path, bit for bit
  } else {
    set_reference(i, shaped_now, shaped_next);
  }
}

bool TickTask::shapers_settled() const noexcept {
  for (const AxisShaping& s : shaping_)
    if (s.shaper.shaping() && !s.shaper.quiet()) return false;
  return true;
}

void TickTask::moving_reference() noexcept {
  const double t_s = static_cast<double>(phase_tick_) * kTickPeriodS;
  record_.motion_tick = phase_tick_;
  ++phase_tick_;
  switch (source_) {
    case Source::circle: {
      const PlaneSample now = circle_.at(t_s);
      const PlaneSample next = circle_.at(t_s + kTickPeriodS);
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) shape_reference(i, now.axis[i], next.axis[i]);
      if (phase_tick_ > motion_ticks_ && shapers_settled()) {
        state_ = MotionState::holding;
        for (std::size_t i = 0; i < hal::kAxisCount; ++i) hold_[i] = {next.axis[i].position_mm, 0.0};
      }
      return;
    }
    case Source::move: {
      // x_{k+1} at (k + 1) T, so it is bit for bit next tick's x_k.
      const double t_next_s = static_cast<double>(phase_tick_) * kTickPeriodS;
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
        if (i == move_axis_) {
          shape_reference(i, move_.at(t_s), move_.at(t_next_s));
        } else {
          shape_reference(i, hold_[i], hold_[i]);
        }
      }
      if (phase_tick_ > motion_ticks_ && shapers_settled()) {
        state_ = MotionState::holding;
        hold_[move_axis_] = {move_.end_mm(), 0.0};
      }
      return;
    }
    case Source::jog: {
      bool at_rest = true;
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
        const AxisSample now = jog_[i].current();
        shape_reference(i, now, jog_[i].advance(kTickPeriodS));
        at_rest = at_rest && jog_[i].at_rest();
      }
      if (at_rest && shapers_settled()) {
        state_ = MotionState::holding;
        for (std::size_t i = 0; i < hal::kAxisCount; ++i) hold_[i] = {jog_[i].current().position_mm, 0.0};
      }
      return;
    }
  }
}

void TickTask::update_reference() noexcept {
  record_.motion_tick = -1;
  switch (state_) {
    case MotionState::dwell:
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) shape_reference(i, hold_[i], hold_[i]);
      if (++phase_tick_ >= dwell_ticks_) {
        state_ = MotionState::moving;
        phase_tick_ = 0;
      }
      return;
    case MotionState::moving:
      moving_reference();
      return;
    case MotionState::holding:
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) shape_reference(i, hold_[i], hold_[i]);
      return;
    case MotionState::disabled:
    case MotionState::faulted:
      // Servo off: the reference follows the table so the next servo-on is
      // bumpless, and the shapers rest there (a pending change applies now).
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
        hold_[i] = {record_.axis[i].position_mm, 0.0};
        shaping_[i].shaper.reset(hold_[i]);
        record_.axis[i].unshaped_reference_mm = hold_[i].position_mm;
        set_reference(i, hold_[i], hold_[i]);
      }
      return;
  }
}

void TickTask::tick() noexcept {
  ++counters_.ticks;
  record_.tick = counters_.ticks;

  // 1. one batched read of the latched snapshot
  const bool bus_ok = board_.read_inputs() == hal::HalStatus::ok;
  if (!bus_ok) ++counters_.bus_errors;
  std::uint32_t ticks_missed = 0;
  bool advanced = true;
  read_timebase(bus_ok, ticks_missed, advanced);
  record_.sequence = board_.latched_tick().sequence;
  if (bus_ok) last_inputs_ = board_.inputs();
  record_.force_code = board_.latched_force_code();

  // 2. measured state
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    record_.axis[i].position_mm = config_.axis[i].home_position_mm +
                                  static_cast<double>(axis_[i].encoder.counts()) * config_.axis[i].count_mm;
    record_.axis[i].speed_mm_s = axis_[i].speed_mm_s;
  }

  // 3. reference x_ref,k and x_ref,k+1
  update_reference();

  // 4. axis controllers -> speed commands
  const bool on = servo_on();
  SupervisorInput check_in;
  check_in.tick = counters_.ticks;
  check_in.bus_ok = bus_ok;
  check_in.snapshot_advanced = advanced;
  check_in.ticks_missed = ticks_missed;
  check_in.inputs = last_inputs_;
  check_in.servo_on = on;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    AxisTickRecord& r = record_.axis[i];
    double u_mm_s = 0.0;
    AxisController& ctl = axis_[i].active();
    if (on) {
      const AxisState x{r.position_mm, r.speed_mm_s};
      const AxisReference ref{r.reference_mm, r.reference_speed_mm_s, next_[i].position_mm,
                              next_[i].speed_mm_s};
      u_mm_s = ctl.update(x, ref);
    }
    const ControllerSignals sig = ctl.signals();
    r.command_mm_s = u_mm_s;
    r.s = on ? sig.s : 0.0;
    r.d_hat_mm_s = on ? sig.d_hat_mm_s : 0.0;
    check_in.axis[i] = {r.position_mm, r.speed_mm_s, r.reference_mm, r.reference_speed_mm_s, u_mm_s};
  }

  // 5. supervisor: a fault makes this very tick's outputs safe
  const FaultRecord f = check(config_.supervisor, check_in);
  if (f.active()) latch_fault(f);
  const bool outputs_live = servo_on();

  // 6. DAC codes and enables, one batched write, watchdog kick
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    AxisTickRecord& r = record_.axis[i];
    const DacScale& dac = config_.axis[i].dac;
    r.dac_code = outputs_live ? speed_to_dac_code(r.command_mm_s, dac) : dac.mid_code();
    r.enabled = outputs_live;
    board_.set_code(hal::axis_from_index(i), r.dac_code);
    board_.set_servo_enable(hal::axis_from_index(i), outputs_live);
  }
  board_.kick();
  if (board_.write_outputs() != hal::HalStatus::ok) {
    ++counters_.bus_errors;
    latch_fault({FaultReason::bus_error, -1, counters_.ticks, 0.0, 0.0});
  }
  record_.state = state_;
}

CommandStatus TickTask::start_circle(const CircleSpec& spec) noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (state_ == MotionState::dwell || state_ == MotionState::moving) return CommandStatus::busy;
  if (validate(spec)[0] != '\0') return CommandStatus::invalid;
  const CircleTrajectory circle(spec);
  const PlaneSample start = circle.start();
  // The table must already stand at the start point (within the following-error floor).
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const double error_mm = start.axis[i].position_mm - record_.axis[i].position_mm;
    if (!(std::fabs(error_mm) < config_.supervisor.axis[i].following.floor_mm)) return CommandStatus::invalid;
  }
  circle_ = circle;
  source_ = Source::circle;
  dwell_ticks_ = ticks_for(spec.dwell_s);
  motion_ticks_ = static_cast<std::int64_t>(std::ceil(circle.duration_s() / kTickPeriodS - 1e-9));
  phase_tick_ = 0;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) hold_[i] = {start.axis[i].position_mm, 0.0};
  reset_controllers();
  state_ = dwell_ticks_ > 0 ? MotionState::dwell : MotionState::moving;
  return CommandStatus::ok;
}

void TickTask::reset_controllers() noexcept {
  for (AxisLoop& loop : axis_) {
    loop.pid.reset();
    loop.dvsc.reset();
    loop.rdvsc.reset();
  }
}

CommandStatus TickTask::start_move(const MoveSpec& spec) noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (state_ == MotionState::dwell || state_ == MotionState::moving) return CommandStatus::busy;
  if (validate(spec)[0] != '\0') return CommandStatus::invalid;
  const std::size_t a = hal::index(spec.axis);
  const bool was_on = state_ == MotionState::holding;
  // From a servo-off start the table's position is the start (bumpless).
  std::array<AxisSample, hal::kAxisCount> start = hold_;
  if (!was_on)
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) start[i] = {record_.axis[i].position_mm, 0.0};
  const PointToPointMove move(spec, start[a].position_mm);
  const AxisLimits& lim = config_.supervisor.axis[a];
  if (!(move.end_mm() >= lim.position_min_mm && move.end_mm() <= lim.position_max_mm)) return CommandStatus::invalid;
  move_ = move;
  move_axis_ = a;
  source_ = Source::move;
  dwell_ticks_ = ticks_for(spec.dwell_s);
  motion_ticks_ = static_cast<std::int64_t>(std::ceil(move.duration_s() / kTickPeriodS - 1e-9));
  phase_tick_ = 0;
  hold_ = start;
  if (!was_on) reset_controllers();
  state_ = dwell_ticks_ > 0 ? MotionState::dwell : MotionState::moving;
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
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount) return CommandStatus::invalid;
  if (!jogging && speed_mm_s == 0.0) return CommandStatus::ok;  // standing still already
  if (!jogging) {
    // Validate before starting anything: nothing is half-applied.
    JogStream probe(config_.axis[a].jog);
    if (!probe.command(speed_mm_s)) return CommandStatus::invalid;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      jog_[i] = JogStream(config_.axis[i].jog);
      jog_[i].start(hold_[i].position_mm);
    }
    source_ = Source::jog;
    phase_tick_ = 0;
    motion_ticks_ = 0;
    state_ = MotionState::moving;
  }
  return jog_[a].command(speed_mm_s) ? CommandStatus::ok : CommandStatus::invalid;
}

CommandStatus TickTask::configure_shaper(hal::Axis axis, const ShaperSpec& spec) noexcept {
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount || !validate(spec).ok) return CommandStatus::invalid;
  AxisShaping& s = shaping_[a];
  const ShaperDesign design = design_shaper(spec, kTickPeriodS);
  if (!s.shaper.request_taps(design.taps)) return CommandStatus::invalid;
  s.design = design;
  s.configured = true;
  return CommandStatus::ok;
}

CommandStatus TickTask::enable_shaper(hal::Axis axis, bool on) noexcept {
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount) return CommandStatus::invalid;
  if (on && !shaping_[a].configured) return CommandStatus::invalid;
  shaping_[a].shaper.request_enabled(on);
  return CommandStatus::ok;
}

double TickTask::shaper_delay_s(hal::Axis axis) const noexcept {
  return shaping_[hal::index(axis)].shaper.delay_samples() * kTickPeriodS;
}

std::uint32_t TickTask::jog_deadman_stops() const noexcept {
  std::uint32_t n = 0;
  for (const JogStream& j : jog_) n += j.deadman_stops();
  return n;
}

CommandStatus TickTask::select_controller(hal::Axis axis, ControllerKind kind) noexcept {
  if (state_ == MotionState::dwell || state_ == MotionState::moving || state_ == MotionState::holding)
    return CommandStatus::busy;
  if (kind != ControllerKind::pid && kind != ControllerKind::dvsc && kind != ControllerKind::rdvsc)
    return CommandStatus::invalid;
  axis_[hal::index(axis)].kind = kind;
  return CommandStatus::ok;
}

CommandStatus TickTask::disable() noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::ok;  // already safe
  state_ = MotionState::disabled;
  return CommandStatus::ok;
}

CommandStatus TickTask::clear_fault() noexcept {
  if (state_ != MotionState::faulted) return CommandStatus::ok;
  const hal::DiscreteInputs& in = last_inputs_;
  bool cause = in.estop || in.watchdog_tripped;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    cause = cause || in.servo_alarm[i] || in.limit_positive[i] || in.limit_negative[i];
  if (cause) return CommandStatus::cause_present;
  fault_ = {};
  state_ = MotionState::disabled;
  return CommandStatus::ok;
}

}  // namespace tnv::fw
