#include "tools/hil/spindle_safety_run.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/machine.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tools/hil/feed_start_judge.hpp"
#include "tools/hil/hil_firmware_config.hpp"

namespace tnv::hil {

namespace {

constexpr double kFirstRpm = 3000.0;   // the start before the transition
constexpr double kSecondRpm = 2400.0;  // the new start after it
constexpr double kRestRpm = 1.0;
constexpr int kWatchTicks = 3000;      // watched after the transition's recovery
constexpr int kLimitTicks = 30'000;    // any wait longer than this is a failure

// The self-start judge: the emulator's truth against what the bench asked
// for. Feed starts are the shared judge's (feed_start_judge.hpp).
class SelfStartJudge {
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
    if (asked_on_) return;
    const double n = std::fabs(m.spindle_truth().speed_rpm);
    low_rpm_ = std::min(low_rpm_, n);
    rise_rpm_ = std::max(rise_rpm_, n - low_rpm_);
  }
  // The real speed within the at-speed window of what was asked.
  bool at_asked_speed(const emu::Machine& m) const noexcept {
    return asked_on_ && within_at_speed_window(m.spindle_truth().speed_rpm, asked_rpm_);
  }
  double rise_rpm() const noexcept { return rise_rpm_; }

 private:
  bool asked_on_ = false;
  double asked_rpm_ = 0.0;
  double low_rpm_ = 0.0;
  double rise_rpm_ = 0.0;
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
    feed.observe(machine, front());
  }
  // The element at the front of the queue, as an index into `elements`.
  std::size_t front() const {
    return program_base + static_cast<std::size_t>(task->motion().stats().segments_done - done_base);
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
    program_base = elements.size();
    done_base = task->motion().stats().segments_done;
    for (const auto& d : kSide) {
      fw::motion::PlanePoint end = task->next_segment_start_mm();
      end[hal::index(hal::kPlaneFirst)] += d[0];
      end[hal::index(hal::kPlaneSecond)] += d[1];
      const fw::motion::Segment line = fw::motion::line_to(end, 3.0);
      fw::motion::SegmentRefusal why{};
      if (task->push_segment(line, why) != fw::CommandStatus::ok) return false;
      elements.push_back(line);
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
  SelfStartJudge judge{};
  FeedStartJudge feed{};
  std::vector<fw::motion::Segment> elements;  // every element pushed, in order (what `feed` counts against)
  std::size_t program_base = 0;               // the running program's first element in `elements`
  std::uint64_t done_base = 0;                // the task's segments_done when it was pushed
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
    if (!b.run_until([&] { return b.judge.at_asked_speed(b.machine); })) return r;
    b.run(200);
  } else {
    if (!b.push_square()) return r;
    if (!b.run_until([&] { return !b.feed.onsets().empty(); })) return r;
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
        reached = reached || b.judge.at_asked_speed(b.machine);
        return reached && b.program_done();
      }))
    return r;
  r.restarted = reached;
  b.judge.ask_off(b.machine);
  b.run(kWatchTicks);
  r.program_end_stop = b.task->spindle().last_stop_cause() == fw::SpindleStopCause::program_end &&
                       std::fabs(b.rpm()) < kRestRpm && b.judge.rise_rpm() <= kSelfStartRpm;
  const FeedStartCount feed = b.feed.count(b.elements);
  r.feed_onsets = feed.feed_onsets;
  r.feed_before_at_speed = feed.feed_before_at_speed;
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
