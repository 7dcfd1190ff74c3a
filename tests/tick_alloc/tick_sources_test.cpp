// Tick discipline for every controller kind, motion source and fault path
// (issue 15): each case starts from the HIL rig at rest, then its commands
// and every tick run under the allocation guard (operator new and the
// malloc family, alloc_guard.hpp) and, in a forked child on a fresh rig,
// under the seccomp guard (seccomp_guard.hpp). Each case also checks where
// it ended (state or latched fault), so a case that silently did nothing
// cannot pass.
#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "emulator/scenario_file.hpp"
#include "firmware/control/speed_observer_design.hpp"
#include "tests/hil/hil_rig.hpp"
#include "tests/tick_alloc/alloc_guard.hpp"
#include "tests/tick_alloc/seccomp_guard.hpp"

namespace tnv::hil {
namespace {

struct SourceCase {
  std::string name;
  fw::ControllerKind controller = fw::ControllerKind::rdvsc;
  bool friction_and_observer = false;      // friction feed-forward and the speed observer on, both axes
  bool force_loop = false;                 // [milling] on and the force loop (arsc.enable) setting the override
  std::uint32_t period_ticks = 1;          // its arsc.period_ticks
  std::vector<emu::FaultSpec> faults{};    // injected by the emulated board
  bool home_switches = false;              // the board's home switches and index marks near the start (homing cases)
  double home_search_max_mm = 0.0;         // homing search bound of x; 0 = the default
  // The command(s) that start the case, right after the rig is at rest.
  std::function<fw::CommandStatus(test::HilRig&)> start;
  // Called before tick k (1..ticks): jog repeats, a stop, an e-stop.
  std::function<void(test::HilRig&, int)> between_ticks = [](test::HilRig&, int) {};
  int ticks = 1500;
  // Where the case must end: a motion state, or (fault != none) a latched fault.
  fw::MotionState end_state = fw::MotionState::moving;
  fw::FaultReason fault = fw::FaultReason::none;
};

std::ostream& operator<<(std::ostream& os, const SourceCase& c) { return os << c.name; }

fw::FirmwareConfig source_config(const SourceCase& c) {
  fw::FirmwareConfig config = fw::default_firmware_config();
  config.arsc.enabled = c.force_loop;
  config.arsc.period_ticks = c.period_ticks;
  if (c.home_search_max_mm > 0.0) config.axis[0].homing.search_max_mm = c.home_search_max_mm;
  for (auto& axis : config.axis) {
    axis.controller = c.controller;
    if (!c.friction_and_observer) continue;
    axis.friction.enabled = true;
    const fw::ObserverDesign d = fw::steady_state_kalman_gain(axis.model, {0.5, 2.0, axis.count_mm});
    axis.observer = d.params;
    axis.observer.enabled = d.ok;
    axis.observer.use_position = d.ok;
  }
  return config;
}

std::unique_ptr<test::HilRig> rig_at_rest(const SourceCase& c) {
  emu::Scenario s = *emu::builtin_scenario("no-cut");
  s.faults = c.faults;
  if (c.home_switches) {
    // x stands at 6 mm, y at 0: switches 2 mm below, marks 0.5 mm past their release.
    s.board.axis[0].home_switch = s.board.axis[1].home_switch = true;
    s.board.axis[0].home_mm = 4.0;
    s.board.axis[1].home_mm = -2.0;
    s.board.axis[0].index_deg = 162.0;  // marks at 4.5 + 10 k mm
    s.board.axis[1].index_deg = 306.0;  // marks at -1.5 + 10 k mm
    // z 2 mm below its switch at the top (the default board's), marks 0.5 mm below its release.
    s.z_axis.start_mm = -2.0;
    s.board.axis[hal::index(hal::Axis::z)].index_deg = 342.0;  // marks at -0.5 + 10 k mm
  }
  if (c.force_loop) s.milling = {.enabled = true, .depth = {0.2, 1.0, 1.0, 1.0}};
  auto rig = std::make_unique<test::HilRig>(s, source_config(c));
  for (int i = 0; i < 3; ++i) rig->tick();
  return rig;
}

// The case's commands and ticks; true when it ended where it must.
bool run_source_case(const SourceCase& c, test::HilRig& rig) noexcept {
  if (c.start(rig) != fw::CommandStatus::ok) return false;
  for (int k = 1; k <= c.ticks; ++k) {
    c.between_ticks(rig, k);
    rig.machine.advance_to_next_tick();
    rig.task.tick();
  }
  if (c.fault != fw::FaultReason::none) return rig.task.fault().reason == c.fault;
  // The force loop must have cut: sampled at its rate and set the override.
  if (c.force_loop && (rig.task.feed_source().status().state != fw::arsc::ArscSourceState::cutting ||
                       rig.task.feed_source().status().samples < static_cast<std::uint32_t>(c.ticks) / c.period_ticks))
    return false;
  return !rig.task.fault().active() && rig.task.state() == c.end_state;
}

std::string where_it_ended(const test::HilRig& rig) {
  return std::string("state ") + fw::to_string(rig.task.state()) + ", fault " + fw::to_string(rig.task.fault().reason);
}

fw::CommandStatus start_test_circle(test::HilRig& rig) { return rig.task.start_circle(circle_spec_for(rig.scenario)); }

// The spindle cases start from rest, held, with the spindle started forward at 3000 rpm.
fw::CommandStatus hold_with_spindle_at_3000(test::HilRig& rig) {
  const fw::CommandStatus held = rig.task.hold_position();
  if (held != fw::CommandStatus::ok) return held;
  return rig.task.spindle_start(fw::SpindleDirection::forward, 3000.0) == fw::SpindleResult::ok
             ? fw::CommandStatus::ok
             : fw::CommandStatus::invalid;
}

std::vector<SourceCase> source_cases() {
  std::vector<SourceCase> out;
  // Every controller kind on the circle (past the dwell, into the motion), plain and compensated.
  for (const fw::ControllerKind kind : {fw::ControllerKind::pid, fw::ControllerKind::dvsc, fw::ControllerKind::rdvsc}) {
    for (const bool compensated : {false, true}) {
      SourceCase c;
      c.name = std::string("circle_") + fw::to_string(kind) + (compensated ? "_friction_observer" : "");
      c.controller = kind;
      c.friction_and_observer = compensated;
      c.start = start_test_circle;
      out.push_back(c);
    }
  }
  {
    SourceCase c;  // point-to-point move of x, run to its end
    c.name = "start_move";
    c.start = [](test::HilRig& rig) {
      const fw::CommandStatus held = rig.task.hold_position();
      return held != fw::CommandStatus::ok ? held : rig.task.start_move({hal::Axis::x, 2.0, 10.0, 0.02, 0.0});
    };
    c.ticks = 800;
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  {
    SourceCase c;  // the operator's jog stream, reversing, then released: back to holding
    c.name = "jog";
    c.start = [](test::HilRig& rig) { return rig.task.hold_position(); };
    c.between_ticks = [](test::HilRig& rig, int k) {
      if (k <= 900) rig.task.jog(hal::Axis::x, (k / 300) % 2 == 0 ? 5.0 : -5.0);
      if (k <= 900) rig.task.jog(hal::Axis::y, 2.0);
      if (k == 901) rig.task.jog(hal::Axis::x, 0.0);
      if (k == 901) rig.task.jog(hal::Axis::y, 0.0);
    };
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  {
    SourceCase c;  // controlled stop of a running circle
    c.name = "circle_controlled_stop";
    c.start = start_test_circle;
    c.between_ticks = [](test::HilRig& rig, int k) {
      if (k == 800) rig.task.stop();
    };
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  {
    SourceCase c;  // homing cycle of every axis: switch, back-off, index, frame moved at the index
    c.name = "home_all";
    c.home_switches = true;
    c.start = [](test::HilRig& rig) { return rig.task.home(hal::kEveryAxis); };
    c.ticks = 4000;
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  {
    SourceCase c;  // homing without a switch: the search runs out of travel and faults
    c.name = "home_missing_switch";
    c.home_search_max_mm = 3.0;
    c.start = [](test::HilRig& rig) { return rig.task.home(hal::axis_bit(hal::Axis::x)); };
    c.ticks = 1000;
    c.fault = fw::FaultReason::homing_failed;
    out.push_back(c);
  }
  {
    SourceCase c;  // stop of a jog: both targets to 0
    c.name = "jog_stop";
    c.start = [](test::HilRig& rig) { return rig.task.hold_position(); };
    c.between_ticks = [](test::HilRig& rig, int k) {
      if (k < 300) rig.task.jog(hal::Axis::x, 8.0);
      if (k == 300) rig.task.stop();
    };
    c.ticks = 1000;
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  {
    SourceCase c;  // the spindle: a start, a rapid while it ramps, feed moves that wait for it, a speed
                   // change mid-cut (the feed brakes and waits), the program's end stopping it
    c.name = "spindle_program";
    c.start = [](test::HilRig& rig) {
      if (const fw::CommandStatus held = hold_with_spindle_at_3000(rig); held != fw::CommandStatus::ok) return held;
      const fw::motion::PlanePoint at = rig.task.next_segment_start_mm();
      fw::motion::Segment rapid = fw::motion::line_to({at[0] + 1.0, at[1]}, 20.0);
      rapid.rapid = true;
      fw::motion::SegmentRefusal why{};
      const fw::CommandStatus pushed = rig.task.push_segment(rapid, why);
      if (pushed != fw::CommandStatus::ok) return pushed;
      return rig.task.push_segment(fw::motion::line_to({at[0] + 6.0, at[1]}, 5.0), why);
    };
    c.between_ticks = [](test::HilRig& rig, int k) {
      if (k == 1500) (void)rig.task.spindle_set_speed(2000.0);
      if (k == 2000) (void)rig.task.end_program();
    };
    c.ticks = 5000;
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  {
    SourceCase c;  // a feed per revolution (G95): the path speed from the measured spindle speed every
                   // tick, through a speed change mid-cut, to the program's end
    c.name = "spindle_per_rev";
    c.start = [](test::HilRig& rig) {
      if (const fw::CommandStatus held = hold_with_spindle_at_3000(rig); held != fw::CommandStatus::ok) return held;
      const fw::motion::PlanePoint at = rig.task.next_segment_start_mm();
      fw::motion::PlanePoint end = at;
      end[0] += 10.0;
      fw::motion::Segment line = fw::motion::line_to(end, 5.0);
      line.feed_mm_rev = 0.1;  // 5 mm/s at 3000 rpm
      fw::motion::SegmentRefusal why{};
      return rig.task.push_segment(line, why);
    };
    c.between_ticks = [](test::HilRig& rig, int k) {
      if (k == 1500) (void)rig.task.spindle_set_speed(2000.0);
      if (k == 2000) (void)rig.task.end_program();
    };
    c.ticks = 7000;
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  {
    SourceCase c;  // a feed per revolution along a boring pass's depth: the infeed from the boring schedule at
                   // the bar's overhang and the path speed from the measured spindle speed every tick, through
                   // a speed change mid-cut, to the program's end
    c.name = "spindle_per_rev_depth";
    c.start = [](test::HilRig& rig) {
      if (const fw::CommandStatus held = hold_with_spindle_at_3000(rig); held != fw::CommandStatus::ok) return held;
      rig.task.set_depth_infeed({40.0, 0.12, 310.0, 0.05});
      const fw::motion::PlanePoint at = rig.task.next_segment_start_mm();
      fw::motion::PlanePoint end = at;
      end[2] -= 10.0;
      fw::motion::Segment line = fw::motion::line_to(end, 6.0);  // 0.12 mm/rev at 3000 rpm
      line.overhang_at_end_mm = 50.0;
      fw::motion::SegmentRefusal why{};
      return rig.task.push_segment(line, why);
    };
    c.between_ticks = [](test::HilRig& rig, int k) {
      if (k == 1000) (void)rig.task.spindle_set_speed(2000.0);
      if (k == 1500) (void)rig.task.end_program();
    };
    c.ticks = 7000;
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  {
    SourceCase c;  // the spindle turning when the e-stop input trips: stopped in that tick
    c.name = "spindle_estop";
    c.start = [](test::HilRig& rig) {
      const fw::CommandStatus held = rig.task.hold_position();
      if (held != fw::CommandStatus::ok) return held;
      return rig.task.spindle_start(fw::SpindleDirection::reverse, 2000.0) == fw::SpindleResult::ok
                 ? fw::CommandStatus::ok
                 : fw::CommandStatus::invalid;
    };
    c.between_ticks = [](test::HilRig& rig, int k) {
      if (k == 1000) rig.machine.set_estop(true);
    };
    c.fault = fw::FaultReason::estop;
    out.push_back(c);
  }
  for (const std::uint32_t period : {1u, 10u}) {
    SourceCase c;  // a program of 1 mm pieces cut under the force loop (the S3 feed-override source)
    c.name = "program_force_loop_every_" + std::to_string(period) + "_ticks";
    c.force_loop = true;
    c.start = [](test::HilRig& rig) {
      const fw::CommandStatus held = rig.task.hold_position();
      fw::motion::SegmentRefusal why{};
      return held != fw::CommandStatus::ok ? held : rig.task.push_segment(fw::motion::line_to({1.0, 0.0}, 60.0), why);
    };
    c.between_ticks = [](test::HilRig& rig, int k) {
      fw::motion::SegmentRefusal why{};
      while (rig.task.motion().free_slots() > 0) {
        const fw::motion::PlanePoint end = rig.task.motion().queue_end_mm();
        if (rig.task.push_segment(fw::motion::line_to({end[0] + 1.0, end[1]}, 60.0), why) != fw::CommandStatus::ok) break;
      }
      if (k == 700) rig.task.set_feed_override(0.8);  // the operator scales the loop's range
    };
    c.period_ticks = period;
    c.ticks = 1500;
    out.push_back(c);
  }
  for (const fw::ExcitationKind kind : {fw::ExcitationKind::step, fw::ExcitationKind::ramp}) {
    SourceCase c;  // open-loop excitation for identification, run out
    c.name = kind == fw::ExcitationKind::step ? "excitation_step" : "excitation_ramp";
    c.start = [kind](test::HilRig& rig) {
      const fw::CommandStatus held = rig.task.hold_position();
      fw::ExcitationSpec spec;
      spec.kind = kind;
      spec.level_mm_s = kind == fw::ExcitationKind::step ? 5.0 : 20.0;
      spec.duration_s = kind == fw::ExcitationKind::step ? 0.15 : 3.0;
      return held != fw::CommandStatus::ok ? held : rig.task.start_excitation(hal::Axis::y, spec);
    };
    c.ticks = 3500;
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  for (const fw::ExcitationKind kind :
       {fw::ExcitationKind::sweep, fw::ExcitationKind::multisine, fw::ExcitationKind::multisine_open}) {
    SourceCase c;  // frequency-response excitations (issue 17): 64 tones at most, run out
    c.name = kind == fw::ExcitationKind::sweep       ? "excitation_sweep"
             : kind == fw::ExcitationKind::multisine ? "excitation_multisine"
                                                     : "excitation_multisine_open";
    c.start = [kind](test::HilRig& rig) {
      const fw::CommandStatus held = rig.task.hold_position();
      fw::ExcitationSpec spec;
      spec.kind = kind;
      spec.level_mm_s = 3.0;
      spec.duration_s = 2.0;
      spec.f_min_hz = 5.0;
      spec.f_max_hz = 400.0;
      spec.tones = fw::kMaxMultisineTones;
      return held != fw::CommandStatus::ok ? held : rig.task.start_excitation(hal::Axis::x, spec);
    };
    c.ticks = 2500;
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  {
    SourceCase c;  // a multisine on a carrier: the holding reference moves, then rests (run out)
    c.name = "excitation_multisine_carrier";
    c.start = [](test::HilRig& rig) {
      const fw::CommandStatus held = rig.task.hold_position();
      fw::ExcitationSpec spec;
      spec.kind = fw::ExcitationKind::multisine;
      spec.level_mm_s = 3.0;
      spec.duration_s = 2.0;
      spec.f_min_hz = 5.0;
      spec.f_max_hz = 400.0;
      spec.tones = fw::kMaxMultisineTones;
      spec.carrier_mm_s = 3.0776;
      return held != fw::CommandStatus::ok ? held : rig.task.start_excitation(hal::Axis::x, spec);
    };
    c.ticks = 2500;
    c.end_state = fw::MotionState::holding;
    out.push_back(c);
  }
  {
    SourceCase c;  // the fault latch: a remote e-stop mid-circle, then faulted ticks
    c.name = "fault_latch_remote_estop";
    c.start = start_test_circle;
    c.between_ticks = [](test::HilRig& rig, int k) {
      if (k == 700) rig.task.estop();
    };
    c.fault = fw::FaultReason::remote_estop;
    out.push_back(c);
  }
  {
    SourceCase c;  // the stall trip: y's encoder goes dead mid-circle
    c.name = "stall_trip";
    c.start = start_test_circle;
    c.faults = {{.kind = emu::FaultKind::encoder_dead, .start_s = 1.0004, .axis = hal::Axis::y}};
    c.ticks = 2000;
    c.fault = fw::FaultReason::encoder_stall;
    out.push_back(c);
  }
  {
    SourceCase c;  // a fault the board reports: the e-stop input
    c.name = "fault_latch_estop_input";
    c.start = start_test_circle;
    c.faults = {{.kind = emu::FaultKind::estop, .start_s = 0.9}};
    c.fault = fw::FaultReason::estop;
    out.push_back(c);
  }
  return out;
}

class TickSources : public ::testing::TestWithParam<SourceCase> {};

TEST_P(TickSources, CommandsAndTicksAllocateNothing) {
  const SourceCase& c = GetParam();
  auto rig = rig_at_rest(c);
  ASSERT_TRUE(rig->init_ok);
  bool ok = false;
  const long heap_calls = test::heap_calls_in([&] { ok = run_source_case(c, *rig); });
  EXPECT_TRUE(ok) << "the case did not end where it must: " << where_it_ended(*rig);
  EXPECT_EQ(heap_calls, 0) << "heap calls in the commands and ticks of " << c.name;
}

TEST_P(TickSources, CommandsAndTicksMakeNoSystemCall) {
  if (!test::kSeccompUsable) GTEST_SKIP() << "the sanitizer runtime makes its own system calls; proven in the plain build";
  const SourceCase& c = GetParam();
  auto rig = rig_at_rest(c);
  ASSERT_TRUE(rig->init_ok);
  const int result = test::run_without_syscalls([&] { return run_source_case(c, *rig) ? 0 : 3; });
  if (result == test::kSeccompUnavailable) GTEST_SKIP() << "seccomp is not available on this kernel";
  EXPECT_EQ(result, 0) << (result < 0 ? "killed by signal " + std::to_string(-result) + ": a system call"
                                      : "the case did not end where it must");
}

INSTANTIATE_TEST_SUITE_P(Every, TickSources, ::testing::ValuesIn(source_cases()),
                         [](const ::testing::TestParamInfo<SourceCase>& p) { return p.param.name; });

}  // namespace
}  // namespace tnv::hil
