#include "firmware/tick/tick_task.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "firmware/io/accel_code.hpp"
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
      kind(config.controller) {
  observer.configure(config.model, config.observer);
}

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
    origin_mm_[i] = config_.axis[i].home_position_mm;
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
  one_nominal_period_ = false;
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
  // A step of 2^31 or more is the sequence going backwards (a replayed older
  // snapshot), not 4 billion lost ticks: stale, and no counter is touched.
  if (sequence_step == 0 || sequence_step >= 0x8000'0000u || period_clocks == 0) {
    advanced = false;  // the board did not tick: never reuse stale data silently
    return;
  }
  ticks_missed = sequence_step - 1;
  counters_.missed_ticks += ticks_missed;
  const std::uint32_t expected = kNominalPeriodClocks * sequence_step;
  const std::uint32_t deviation = period_clocks > expected ? period_clocks - expected : expected - period_clocks;
  if (deviation > kLateToleranceClocks) ++counters_.late_ticks;
  one_nominal_period_ = sequence_step == 1 && deviation <= kLateToleranceClocks;
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

PlaneSample TickTask::circle_at(double t_s) const noexcept {
  PlaneSample p = circle_.at(t_s);
  if (centred_)
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) p.axis[i].position_mm += centre_mm_[i];
  return p;
}

AxisSample TickTask::source_sample(std::size_t i, double t_s) const noexcept {
  if (source_ == Source::circle) return circle_at(t_s).axis[i];
  return i == move_axis_ ? move_.at(t_s) : hold_[i];
}

// Controlled stop of a circle or move (stop()): the trajectory evaluated at
// a warped time tau whose rate falls from 1 to 0; the reference speed is
// the path speed times that rate, so position and speed stay consistent.
void TickTask::stopping_reference() noexcept {
  record_.motion_tick = phase_tick_;
  ++phase_tick_;
  const auto rate = [this](std::int64_t k) noexcept {
    return k >= stop_.n ? 0.0
                        : 0.5 * (1.0 + std::cos(std::numbers::pi * static_cast<double>(k) / static_cast<double>(stop_.n)));
  };
  const double r_now = rate(stop_.k);
  const double r_next = rate(stop_.k + 1);
  const double tau_next_s = stop_.tau_s + 0.5 * (r_now + r_next) * kTickPeriodS;
  std::array<AxisSample, hal::kAxisCount> next{};
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    AxisSample now = source_sample(i, stop_.tau_s);
    now.speed_mm_s *= r_now;
    next[i] = source_sample(i, tau_next_s);
    next[i].speed_mm_s *= r_next;
    shape_reference(i, now, next[i]);
  }
  stop_.tau_s = tau_next_s;
  ++stop_.k;
  if (stop_.k >= stop_.n && shapers_settled()) {
    state_ = MotionState::holding;
    stop_.active = false;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) hold_[i] = {next[i].position_mm, 0.0};
  }
}

void TickTask::moving_reference() noexcept {
  if (stop_.active && source_ != Source::jog) {
    stopping_reference();
    return;
  }
  const double t_s = static_cast<double>(phase_tick_) * kTickPeriodS;
  record_.motion_tick = phase_tick_;
  ++phase_tick_;
  switch (source_) {
    case Source::circle: {
      const PlaneSample now = circle_at(t_s);
      const PlaneSample next = circle_at(t_s + kTickPeriodS);
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
        stop_.active = false;
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
  board_answering_ = bus_ok;
  std::uint32_t ticks_missed = 0;
  bool advanced = true;
  read_timebase(bus_ok, ticks_missed, advanced);
  record_.sequence = board_.latched_tick().sequence;
  if (bus_ok) last_inputs_ = board_.inputs();
  record_.force_code = board_.latched_force_code();

  // 2. measured state; record_ still holds the previous tick's outputs,
  // which acted over the interval this snapshot ends (stall monitor)
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    record_.axis[i].position_mm = origin_mm_[i] + static_cast<double>(axis_[i].encoder.counts()) * config_.axis[i].count_mm;
    record_.axis[i].speed_mm_s = axis_[i].speed_mm_s;
    if (config_.axis[i].observer.enabled) {
      // Speed observer (speed_observer.hpp): predicted with the command the
      // DAC applied over the last tick, corrected with this count. Restarted
      // from the measurement while the outputs were off or a tick was lost.
      const AxisTickRecord& r = record_.axis[i];  // this tick's measurement, last tick's outputs
      if (r.enabled && advanced && ticks_missed == 0)
        axis_[i].observer.update(r.position_mm, dac_code_to_speed_mm_s(r.dac_code, config_.axis[i].dac));
      else
        axis_[i].observer.reset(r.position_mm, r.speed_mm_s);
    }
    record_.axis[i].accel_mm_s2 = accel_code_to_mm_s2(board_.latched_accel_code(hal::axis_from_index(i)));
    stall_[i].update(axis_[i].encoder.counts(), record_.axis[i].command_mm_s, record_.axis[i].enabled,
                     config_.supervisor.axis[i].stall);
    // What the DAC applied over the interval this snapshot ends (its code, not the unquantised command).
    const AxisTickRecord& applied = record_.axis[i];
    const double applied_mm_s = applied.enabled ? dac_code_to_speed_mm_s(applied.dac_code, config_.axis[i].dac) : 0.0;
    plausibility_[i] = plausibility_monitor_[i].update(
        axis_[i].encoder.counts(), applied_mm_s, advanced && one_nominal_period_, config_.axis[i].model,
        config_.axis[i].count_mm, config_.axis[i].dac.full_scale_mm_s, config_.supervisor.axis[i].plausibility);
  }

  // 3. reference x_ref,k and x_ref,k+1
  update_reference();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    if (!excite_[i].active()) continue;
    if (state_ != MotionState::holding) {
      excite_[i] = ExcitationGenerator{};  // a motion, disable or fault cancels it
      continue;
    }
    // Open loop: the reference follows the table, so the following error stays 0.
    hold_[i] = {record_.axis[i].position_mm, 0.0};
    set_reference(i, hold_[i], hold_[i]);
  }

  // 4. axis controllers -> speed commands
  const bool on = servo_on();
  SupervisorInput check_in;
  check_in.tick = counters_.ticks;
  check_in.bus_ok = bus_ok;
  check_in.snapshot_advanced = advanced;
  check_in.ticks_missed = ticks_missed;
  check_in.period_clocks = advanced ? record_.period_clocks : 0;
  check_in.inputs = last_inputs_;
  check_in.servo_on = on;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    AxisTickRecord& r = record_.axis[i];
    double u_mm_s = 0.0;
    AxisController& ctl = axis_[i].active();
    if (on && excite_[i].active()) {
      u_mm_s = excite_[i].next(axis_[i].encoder.counts() - excite_start_counts_[i]);
      if (!excite_[i].active()) {
        // Holding resumes from where the axis came to rest, bumpless.
        ctl.reset();
        shaping_[i].shaper.reset(hold_[i]);
      }
    } else if (on) {
      AxisState x{r.position_mm, r.speed_mm_s};
      if (const SpeedObserverParams& obs = config_.axis[i].observer; obs.enabled) {
        x.speed_mm_s = axis_[i].observer.speed_mm_s();
        if (obs.use_position) x.position_mm = axis_[i].observer.position_mm();
      }
      const AxisReference ref{r.reference_mm, r.reference_speed_mm_s, next_[i].position_mm,
                              next_[i].speed_mm_s};
      u_mm_s = ctl.update(x, ref);
      u_mm_s += friction_feedforward_mm_s(config_.axis[i].friction, r.reference_speed_mm_s, next_[i].speed_mm_s);
    }
    const ControllerSignals sig = ctl.signals();
    r.command_mm_s = u_mm_s;
    r.s = on ? sig.s : 0.0;
    r.d_hat_mm_s = on ? sig.d_hat_mm_s : 0.0;
    check_in.axis[i] = {r.position_mm,      r.speed_mm_s, r.reference_mm, r.reference_speed_mm_s,
                        u_mm_s,             stall_[i].stalled_ticks(), stall_[i].applied_command_mm_s(),
                        plausibility_[i]};
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
  if (const hal::HalStatus written = board_.write_outputs(); written != hal::HalStatus::ok) {
    ++counters_.bus_errors;
    const FaultReason reason =
        written == hal::HalStatus::output_failed ? FaultReason::output_write_failed : FaultReason::bus_error;
    latch_fault({reason, -1, counters_.ticks, 0.0, 0.0});
  }
  record_.state = state_;
}

CommandStatus TickTask::start_circle(const CircleSpec& spec) noexcept { return start_circle(spec, 0.0, 0.0); }

CommandStatus TickTask::start_circle(const CircleSpec& spec, double centre_x_mm, double centre_y_mm) noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (state_ == MotionState::dwell || state_ == MotionState::moving) return CommandStatus::busy;
  if (validate(spec)[0] != '\0') return CommandStatus::invalid;
  if (!std::isfinite(centre_x_mm) || !std::isfinite(centre_y_mm)) return CommandStatus::invalid;
  const std::array<double, hal::kAxisCount> centre{centre_x_mm, centre_y_mm};
  // About the origin the reference is circle_.at() untouched, bit for bit.
  const bool centred = centre_x_mm != 0.0 || centre_y_mm != 0.0;
  const CircleTrajectory circle(spec);
  PlaneSample start = circle.start();
  if (centred)
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) start.axis[i].position_mm += centre[i];
  // The table must already stand at the start point (within the following-error floor).
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const double error_mm = start.axis[i].position_mm - record_.axis[i].position_mm;
    if (!(std::fabs(error_mm) < config_.supervisor.axis[i].following.floor_mm)) return CommandStatus::invalid;
  }
  circle_ = circle;
  centred_ = centred;
  centre_mm_ = centred ? centre : std::array<double, hal::kAxisCount>{};
  stop_ = {};
  stop_ramp_s_ = spec.ramp_s;
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
  stop_ = {};
  stop_ramp_s_ = spec.ramp_s;
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
  if (jogging && stop_.active) return CommandStatus::busy;  // a controlled stop wins until the jog rests
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
    stop_ = {};
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
  config_.axis[hal::index(axis)].controller = kind;  // config() tells the live selection
  return CommandStatus::ok;
}

CommandStatus TickTask::disable() noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::ok;  // already safe
  state_ = MotionState::disabled;
  return CommandStatus::ok;
}

CommandStatus TickTask::clear_fault() noexcept {
  if (state_ != MotionState::faulted) return CommandStatus::ok;
  // The board's trips are sticky: reset them here, between ticks. This
  // clear still answers cause_present; once a snapshot shows them gone,
  // the next clear succeeds (if the cause is real, they latch again).
  bool board_latched = last_inputs_.watchdog_tripped;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    board_latched = board_latched || last_inputs_.encoder_error[i] || last_inputs_.dac_error[i];
  if (board_latched) (void)board_.clear_latched_faults();
  if (fault_cause_present(last_inputs_)) return CommandStatus::cause_present;
  // The board did not answer the last tick's read: nothing says the cause is gone.
  if (!board_answering_) return CommandStatus::cause_present;
  fault_ = {};
  state_ = MotionState::disabled;
  return CommandStatus::ok;
}


// --- commands for the CAN node

namespace {

bool same(const AxisModel& a, const AxisModel& b) noexcept {
  return a.A == b.A && a.B == b.B && a.period_s == b.period_s;
}
bool same(const SlidingModeParams& a, const SlidingModeParams& b) noexcept {
  return a.G_position_1_s == b.G_position_1_s && a.G_speed == b.G_speed && a.eta_mm_s == b.eta_mm_s &&
         a.phi_mm_s == b.phi_mm_s && a.q == b.q && a.g == b.g && a.gamma == b.gamma && a.u_max_mm_s == b.u_max_mm_s;
}
bool same(const PidParams& a, const PidParams& b) noexcept {
  return a.kp == b.kp && a.ki == b.ki && a.kd == b.kd && a.derivative_filter_tf_s == b.derivative_filter_tf_s &&
         a.u_max_mm_s == b.u_max_mm_s && a.feedforward == b.feedforward;
}
bool same(const JogLimits& a, const JogLimits& b) noexcept {
  return a.speed_max_mm_s == b.speed_max_mm_s && a.accel_mm_s2 == b.accel_mm_s2 && a.deadman_s == b.deadman_s;
}
bool same(const AxisLimits& a, const AxisLimits& b) noexcept {
  return a.position_min_mm == b.position_min_mm && a.position_max_mm == b.position_max_mm &&
         a.speed_max_mm_s == b.speed_max_mm_s && a.following.floor_mm == b.following.floor_mm &&
         a.following.lag_s == b.following.lag_s && a.stall.command_mm_s == b.stall.command_mm_s &&
         a.stall.ticks == b.stall.ticks &&
         a.plausibility.jump_disturbance_scale == b.plausibility.jump_disturbance_scale &&
         a.plausibility.runaway_margin_mm_s == b.plausibility.runaway_margin_mm_s &&
         a.plausibility.runaway_min_command_mm_s == b.plausibility.runaway_min_command_mm_s;
}

}  // namespace

bool TickTask::live_tunable_only(const FirmwareConfig& from, const FirmwareConfig& to) noexcept {
  if (from.supervisor.max_consecutive_missed_ticks != to.supervisor.max_consecutive_missed_ticks) return false;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const AxisConfig& a = from.axis[i];
    const AxisConfig& b = to.axis[i];
    if (!same(from.supervisor.axis[i], to.supervisor.axis[i])) return false;
    if (a.count_mm != b.count_mm || a.dac.bits != b.dac.bits || a.dac.full_scale_mm_s != b.dac.full_scale_mm_s ||
        a.controller != b.controller || !same(a.model, b.model) || !same(a.jog, b.jog) ||
        !same(a.friction, b.friction) || !same(a.observer, b.observer))
      return false;
    // PID: kp, ki, kd and the clamp are live; the filter and the feed-forward switch are not.
    if (a.pid.derivative_filter_tf_s != b.pid.derivative_filter_tf_s || a.pid.feedforward != b.pid.feedforward)
      return false;
    // sliding.*: all live.
  }
  return true;
}

CommandStatus TickTask::apply_config(const FirmwareConfig& config) noexcept {
  if (!validate(config).ok()) return CommandStatus::invalid;
  if (moving() && !live_tunable_only(config_, config)) return CommandStatus::busy;
  // Everything checked: from here on nothing can refuse, so it applies whole.
  FirmwareConfig next = config;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    AxisConfig& a = next.axis[i];
    const AxisConfig& old = config_.axis[i];
    AxisLoop& loop = axis_[i];
    a.home_position_mm = old.home_position_mm;  // the frame moves with zero() only
    if (!same(a.model, old.model)) {
      loop.pid = PidController(a.model, a.pid);
      loop.dvsc = RdvscController(ControllerKind::dvsc, a.model, a.sliding);
      loop.rdvsc = RdvscController(ControllerKind::rdvsc, a.model, a.sliding);
    } else {
      // Bumpless: each controller keeps its state and re-forms it for the new gains.
      if (!same(a.pid, old.pid)) loop.pid.set_params(a.pid);
      if (!same(a.sliding, old.sliding)) {
        loop.dvsc.set_params(a.sliding);
        loop.rdvsc.set_params(a.sliding);
      }
    }
    if (!same(a.model, old.model) || !same(a.observer, old.observer)) {
      loop.observer.configure(a.model, a.observer);
      loop.observer.reset(record_.axis[i].position_mm, loop.speed_mm_s);
    }
    // The residual's history was formed with the old model and scale.
    if (!same(a.model, old.model) || a.count_mm != old.count_mm || a.dac.full_scale_mm_s != old.dac.full_scale_mm_s)
      plausibility_monitor_[i].reset();
    if (a.count_mm != old.count_mm) {
      // Re-base: the position reading stays where it is, later counts use the new scale.
      const double counts = static_cast<double>(loop.encoder.counts());
      origin_mm_[i] = origin_mm_[i] + counts * old.count_mm - counts * a.count_mm;
    }
    if (a.controller != loop.kind) {
      loop.kind = a.controller;
      if (servo_on()) loop.active().reset();
    }
  }
  config_ = next;
  return CommandStatus::ok;
}

CommandStatus TickTask::stop() noexcept {
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (state_ == MotionState::dwell) {
    state_ = MotionState::holding;  // the reference never left hold_
    return CommandStatus::ok;
  }
  if (state_ != MotionState::moving || stop_.active) return CommandStatus::ok;
  if (source_ == Source::jog) {
    for (JogStream& j : jog_) j.command(0.0);
  } else {
    stop_.tau_s = static_cast<double>(phase_tick_) * kTickPeriodS;
    stop_.k = 0;
    stop_.n = std::max<std::int64_t>(1, ticks_for(stop_ramp_s_));
  }
  stop_.active = true;
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
  const double delta_mm = position_mm - record_.axis[a].position_mm;
  origin_mm_[a] += delta_mm;
  hold_[a].position_mm += delta_mm;
  next_[a].position_mm += delta_mm;
  AxisTickRecord& r = record_.axis[a];
  r.position_mm += delta_mm;
  r.reference_mm += delta_mm;
  r.unshaped_reference_mm += delta_mm;
  axis_[a].observer.shift(delta_mm);
  shaping_[a].shaper.reset(hold_[a]);  // at rest: its history is the old frame's rest point
  return CommandStatus::ok;
}

CommandStatus TickTask::start_excitation(hal::Axis axis, const ExcitationSpec& spec) noexcept {
  const std::size_t a = hal::index(axis);
  if (a >= hal::kAxisCount || !validate(spec).ok) return CommandStatus::invalid;
  if (state_ == MotionState::faulted) return CommandStatus::faulted;
  if (state_ != MotionState::holding || exciting()) return CommandStatus::busy;
  excite_start_counts_[a] = axis_[a].encoder.counts();
  excite_[a].start(spec);
  return CommandStatus::ok;
}

bool TickTask::exciting() const noexcept {
  for (const ExcitationGenerator& e : excite_)
    if (e.active()) return true;
  return false;
}

CommandStatus TickTask::estop() noexcept {
  latch_fault({FaultReason::remote_estop, -1, counters_.ticks, 0.0, 0.0});
  return CommandStatus::ok;
}

double TickTask::standing_mm(hal::Axis axis) const noexcept {
  const std::size_t a = hal::index(axis);
  return state_ == MotionState::holding ? hold_[a].position_mm : record_.axis[a].position_mm;
}

}  // namespace tnv::fw
