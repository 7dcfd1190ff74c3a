#include "tools/hil/spindle_safety_run.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/machine.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tools/hil/hil_firmware_config.hpp"

namespace tnv::hil {

namespace {

constexpr double kFirstRpm = 3000.0;   // the start before the transition
constexpr double kSecondRpm = 2400.0;  // the new start after it
// A feed move begins when the table's real XY speed passes kMovingMmS (a
// sixth of the programs' 3 mm/s) after it was at rest (below kRestMmS): a
// holding axis dithers at up to ~0.2 mm/s, which is no feed move.
constexpr double kMovingMmS = 0.5;
constexpr double kRestMmS = 0.05;
constexpr double kRestRpm = 1.0;
constexpr int kWatchTicks = 3000;      // watched after the transition's recovery
constexpr int kLimitTicks = 30'000;    // any wait longer than this is a failure

// The judge: the emulator's truth against what the bench asked for.
class Judge {
 public:
  void ask_on(double rpm) noexcept {
    asked_on_ = true;
    asked_rpm_ = rpm;
  }
  void ask_off(const emu::Machine& m) noexcept {
    asked_on_ = false;
    low_rpm_ = std::fabs(m.spindle_truth().speed_rpm);
    rise_rpm_ = 0.0;
  }
  void observe(const emu::Machine& m) noexcept {
    const double n = m.spindle_truth().speed_rpm;
    const double v = std::hypot(m.truth(hal::Axis::x).speed_mm_s, m.truth(hal::Axis::y).speed_mm_s);
    if (v > kMovingMmS && !was_moving_) {
      ++onsets_;
      if (asked_on_ && !at_speed(n)) ++early_;
      was_moving_ = true;
    } else if (v < kRestMmS) {
      was_moving_ = false;
    }
    if (!asked_on_) {
      low_rpm_ = std::min(low_rpm_, std::fabs(n));
      rise_rpm_ = std::max(rise_rpm_, std::fabs(n) - low_rpm_);
    }
  }
  // The firmware's default window (spindle.at_speed_fraction 5 %, floor 20 rpm) around what was asked.
  bool at_speed(double n) const noexcept {
    return std::fabs(n - asked_rpm_) <= std::max(0.05 * std::fabs(asked_rpm_), 20.0);
  }
  double rise_rpm() const noexcept { return rise_rpm_; }
  std::uint32_t onsets() const noexcept { return onsets_; }
  std::uint32_t early() const noexcept { return early_; }

 private:
  bool asked_on_ = false;
  double asked_rpm_ = 0.0;
  double low_rpm_ = 0.0;
  double rise_rpm_ = 0.0;
  bool was_moving_ = false;
  std::uint32_t onsets_ = 0;
  std::uint32_t early_ = 0;
};

// The machine, the board and the firmware; restart() is a node restart:
// a new firmware (nothing kept) and the board initialised again, the
// machine (and its coasting spindle) untouched.
struct Bench {
  Bench(const emu::Scenario& s, const fw::SpindleParams& spindle_params)
      : scenario(s), spindle(spindle_params), machine(s), bus(machine), board(bus) {
    ok = restart();
  }
  bool restart() {
    task.reset();
    if (!board.init({}).ok()) return false;
    fw::FirmwareConfig config = firmware_config_for(scenario, fw::default_firmware_config());
    config.spindle = spindle;
    task = std::make_unique<fw::TickTask>(board, config);
    for (int i = 0; i < 3; ++i) tick();
    return task->hold_position() == fw::CommandStatus::ok;
  }
  void tick() {
    machine.advance_to_next_tick();
    task->tick();
    judge.observe(machine);
  }
  void run(int ticks) {
    for (int i = 0; i < ticks; ++i) tick();
  }
  // Ticks until done() (true) or kLimitTicks (false).
  template <class Done>
  bool run_until(Done done) {
    for (int i = 0; i < kLimitTicks; ++i) {
      if (done()) return true;
      tick();
    }
    return done();
  }
  double rpm() const noexcept { return machine.spindle_truth().speed_rpm; }

  // A 3 mm square of feed moves at 3 mm/s from where the table is held (4 s).
  bool push_square() {
    static constexpr double kSide[4][2] = {{3.0, 0.0}, {0.0, 3.0}, {-3.0, 0.0}, {0.0, -3.0}};
    for (const auto& d : kSide) {
      fw::motion::PlanePoint end = task->next_segment_start_mm();
      end[0] += d[0];
      end[1] += d[1];
      fw::motion::SegmentRefusal why{};
      if (task->push_segment(fw::motion::line_to(end, 3.0), why) != fw::CommandStatus::ok) return false;
    }
    return task->end_program() == fw::CommandStatus::ok;
  }
  bool start(double start_rpm) {
    judge.ask_on(start_rpm);
    return task->spindle_start(fw::SpindleDirection::forward, start_rpm) == fw::SpindleResult::ok;
  }
  bool program_done() const { return !task->program_running() && task->state() == fw::MotionState::holding; }

  emu::Scenario scenario;
  fw::SpindleParams spindle;
  emu::Machine machine;
  drivers::EmulatedRegisterBus bus;
  drivers::FpgaIoBoard board;
  Judge judge{};
  std::unique_ptr<fw::TickTask> task;  // after the board it drives: destroyed before it
  bool ok = false;
};

std::string cause_name(const fw::TickTask& task) {
  return fw::to_string(task.spindle().last_stop_cause());
}

// The transition itself and its recovery. false when the bench could not
// drive it (a refused command), which fails the transition.
bool drive_transition(Bench& b, const std::string& name, SpindleTransitionResult& r) {
  fw::TickTask& t = *b.task;
  if (name == "feed_hold") {
    if (t.feed_hold(true) != fw::CommandStatus::ok) return false;
    b.run(500);
    b.judge.ask_off(b.machine);
    t.spindle_stop();  // the operator stops the spindle in the hold
    r.stop_cause = cause_name(t);
    if (!b.run_until([&] { return std::fabs(b.rpm()) < kRestRpm; })) return false;
    return b.task->feed_hold(false) == fw::CommandStatus::ok;  // resume: the spindle must stay off
  }
  if (name == "abort") {
    b.judge.ask_off(b.machine);
    if (t.stop() != fw::CommandStatus::ok) return false;
    r.stop_cause = cause_name(t);
    return true;
  }
  if (name == "fault_clear" || name == "estop_release") {
    const bool estop = name == "estop_release";
    b.judge.ask_off(b.machine);
    if (estop) b.machine.set_estop(true);
    else b.machine.set_servo_alarm(hal::Axis::y, true);
    b.tick();
    r.stop_cause = cause_name(t);
    b.run(500);
    if (estop) b.machine.set_estop(false);
    else b.machine.set_servo_alarm(hal::Axis::y, false);
    b.run(2);
    return t.clear_fault() == fw::CommandStatus::ok && t.hold_position() == fw::CommandStatus::ok;
  }
  if (name == "host_timeout") {
    b.judge.ask_off(b.machine);
    t.set_host_lost(true);
    (void)t.stop();  // what the CAN node does at its host timeout: motion comes to a controlled stop
    r.stop_cause = cause_name(t);
    b.run(500);
    t.set_host_lost(false);  // a host takes ownership again
    return true;
  }
  if (name == "node_restart") {
    b.judge.ask_off(b.machine);
    r.stop_cause = "restart";
    return b.restart();
  }
  if (name == "parameter_load") {
    // While it turns a load is refused and changes nothing; stopped and still, it applies.
    fw::FirmwareConfig next = t.config();
    const double accel = t.spindle().params().accel_rpm_s == 4000.0 ? 3000.0 : 4000.0;
    next.spindle.accel_rpm_s = accel;
    const fw::SpindleParams before = t.spindle().params();
    r.refused_while_turning = t.apply_config(next) != fw::CommandStatus::ok && t.spindle().params() == before &&
                              t.spindle().commanded_on();
    b.judge.ask_off(b.machine);
    t.spindle_stop();
    r.stop_cause = cause_name(t);
    if (!b.run_until([&] { return !t.spindle().active() && std::fabs(b.rpm()) < kRestRpm; })) return false;
    return t.apply_config(next) == fw::CommandStatus::ok && t.spindle().params().accel_rpm_s == accel;
  }
  return false;
}

SpindleTransitionResult run_transition(const emu::Scenario& scenario, const fw::SpindleParams& spindle,
                                       const std::string& name) {
  SpindleTransitionResult r;
  r.name = name;
  r.refused_while_turning = name != "parameter_load";  // only the load has the check
  Bench b(scenario, spindle);
  if (!b.ok) return r;
  // Before: a start, and a program of feed moves running with it (the
  // parameter load: turning at rest, the load's own condition).
  if (!b.start(kFirstRpm)) return r;
  if (name == "parameter_load") {
    if (!b.run_until([&] { return b.judge.at_speed(b.rpm()); })) return r;
    b.run(200);
  } else {
    if (!b.push_square()) return r;
    if (!b.run_until([&] { return b.judge.onsets() > 0; })) return r;
    b.run(1500);  // well into the program
  }
  if (!drive_transition(b, name, r)) return r;
  b.run(kWatchTicks);
  r.stopped = std::fabs(b.rpm()) < kRestRpm;
  r.rise_rpm = b.judge.rise_rpm();
  r.self_start = r.rise_rpm > kSelfStartRpm;
  // After: whatever still runs ends, then a new start and a second program.
  if (!b.run_until([&] { return b.program_done(); })) return r;
  if (!b.start(kSecondRpm)) return r;
  if (!b.push_square()) return r;
  bool reached = false;
  if (!b.run_until([&] {
        reached = reached || b.judge.at_speed(b.rpm());
        return reached && b.program_done();
      }))
    return r;
  r.restarted = reached;
  b.judge.ask_off(b.machine);
  b.run(kWatchTicks);
  r.program_end_stop = b.task->spindle().last_stop_cause() == fw::SpindleStopCause::program_end &&
                       std::fabs(b.rpm()) < kRestRpm && b.judge.rise_rpm() <= kSelfStartRpm;
  r.feed_onsets = b.judge.onsets();
  r.feed_before_at_speed = b.judge.early();
  return r;
}

}  // namespace

const std::vector<std::string>& spindle_transition_names() {
  static const std::vector<std::string> names{"feed_hold",    "abort",        "fault_clear",   "estop_release",
                                              "host_timeout", "node_restart", "parameter_load"};
  return names;
}

SpindleSafetySummary run_spindle_safety(const emu::Scenario& scenario, const fw::SpindleParams& firmware_spindle) {
  SpindleSafetySummary s;
  s.all_ok = true;
  for (const std::string& name : spindle_transition_names()) {
    SpindleTransitionResult r = run_transition(scenario, firmware_spindle, name);
    s.self_starts += r.self_start ? 1u : 0u;
    s.feed_before_at_speed += r.feed_before_at_speed;
    s.feed_onsets += r.feed_onsets;
    s.all_ok = s.all_ok && r.ok();
    s.transitions.push_back(std::move(r));
  }
  return s;
}

}  // namespace tnv::hil
