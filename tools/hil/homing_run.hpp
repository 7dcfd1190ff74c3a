#pragma once
// tnv-hil homing: the firmware's homing cycle (COMMAND home, both axes) on
// the emulated table from seeded power-up positions and encoder phases,
// judged against the machine's truth.
//
// Reading error, per axis, at rest after homing: where the firmware says
// the axis stands, minus the configured home (homing.position_mm), against
// where the motor side really stands from the index mark the cycle should
// have latched (the first mark past the switch's release, in the back-off
// direction). Home error: the same less the present reading's own rounding
// to a count, i.e. the error of the frame itself (where it puts the mark);
// what is left is the latch's rounding, at most half a count. Motor side:
// the encoder and its index are on the motor, so home is a motor
// reference; with backlash or lead error the table differs from it by the
// screw (docs/safety.md "Homing").
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "hal/axis.hpp"
#include "firmware/tick/firmware_config.hpp"

namespace tnv::hil {

struct HomingSeedResult {
  std::uint32_t seed = 0;
  // Per axis, indexed by hal::index(axis).
  std::array<double, hal::kAxisCount> power_up_offset_mm{};  // [board] power_up_offset_*_mm of this seed
  std::array<double, hal::kAxisCount> offset_counts{};       // [encoder] offset_counts_* (power-up count and phase)
  bool homed = false;
  std::string failure;                // why not, when not homed
  bool faulted = false;               // not homed: the firmware latched a fault
  bool timed_out = false;             // not homed: still homing when the bench's time ran out
  std::array<double, hal::kAxisCount> home_error_um{};     // the frame's error at the mark, motor side
  std::array<double, hal::kAxisCount> reading_error_um{};  // the reading at rest after homing, motor side
  double time_s = 0.0;                // command to every axis homed
};

struct HomingSummary {
  std::vector<HomingSeedResult> seeds;
  double home_error_um_max = 0.0;     // largest |home error| over seeds and axes
  double home_error_spread_um = 0.0;  // largest (max - min) over seeds, per axis: repeatability
  double reading_error_um_max = 0.0;  // largest |reading error|
  double time_s_max = 0.0;
  bool all_homed = true;
};

// The emulated table homing runs on: home switches at the negative end of
// both axes and index marks away from the switches' release points.
emu::Scenario homing_scenario();
// `table` with homing_scenario()'s switches and index marks where it has
// none of its own (a built-in such as bench-no-cut), so its plant, noise
// and transport are homed on the same board.
emu::Scenario with_homing_board(emu::Scenario table);
// The firmware config for it: homing parameters set for that table.
fw::FirmwareConfig homing_firmware_config();

// One homing from the seed's power-up (position within +-20 mm of the
// scenario's, count offset anywhere in the 16-bit counter with a random
// fraction of a count as encoder phase).
HomingSeedResult run_homing_seed(const emu::Scenario& scenario, const fw::FirmwareConfig& config, std::uint32_t seed);
HomingSummary run_homing(const emu::Scenario& scenario, const fw::FirmwareConfig& config, std::uint32_t seeds);

}  // namespace tnv::hil
