#pragma once
// tnv-hil rt-budget: what every kind of CAN request costs the real-time
// loop. A scripted bench session runs through the CAN node on the HIL rig
// (charged time on) while the servo holds: parameter get / set / stage /
// commit / discard, save, load, restore_defaults, select_controller,
// SHAPER, capture arm / status / upload / abort, an identification
// EXCITE and BORE_GAUGE (query, the start-up part, parts learned by RLS
// with a variance-perturbation reset), with telemetry on. Each tick and each service() is timed in the
// calling thread's CPU time (thread_cpu_clock.hpp) and metered in board
// time (the rig's work meter and cost model, hil_rig.hpp), and filed under
// the request it handled; the board counts missed and late ticks as it
// would on a real FPGA (charged time).
#include <cstdint>
#include <string>
#include <vector>

#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {

struct RtBudgetOptions {
  std::string scenario = "no-cut";
  int rounds = 20;  // times the scripted session is repeated
};

struct RtBudgetRow {
  std::string kind;          // "overall", "tick", "service_idle", or a request kind
  std::uint64_t calls = 0;
  double max_call_us = 0.0;    // host thread CPU time
  double p999_call_us = 0.0;   // 99.9th percentile (nearest rank)
  double max_board_us = 0.0;   // modelled board time (the rig's charge model)
  double p999_board_us = 0.0;
  std::uint64_t refused = 0;  // answers (in the calls of this kind) that were not ok
};

struct RtBudgetResult {
  std::string error;  // "" when the session ran
  RtBudgetRow overall;
  std::vector<RtBudgetRow> kinds;  // first-seen order
  std::uint64_t ticks = 0;
  std::uint64_t missed_ticks = 0;
  std::uint64_t late_ticks = 0;
  std::uint64_t requests = 0;         // frames sent to the node
  std::uint64_t replies = 0;          // answers received (ACK, PARAM_REPLY, CAPTURE_STATUS)
  std::uint64_t refused = 0;          // answers that were not ok
  std::uint64_t upload_frames = 0;    // CAPTURE_DATA frames received
  std::uint64_t worker_jobs = 0;      // saves, loads and shaper designs run by the worker
  ChargedTime charged{};              // the rig's charged-time account
  bool held = false;                  // holding, no fault, at the end
};

RtBudgetResult run_rt_budget(const RtBudgetOptions& options);

}  // namespace tnv::hil
