#pragma once
// tnv-hil bus-stress: the emulated node (EmulatedBus: real firmware, virtual
// CAN wire) runs the scenario's circle while a flood of frames at one
// identifier keeps the wire at the given load, several hosts (each with its
// own host id) send requests and stage parameter sets at once, and an
// ESTOP is sent into the flood. Every number is counted on the simulated
// wire and the node's own counters (docs/safety.md "Bus priority, tags,
// hosts and ownership").
#include <cstdint>
#include <string>

namespace tnv::can_host {

struct BusStressOptions {
  std::uint32_t flood_id = 0x7FF;  // 11-bit identifier of the flood frames (8 data bytes each)
  double load = 1.0;               // share of the wire the flood offers, 0 .. 1
  int hosts = 2;                   // requesting hosts, ids 1 .. hosts (1 .. 4)
  std::string scenario = "no-cut";
  int rounds = 40;                 // read rounds (get + capture status) per host
  std::int64_t estop_motion_tick = 6000;  // when the ESTOP goes out (ticks into the circle)
};

struct BusStressResult {
  std::uint64_t requests = 0;
  std::uint64_t replies_received = 0;       // the reply with the request's tag, within the timeout
  std::uint64_t replies_misattributed = 0;  // a reply taken by tag whose content answers another request
  std::uint64_t replies_stale = 0;          // replies whose tag no host was waiting for (discarded)
  double heartbeat_max_gap_ms = 0.0;
  double fault_event_delay_ms = -1.0;       // ESTOP queued -> FAULT_EVENT received (-1: never)
  std::uint64_t missed_ticks = 0;
  std::uint64_t late_ticks = 0;
  std::uint64_t staged_sets_crossed = 0;    // commits whose applied count was not the host's own
  std::uint64_t commits = 0;
  std::uint64_t flood_frames = 0;
  double bus_load = 0.0;                    // busy bits / bits while the flood ran
  std::uint64_t telemetry_dropped = 0;      // node: telemetry frames dropped for want of room
  std::uint64_t node_tx_dropped = 0;
  bool circle_ran = false;
  std::string error;                        // set when the run could not be made
};

// Empty when the options are usable, else why not.
std::string validate(const BusStressOptions& options);
BusStressResult run_bus_stress(const BusStressOptions& options);

}  // namespace tnv::can_host
