#pragma once
// tnv-hil screw-map: a lead-error calibration run on the emulated machine,
// as one is done with a laser interferometer on a real one. The axis steps
// through its range forward, then back, stopping at each point; at each
// stop, settled, the run records where the control's encoder puts the axis
// and what a table-side reference reads (the emulator's true table
// position plus the reference's own noise). The file it writes is what
// tnv-hil screw-fit reads, from this run or from a real machine's laser.
#include <cstdint>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "hal/io_board.hpp"
#include "tools/hil/gauge_file.hpp"

namespace tnv::hil {

struct ScrewMapOptions {
  hal::Axis axis = hal::Axis::x;
  double start_mm = -40.0;    // first point (from where the axis stands at power-up: 0)
  double length_mm = 80.0;    // covered forward, then back: the lead error shows over a long span
  double step_mm = 0.625;     // 16 points per 10 mm turn
  double overshoot_mm = 1.0;  // past each end before the pass, so every point is approached one way
  double speed_mm_s = 10.0;
  double settle_s = 0.2;                 // at rest before each reading
  double reference_noise_um_rms = 0.05;  // the reference's own noise (a laser: tens of nm)
  std::uint32_t seed = 1;
};

struct ScrewMapResult {
  bool completed = false;
  std::string error;  // a refused move or a fault, naming the point
  std::vector<GaugePoint> points;  // forward pass, then the reverse pass
};

ScrewMapResult run_screw_map(const emu::Scenario& scenario, const fw::FirmwareConfig& config,
                             const ScrewMapOptions& options);

// Empty when the options make a run; otherwise why (naming the option).
std::string validate(const ScrewMapOptions& options);

}  // namespace tnv::hil
