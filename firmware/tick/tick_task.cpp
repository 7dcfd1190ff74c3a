#include "firmware/tick/tick_task.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include "firmware/io/accel_code.hpp"
#include "firmware/io/dac_code.hpp"
#include "firmware/supervisor/supervisor.hpp"
#include "firmware/timing/m_method_speed.hpp"

namespace tnv::fw {

namespace {
constexpr std::uint32_t kNominalPeriodClocks = 10'000;
constexpr std::uint32_t kLateToleranceClocks = 500;  // 5% of a period
}  // namespace

std::array<TickTask::AxisLoop, hal::kAxisCount> TickTask::make_axis_loops(const FirmwareConfig& config) noexcept {
  return [&config]<std::size_t... I>(std::index_sequence<I...>) {
    return std::array<AxisLoop, hal::kAxisCount>{AxisLoop(config.axis[I])...};
  }(std::make_index_sequence<hal::kAxisCount>{});
}

std::int64_t TickTask::ticks_for(double seconds) noexcept {
  return static_cast<std::int64_t>(std::llround(seconds / kTickPeriodS));
}

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
    : board_(board), config_(config), axis_(make_axis_loops(config)) {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    axis_[i].encoder = EncoderPosition(board_.counter_bits());
    spindle_encoder_ = EncoderPosition(board_.counter_bits());
    hold_[i] = {config_.axis[i].home_position_mm, 0.0};
    next_[i] = hold_[i];
    origin_mm_[i] = config_.axis[i].home_position_mm;
  }
  (void)motion_.configure(path_limits(config_), held_point());  // validate(config) checked the limits
  feed_.configure(config_.arsc);                                  // and the force loop's parameters
  (void)spindle_.set_params(config_.spindle);                     // and the spindle's (at rest)
}

bool TickTask::servo_on() const noexcept {
  return state_ == MotionState::dwell || state_ == MotionState::moving || state_ == MotionState::holding;
}

void TickTask::latch_fault(const FaultRecord& f) noexcept {
  if (state_ == MotionState::faulted) return;  // the first reason wins
  // A count that cannot be trusted loses home with it.
  if (f.reason == FaultReason::encoder_error || f.reason == FaultReason::encoder_implausible ||
      f.reason == FaultReason::encoder_stall) {
    if (f.axis >= 0 && static_cast<std::size_t>(f.axis) < hal::kAxisCount) homing_.unhome(static_cast<std::size_t>(f.axis));
    else homing_.unhome_all();
  }
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
    spindle_encoder_.reset(board_.spindle_latched_count());
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
  spindle_rpm_ = spindle_rpm(spindle_encoder_.update(board_.spindle_latched_count()), period_clocks);
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
  const PathShapers::Pair shaped = shapers_.shape(i, now, next);
  set_reference(i, shaped.now, shaped.next);
}

// Every producer's reference comes from the motion core: x_ref,k and
// x_ref,k+1 of both axes, through each axis' shaper.
void TickTask::moving_reference() noexcept {
  if (source_ == Source::homing) {
    homing_reference();
    return;
  }
  record_.motion_tick = phase_tick_;
  ++phase_tick_;
  if (source_ == Source::jog) jog_.produce(motion_);
  // Feed moves of programs, circles and moves wait for the spindle; the operator's jog does not.
  motion_.set_feed_gate(source_ == Source::jog || spindle_.feed_permitted());
  motion_.set_probe_input(last_inputs_.probe);
  const motion::MotionReference r = motion_.tick();
  if (source_ == Source::program) probe_tick(r);
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const AxisReference& a = r.axis[i];
    shape_reference(i, {a.position_mm, a.speed_mm_s}, {a.next_position_mm, a.next_speed_mm_s});
  }
  if (source_ == Source::program)
    if (const motion::Segment* change = motion_.spindle_change_due()) program_spindle_change(*change);
  const bool done = motion_.state() == motion::MotionState::idle && (source_ != Source::jog || jog_.idle());
  // The program's end (its stream closed and run dry; an aborted one stopped the spindle already).
  if (done && source_ == Source::program && spindle_.commanded_on()) spindle_.stop(SpindleStopCause::program_end);
  if (done && shapers_.settled()) {
    state_ = MotionState::holding;
    stop_requested_ = false;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) hold_[i] = {r.axis[i].next_position_mm, 0.0};
  }
}

void TickTask::update_reference() noexcept {
  record_.motion_tick = -1;
  // A new path shaper goes to every axis in the same tick, once all are quiet.
  shapers_.forward_when_quiet(state_ == MotionState::disabled || state_ == MotionState::faulted);
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
      if (homing_.running()) homing_.cancel();  // a stop from dwell never reaches here mid-cycle; defensive
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) shape_reference(i, hold_[i], hold_[i]);
      return;
    case MotionState::disabled:
    case MotionState::faulted:
      if (homing_.running()) homing_.cancel();  // disabled or faulted mid-cycle: not homed
      // Servo off: the reference follows the table so the next servo-on is
      // bumpless, and the shapers rest there (a pending change applies now).
      // The screw compensation's last offset is taken off the measured
      // (motor-side) position: compensated, the reference is where the axis is.
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
        hold_[i] = {record_.axis[i].position_mm - screw_[i].next_offset_mm(), 0.0};
        shapers_.reset(i, hold_[i]);
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

  // 3. feed override of a running program (the force loop, when on), then
  // the reference x_ref,k and x_ref,k+1
  feed_.tick(state_ == MotionState::moving && source_ == Source::program, config_.force_sensor.n_per_volt, motion_,
             record_);
  update_reference();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    // A motion, disable or fault cancels a running excitation (hold_step: none).
    const AxisExcitations::HoldStep step = excite_.hold_step(i, state_ == MotionState::holding);
    if (step.kind == AxisExcitations::HoldStep::Kind::carrier) {
      // Closed loop: the controller keeps holding hold_; on a carrier, hold_
      // moves at the carrier's speed through the drive phase and then rests
      // where it ended (the shaper, bypassed meanwhile, rests there with it).
      const double v_mm_s = step.speed_mm_s;
      const AxisSample now{hold_[i].position_mm, v_mm_s};
      const AxisSample next{hold_[i].position_mm + v_mm_s * kTickPeriodS, v_mm_s};
      record_.axis[i].unshaped_reference_mm = now.position_mm;
      set_reference(i, now, next);
      hold_[i] = {next.position_mm, 0.0};
      shapers_.reset(i, hold_[i]);
    } else if (step.kind == AxisExcitations::HoldStep::Kind::follow_table) {
      // Open loop: the reference follows the table, so the following error stays 0.
      hold_[i] = {record_.axis[i].position_mm, 0.0};
      set_reference(i, hold_[i], hold_[i]);
    }
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
    double excitation_mm_s = 0.0;
    if (on && excite_.open_loop(i)) {
      u_mm_s = excite_.next(i, axis_[i].encoder.counts());
      excitation_mm_s = u_mm_s;
      if (!excite_.running(i)) {
        // Holding resumes from where the axis came to rest, bumpless.
        ctl.reset();
        shapers_.reset(i, hold_[i]);
      }
    } else if (on) {
      AxisState x{r.position_mm, r.speed_mm_s};
      if (const SpeedObserverParams& obs = config_.axis[i].observer; obs.enabled) {
        x.speed_mm_s = axis_[i].observer.speed_mm_s();
        if (obs.use_position) x.position_mm = axis_[i].observer.position_mm();
      }
      // The program is for the table, the encoder reads the motor: the
      // controllers follow the motor-side reference (screw_compensation.hpp).
      const ScrewCompensator::Offsets screw =
          screw_[i].advance(config_.axis[i].screw, r.reference_mm, next_[i].position_mm, kTickPeriodS);
      const AxisReference ref{r.reference_mm + screw.now_mm, r.reference_speed_mm_s,
                              next_[i].position_mm + screw.next_mm, next_[i].speed_mm_s};
      u_mm_s = ctl.update(x, ref);
      u_mm_s += friction_feedforward_mm_s(config_.axis[i].friction, r.reference_speed_mm_s, next_[i].speed_mm_s);
      // Closed-loop excitation at the plant input: u = c + d (excitation.hpp).
      if (excite_.running(i)) excitation_mm_s = excite_.next(i, axis_[i].encoder.counts());
      u_mm_s += excitation_mm_s;
    }
    r.excitation_mm_s = excitation_mm_s;
    const ControllerSignals sig = ctl.signals();
    r.command_mm_s = u_mm_s;
    r.s = on ? sig.s : 0.0;
    r.d_hat_mm_s = on ? sig.d_hat_mm_s : 0.0;
    // Field by field: a braced temporary is built on the stack and copied
    // with overlapping loads that stall on its own stores (about 4 % of a
    // whole-process circle, docs/performance.md).
    AxisCheckInput& a = check_in.axis[i];
    a.position_mm = r.position_mm;
    a.speed_mm_s = r.speed_mm_s;
    a.reference_mm = r.reference_mm;
    a.reference_speed_mm_s = r.reference_speed_mm_s;
    a.command_mm_s = u_mm_s;
    a.stalled_ticks = stall_[i].stalled_ticks();
    a.stall_command_mm_s = stall_[i].applied_command_mm_s();
    a.plausibility = plausibility_[i];
    a.soft_limits = !homing_.soft_limits_off(i);
  }

  // 5. supervisor: a fault makes this very tick's outputs safe
  const FaultRecord f = check(config_.supervisor, check_in);
  if (f.active()) latch_fault(f);
  const bool outputs_live = servo_on();
  spindle_tick();

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

}  // namespace tnv::fw
