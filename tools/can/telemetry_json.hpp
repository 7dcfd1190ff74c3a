#pragma once
// The heartbeat and the latest telemetry as JSON objects: what
// `tnvctl status --json` / `tnvctl monitor --json` print and what the
// Python module returns as dicts.
#include <nlohmann/json.hpp>

#include "tools/can/node_messages.hpp"
#include "tools/can/telemetry_view.hpp"

namespace tnv::can_host {

// {"state": ..., "fault": ..., "flags": [...], "overruns", "free_slots", "owner"}
nlohmann::json heartbeat_json(const Heartbeat& hb);
// {"state", "target_rpm", "command_rpm", "measured_rpm", "at_speed", "commanded_on",
//  "direction", "inhibited", "waiting_feed", "stop_cause"}
nlohmann::json spindle_json(const SpindleTelemetry& s);
// One monitor sample: t_s, frames, bus_load and every value seen so far.
nlohmann::json telemetry_json(const TelemetryView& l, double t_s, double load);

}  // namespace tnv::can_host
