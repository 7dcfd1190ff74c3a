#pragma once
// Runs a set of circle jobs (scenario x controller x seed) on all cores and
// averages each (scenario, controller) cell over its seeds.
#include <functional>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/circle_run.hpp"

namespace tnv::hil {

struct SweepCell {
  std::string scenario;
  fw::ControllerKind controller = fw::ControllerKind::rdvsc;
  ContourStats averaged{};             // seed average (encoder-measured, as S1 scored)
  std::vector<ContourStats> per_seed;  // in seed order
  // Truth beside it (circle_run.hpp): the table and the tool point.
  ContourStats true_table_averaged{};
  ContourStats true_tool_averaged{};
  std::vector<ContourStats> true_table_per_seed;
  std::vector<ContourStats> true_tool_per_seed;
  CircleRunResult seed0;               // with trace when traces were asked for
  std::string error;                   // first failed seed, if any
};

struct SweepRequest {
  std::vector<emu::Scenario> scenarios;
  std::vector<fw::ControllerKind> controllers;
  int seeds = 1;
  bool keep_seed0_trace = false;
  unsigned threads = 0;  // 0 = hardware concurrency
  // Called from worker threads as jobs finish (done, total); may be empty.
  std::function<void(std::size_t, std::size_t)> progress;
};

// Cells in scenario-major, controller-minor order.
std::vector<SweepCell> run_sweep(const SweepRequest& request, const fw::FirmwareConfig& config);

}  // namespace tnv::hil
