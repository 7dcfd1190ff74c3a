#pragma once
// What the node's planner sees of a boring run (BORE_GAUGE on the board):
// its settings as the bore.* parameters carry them (f32 on the wire), the
// gauge readings on BORE_GAUGE's grid (0.1 um) and the infeeds on
// BORE_INFEED's grid. The in-process planner
// (tools/hil/boring_direct_link.hpp) uses the same, so the two give the
// same infeeds bit for bit.
#include <optional>
#include <string>
#include <vector>

#include "firmware/adaptive/boring/boring_station.hpp"

namespace tnv::hil {

// "" when the node's planner can run `params` measured at `positions_mm`,
// else what it cannot do (the node fixes the log base, P0, the band, the
// alpha floor, the infeed range, the start-up rule, and measures at two
// overhangs that span the model's range).
std::string node_planner_refusal(const fw::BoringPlannerParams& params, const std::vector<double>& positions_mm);

// The bore.* settings that give the node `params` at `positions_mm`
// (enabled), each value as its parameter carries it.
fw::BoringStationSettings node_bore_settings(const fw::BoringPlannerParams& params,
                                             const std::vector<double>& positions_mm);

// `params` with every value the node carries as an f32 parameter rounded as
// the wire rounds it; the rest as given.
fw::BoringPlannerParams at_node_resolution(const fw::BoringPlannerParams& params);

// A reading as BORE_GAUGE carries it; nullopt when the field cannot (beyond
// +-3.2767 mm, or not finite).
std::optional<double> gauge_on_wire_mm(double bore_error_mm);

// BORE_INFEED's infeed grid, mm/rev.
double node_infeed_step_mm_rev();

}  // namespace tnv::hil
