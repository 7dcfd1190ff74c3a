#pragma once
// Fault injection on the HIL rig: the real firmware runs a circle, a jog or
// a hold on the emulated board while the scenario's fault schedule injects
// one fault; the bench watches the board's outputs (not the firmware's own
// record) to see when they became safe, and what the firmware latched.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "emulator/machine.hpp"
#include "emulator/scenario.hpp"
#include "firmware/supervisor/fault.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_record.hpp"
#include "hal/axis.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {

enum class FaultMotion : std::uint8_t {
  circle,  // the scenario's S1 circle (moving from dwell_s after servo-on)
  jog_x,   // the operator jogs X at +20 mm/s, re-sent every tick
  hold,    // servo on, holding where the table stands
};

const char* to_string(FaultMotion motion) noexcept;

struct FaultCase {
  std::string name{};
  emu::FaultSpec fault{};  // appended to the scenario's schedule
  FaultMotion motion = FaultMotion::circle;
  // What the supervisor should latch; none = the fault is tolerated.
  fw::FaultReason expected = fw::FaultReason::none;
  fw::FaultReason also_accepted = fw::FaultReason::none;  // a second reason that names the same event
  double give_up_s = 1.0;  // keep watching this long after the injection
  std::string note{};      // one line for the report
};

struct FaultObservation {
  std::string error;  // the rig or the motion was refused; empty otherwise
  bool detected = false;
  fw::FaultRecord fault{};  // what the firmware latched
  double injected_s = 0.0;  // machine time the fault took effect (its sub-step boundary)
  double detected_s = 0.0;  // machine time of the tick latch the latching tick read
  std::uint64_t first_tick_after = 0;  // firmware tick count of the first tick after the injection
  std::uint64_t latching_tick = 0;     // firmware tick count of the tick that latched the fault
  // First moment after the injection the board's outputs were safe (DAC
  // registers mid-scale, both enables off): the latching tick's write, or
  // earlier when the board's watchdog tripped first.
  std::optional<double> outputs_safe_s;
  bool watchdog_tripped = false;      // the board's watchdog made the outputs safe on its own
  bool live_before_detection = true;  // both enables on at every tick from the injection until the latch
  emu::BoardOutputs after_latch{};    // the board's outputs right after the latching tick's write
  std::array<double, hal::kAxisCount> command_after_mm_s{};  // per axis: what the servopacks get one sub-step after that
  double deviation_um = 0.0;  // max |table - reference| on either axis from the injection to the latch
  fw::TickCounters counters{};

  // Firmware ticks from the injection to the latch, 1 = the first tick after it.
  std::uint64_t ticks_to_detect() const noexcept { return detected ? latching_tick - first_tick_after + 1 : 0; }
  std::optional<double> time_to_safe_s() const noexcept {
    if (!outputs_safe_s) return std::nullopt;
    return *outputs_safe_s - injected_s;
  }
};

// Runs one case on a fresh rig; `rig_out`, if given, receives the rig
// afterwards (to go on ticking, clear the fault, ...). `config`: the
// firmware's configuration (default_firmware_config() if null).
FaultObservation run_fault_case(const emu::Scenario& scenario, const FaultCase& fault_case,
                                 fw::ControllerKind controller = fw::ControllerKind::rdvsc,
                                 std::unique_ptr<HilRig>* rig_out = nullptr,
                                 const fw::FirmwareConfig* config = nullptr);

// The firmware stops ticking at hang_s (mid-circle) while the board runs on:
// when does the board's watchdog make the outputs safe, and what does the
// firmware latch when it comes back after hang_ms?
struct WatchdogObservation {
  std::string error;
  double last_kick_s = 0.0;
  std::optional<double> trip_s;  // the board's watchdog trip
  emu::BoardOutputs at_trip{};
  std::array<double, hal::kAxisCount> command_at_trip_mm_s{};  // per axis
  fw::FaultRecord fault_on_return{};
  fw::CommandStatus clear_while_tripped = fw::CommandStatus::ok;
  fw::CommandStatus clear_after_reset = fw::CommandStatus::ok;
};

WatchdogObservation run_watchdog_case(const emu::Scenario& scenario, double hang_s, double hang_ms,
                                      fw::ControllerKind controller = fw::ControllerKind::rdvsc);

// Every injected fault of the safety table (docs/safety.md), on the S1 circle
// unless the fault belongs to another motion.
std::vector<FaultCase> standard_fault_cases();

}  // namespace tnv::hil
