#include "tools/hil/fault_run.hpp"

#include <algorithm>
#include <cmath>

#include "emulator/fault_timeline.hpp"
#include "emulator/substep_timing.hpp"
#include "tools/hil/command_status_text.hpp"
#include "tools/hil/hil_firmware_config.hpp"

namespace tnv::hil {

namespace {

constexpr double kJogSpeedMmS = 20.0;

std::uint64_t substep_now(const emu::Machine& machine) noexcept {
  return machine.elapsed_clocks() / emu::kSubstepClocks;
}

// Servo on and moving (or holding) the way the case asks; "" when accepted.
std::string start_motion(HilRig& rig, FaultMotion motion) {
  rig.home();
  fw::CommandStatus st = fw::CommandStatus::ok;
  switch (motion) {
    case FaultMotion::circle: st = rig.task.start_circle(circle_spec_for(rig.machine.scenario())); break;
    case FaultMotion::jog_x:
    case FaultMotion::hold: st = rig.task.hold_position(); break;
  }
  if (st != fw::CommandStatus::ok) return "motion refused: " + command_status_text(st, rig.task);
  return {};
}

// The operator keeps the jog key down: the command is re-sent every tick.
void operator_input(HilRig& rig, FaultMotion motion) noexcept {
  if (motion == FaultMotion::jog_x && rig.task.state() != fw::MotionState::faulted) {
    rig.task.jog(hal::Axis::x, kJogSpeedMmS);
  }
}

}  // namespace

const char* to_string(FaultMotion motion) noexcept {
  switch (motion) {
    case FaultMotion::circle: return "circle";
    case FaultMotion::jog_x: return "jog X";
    case FaultMotion::hold: return "hold";
  }
  return "?";
}

FaultObservation run_fault_case(const emu::Scenario& scenario, const FaultCase& fault_case,
                                 fw::ControllerKind controller, std::unique_ptr<HilRig>* rig_out,
                                 const fw::FirmwareConfig* config) {
  FaultObservation obs;
  emu::Scenario with_fault = scenario;
  with_fault.faults.push_back(fault_case.fault);
  std::unique_ptr<HilRig> rig = HilRig::create(
      with_fault, config != nullptr ? *config : fw::default_firmware_config(), controller, obs.error);
  if (!rig) return obs;
  emu::Machine& machine = rig->machine;
  fw::TickTask& task = rig->task;
  const std::uint32_t mid_code = machine.dac_mid_code();
  const std::uint64_t injected_substep = emu::substep_at_or_after(fault_case.fault.start_s);
  obs.injected_s = emu::substep_time_s(injected_substep);
  if (obs.error = start_motion(*rig, fault_case.motion); !obs.error.empty()) return obs;

  const std::uint64_t give_up_substep =
      injected_substep + emu::substep_at_or_after(fault_case.give_up_s) + 2 * emu::kSubstepsPerSecond / 1000;
  for (;;) {
    rig->settle_charge();  // charged time (hil_rig.hpp)
    machine.advance_to_next_tick();
    // A tick latched on the fault's own boundary cannot see it: the fault
    // takes effect just after that latch.
    const bool after = substep_now(machine) > injected_substep;
    if (after && !obs.outputs_safe_s) {
      const emu::BoardOutputs before_tick = machine.board_outputs();
      if (before_tick.safe(mid_code)) {  // the board made them safe on its own: its watchdog
        obs.watchdog_tripped = before_tick.watchdog_tripped;
        obs.outputs_safe_s = before_tick.watchdog_trip_s.value_or(machine.time_s());
      }
    }
    operator_input(*rig, fault_case.motion);
    rig->charged_call([&task]() noexcept { task.tick(); });
    const bool faulted = task.state() == fw::MotionState::faulted;
    if (!after) {
      if (faulted) {
        obs.error = std::string("faulted before the injection: ") + fw::to_string(task.fault().reason);
        break;
      }
      continue;
    }
    if (obs.first_tick_after == 0) obs.first_tick_after = task.counters().ticks;
    const fw::TickRecord& rec = task.last_record();
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const double table_mm = machine.truth(hal::axis_from_index(i)).position_mm;
      obs.deviation_um = std::max(obs.deviation_um, std::fabs(table_mm - rec.axis[i].reference_mm) * 1e3);
    }
    if (faulted) {
      obs.detected = true;
      obs.fault = task.fault();
      obs.latching_tick = task.counters().ticks;
      obs.detected_s = machine.time_s();
      obs.after_latch = machine.board_outputs();
      // Over a transport ([io] write latency) the safe outputs land after the
      // firmware's write: follow the board until they do, at most one tick.
      for (std::uint64_t k = 0; !obs.after_latch.safe(mid_code) && k < emu::kSubstepsPerSecond / 1000; ++k) {
        machine.advance_clocks(emu::kSubstepClocks);
        obs.after_latch = machine.board_outputs();
      }
      if (!obs.outputs_safe_s && obs.after_latch.safe(mid_code)) obs.outputs_safe_s = machine.time_s();
      machine.advance_clocks(emu::kSubstepClocks);
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
        obs.command_after_mm_s[i] = machine.truth(hal::axis_from_index(i)).command_mm_s;
      }
      break;
    }
    const emu::BoardOutputs out = machine.board_outputs();
    obs.live_before_detection = obs.live_before_detection && out.enabled[0] && out.enabled[1];
    if (substep_now(machine) > give_up_substep) break;
  }
  obs.counters = task.counters();
  if (rig_out != nullptr) *rig_out = std::move(rig);
  return obs;
}

WatchdogObservation run_watchdog_case(const emu::Scenario& scenario, double hang_s, double hang_ms,
                                      fw::ControllerKind controller) {
  WatchdogObservation obs;
  std::unique_ptr<HilRig> rig = HilRig::create(scenario, fw::default_firmware_config(), controller, obs.error);
  if (!rig) return obs;
  emu::Machine& machine = rig->machine;
  if (obs.error = start_motion(*rig, FaultMotion::circle); !obs.error.empty()) return obs;
  while (machine.time_s() < hang_s) rig->tick();
  if (rig->task.state() != fw::MotionState::moving) {
    obs.error = "the circle was not moving when the firmware hung";
    return obs;
  }
  obs.last_kick_s = machine.time_s();  // the tick's batched write, kick included, is at the latch instant
  // The firmware hangs; the board keeps counting. Watch it sub-step by sub-step.
  const std::uint64_t hang_end_clocks =
      machine.elapsed_clocks() + static_cast<std::uint64_t>(std::llround(hang_ms * 1e-3 * emu::kClockHz));
  while (machine.elapsed_clocks() < hang_end_clocks) {
    machine.advance_clocks(emu::kSubstepClocks);
    if (!obs.trip_s && machine.board_outputs().watchdog_tripped) {
      obs.trip_s = machine.board_outputs().watchdog_trip_s;
      obs.at_trip = machine.board_outputs();
      machine.advance_clocks(emu::kSubstepClocks);  // the servopacks' command over the next sub-step
      for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
        obs.command_at_trip_mm_s[i] = machine.truth(hal::axis_from_index(i)).command_mm_s;
      }
    }
  }
  // The firmware comes back.
  rig->tick();
  obs.fault_on_return = rig->task.fault();
  obs.clear_while_tripped = rig->task.clear_fault();
  // The operator resets the board's latches, then clears the firmware's fault.
  rig->board.clear_latched_faults();
  rig->tick();
  obs.clear_after_reset = rig->task.clear_fault();
  return obs;
}

std::vector<FaultCase> standard_fault_cases() {
  using emu::FaultKind;
  using fw::FaultReason;
  using hal::Axis;
  // Mid-tick, 2.5 s into the circle (motion starts at about 0.5 s).
  constexpr double t = 3.0004;
  std::vector<FaultCase> cases = {
      {"estop", {.kind = FaultKind::estop, .start_s = t}, FaultMotion::circle, FaultReason::estop, FaultReason::none, 1.0, ""},
      {"servo_alarm", {.kind = FaultKind::servo_alarm, .start_s = t, .axis = Axis::y}, FaultMotion::circle,
       FaultReason::servo_alarm, FaultReason::none, 1.0, ""},
      {"limit_switch", {.kind = FaultKind::limit_switch, .start_s = 1.0004, .axis = Axis::x, .positive_side = true},
       FaultMotion::jog_x, FaultReason::limit_switch, FaultReason::none, 1.0, "X+ switch while jogging X at +20 mm/s"},
      {"encoder_illegal", {.kind = FaultKind::encoder_illegal, .start_s = t, .axis = Axis::x}, FaultMotion::circle,
       FaultReason::encoder_error, FaultReason::none, 1.0, "board FAULTS bit 0"},
      {"encoder_dead", {.kind = FaultKind::encoder_dead, .start_s = t, .axis = Axis::y}, FaultMotion::circle,
       FaultReason::encoder_stall, FaultReason::none, 1.0, "Y count frozen at 1.35 mm/s"},
      {"dac_stuck", {.kind = FaultKind::dac_stuck, .start_s = t, .axis = Axis::x, .dac_code = 2048 + 600},
       FaultMotion::circle, FaultReason::dac_error, FaultReason::none, 1.0, "X output stuck at +48.8 mm/s; board FAULTS bit 2"},
      {"missed_tick_1", {.kind = FaultKind::missed_tick, .start_s = t, .ticks = 1}, FaultMotion::circle,
       FaultReason::none, FaultReason::none, 0.2, "tolerated (up to 2 in a row), counted"},
      {"missed_tick_3", {.kind = FaultKind::missed_tick, .start_s = t, .ticks = 3}, FaultMotion::circle,
       FaultReason::missed_ticks, FaultReason::none, 1.0, "board watchdog trips first (4 ms without a kick)"},
      {"late_tick_1500us", {.kind = FaultKind::late_tick, .start_s = t, .delay_us = 1500}, FaultMotion::circle,
       FaultReason::late_tick, FaultReason::none, 0.2, "needs the tick_task hook-up (period to the supervisor)"},
      // Today the board's watchdog names it; with the hook-up the root cause
      // (late_tick) is checked first, as missed_ticks is.
      {"late_tick_2500us", {.kind = FaultKind::late_tick, .start_s = t, .delay_us = 2500}, FaultMotion::circle,
       FaultReason::watchdog_tripped, FaultReason::late_tick, 1.0, "board watchdog trips before the late tick"},
      {"stale_snapshot", {.kind = FaultKind::stale_snapshot, .start_s = t, .duration_s = 0.005}, FaultMotion::circle,
       FaultReason::stale_snapshot, FaultReason::none, 1.0, ""},
      {"runaway", {.kind = FaultKind::runaway, .start_s = t, .axis = Axis::x}, FaultMotion::circle,
       FaultReason::runaway, FaultReason::none, 1.0, "X drive gain sign flipped"},
      {"runaway_jog", {.kind = FaultKind::runaway, .start_s = 1.0004, .axis = Axis::x}, FaultMotion::jog_x,
       FaultReason::runaway, FaultReason::none, 1.0, "X gain sign flipped while jogging X at +20 mm/s"},
      {"bus_read_error", {.kind = FaultKind::bus_read_error, .start_s = t, .duration_s = 0.001}, FaultMotion::circle,
       FaultReason::bus_error, FaultReason::none, 1.0, "reads fail for 1 ms"},
      {"encoder_jump_100", {.kind = FaultKind::encoder_jump, .start_s = t, .axis = Axis::x, .counts = 100},
       FaultMotion::circle, FaultReason::encoder_implausible, FaultReason::none, 1.0, "X count +100 (41.7 um) in one tick"},
      {"encoder_jump_120_y", {.kind = FaultKind::encoder_jump, .start_s = t, .axis = Axis::y, .counts = -120},
       FaultMotion::circle, FaultReason::encoder_implausible, FaultReason::none, 1.0, "Y count -120, kept"},
      {"snapshot_replayed", {.kind = FaultKind::snapshot_replayed, .start_s = t}, FaultMotion::circle,
       FaultReason::stale_snapshot, FaultReason::none, 1.0, "sequence one below the last"},
  };
  return cases;
}

}  // namespace tnv::hil
