#include "firmware/tick/tick_task.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <utility>

#include "firmware/io/accel_code.hpp"
#include "firmware/supervisor/supervisor.hpp"
#include "firmware/timing/m_method_speed.hpp"

namespace tnv::fw {

namespace {
constexpr std::uint32_t kNominalPeriodClocks = 10'000;
constexpr std::uint32_t kLateToleranceClocks = 500;  // 5% of a period
}  // namespace

std::array<AxisLoop, hal::kAxisCount> TickTask::make_axis_loops(const FirmwareConfig& config,
                                                                 unsigned counter_bits) noexcept {
  return [&config, counter_bits]<std::size_t... I>(std::index_sequence<I...>) {
    return std::array<AxisLoop, hal::kAxisCount>{AxisLoop(config.axis[I], counter_bits)...};
  }(std::make_index_sequence<hal::kAxisCount>{});
}

std::int64_t TickTask::ticks_for(double seconds) noexcept {
  return static_cast<std::int64_t>(std::llround(seconds / kTickPeriodS));
}

TickTask::TickTask(hal::IoBoard& board, const FirmwareConfig& config) noexcept
    : board_(board), config_(config), axis_(make_axis_loops(config, board.counter_bits())) {
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
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
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) axis_[i].restart_count(board_.latched_count(hal::axis_from_index(i)));
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
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    axis_[i].count(board_.latched_count(hal::axis_from_index(i)), config_.axis[i].count_mm, period_clocks);
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
        hold_[i] = {record_.axis[i].position_mm - axis_[i].screw_offset_mm(), 0.0};
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
    axis_[i].measure(origin_mm_[i], config_.axis[i], config_.supervisor.axis[i], advanced, ticks_missed,
                     one_nominal_period_, record_.axis[i]);
    record_.axis[i].accel_mm_s2 = accel_code_to_mm_s2(board_.latched_accel_code(hal::axis_from_index(i)));
  }

  // 3. feed override of a running program (the force loop, when on) and
  // the spindle speed a feed per revolution runs at (this period's measured
  // one; none from a snapshot that did not advance), then the reference
  // x_ref,k and x_ref,k+1
  motion_.set_spindle_rpm(spindle_sync_.tick(advanced && spindle_.at_speed(), spindle_rpm_, kTickPeriodS));
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
    AxisCheckInput& a = check_in.axis[i];
    // An open-loop excitation that ended: holding resumes where the axis came to rest, bumpless.
    if (axis_[i].control(on, config_.axis[i], next_[i], kTickPeriodS, excite_, i, record_.axis[i], a))
      shapers_.reset(i, hold_[i]);
    a.soft_limits = !homing_.soft_limits_off(i);
  }

  // 5. supervisor: a fault makes this very tick's outputs safe
  const FaultRecord f = check(config_.supervisor, check_in);
  if (f.active()) latch_fault(f);
  const bool outputs_live = servo_on();
  spindle_tick();

  // 6. DAC codes and enables, one batched write, watchdog kick
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    board_.set_code(hal::axis_from_index(i), AxisLoop::output(outputs_live, config_.axis[i].dac, record_.axis[i]));
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
