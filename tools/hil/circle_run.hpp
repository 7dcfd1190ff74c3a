#pragma once
// One HIL run of the S1 circle: the real firmware tick task, through the
// real FPGA driver, on the emulated I/O board and TNV-40 table.
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_record.hpp"
#include "tools/score/circle_trace.hpp"
#include "tools/score/contour_stats.hpp"

namespace tnv::hil {

struct CircleRunOptions {
  bool keep_trace = false;
};

struct CircleRunResult {
  bool completed = false;
  std::string error;  // why the run did not complete; empty when it did
  bool timed_out = false;  // not a fault: the circle did not reach holding in its simulated time
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
