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
  double contour_um = 0.0;
};

struct CircleRunOptions {
  bool keep_trace = false;
};

struct CircleRunResult {
  bool completed = false;
  std::string error;  // why the run did not complete; empty when it did
  ContourStats stats{};
  fw::FaultRecord fault{};
  fw::TickCounters counters{};
  std::vector<TraceSample> trace;
};

CircleRunResult run_circle(const emu::Scenario& scenario, const fw::FirmwareConfig& base_config,
                           fw::ControllerKind controller, const CircleRunOptions& options = {});

}  // namespace tnv::hil
