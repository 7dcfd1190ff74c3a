#pragma once
// One HIL run of the S1 circle: the real firmware tick task, through the
// real FPGA driver, on the emulated I/O board and TNV-40 table.
#include <array>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_record.hpp"
#include "tools/hil/contour_stats.hpp"

namespace tnv::hil {

struct TraceSample {
  double t_s = 0.0;  // since the start of motion
  std::array<double, 2> reference_mm{};
  std::array<double, 2> position_mm{};  // encoder-measured, as scored
  std::array<double, 2> command_mm_s{};
  std::array<double, 2> s{};
  std::array<double, 2> d_hat_mm_s{};
  std::array<double, 2> tool_mm{};      // emulator truth (tool point)
  std::array<double, 2> table_mm{};     // emulator truth (table: the motor side through the ball screw)
  double contour_um = 0.0;
};

struct CircleRunOptions {
  bool keep_trace = false;
};

struct CircleRunResult {
  bool completed = false;
  std::string error;  // why the run did not complete; empty when it did
  ContourStats stats{};             // S1 eq. (33) from the encoder-measured positions, as the paper scored
  // The same error from the emulator's truth on the same ticks: the table,
  // and the tool point (table + structural mode). With backlash or lead
  // error ([plant] keys) the encoder, on the motor, does not see these.
  ContourStats true_table_stats{};
  ContourStats true_tool_stats{};
  fw::FaultRecord fault{};
  fw::TickCounters counters{};
  std::vector<TraceSample> trace;
};

CircleRunResult run_circle(const emu::Scenario& scenario, const fw::FirmwareConfig& base_config,
                           fw::ControllerKind controller, const CircleRunOptions& options = {});

}  // namespace tnv::hil
