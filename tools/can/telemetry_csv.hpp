#pragma once
// `tnvctl monitor --csv`: one row per sample of what the node streams, with
// a fixed header (units in the names) so a spreadsheet or pandas reads it
// whatever the node sends; a value not received yet is an empty cell.
#include <string>

#include "tools/can/telemetry_view.hpp"

namespace tnv::can_host {

// The header line, without its newline.
std::string telemetry_csv_header();
// One row for the view at t_s seconds with the given bus load (0..1), without its newline.
std::string telemetry_csv_row(const TelemetryView& view, double t_s, double bus_load);

}  // namespace tnv::can_host
