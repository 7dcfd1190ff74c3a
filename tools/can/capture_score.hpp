#pragma once
// A circle scored from a capture, the way tnv-hil scores it from tick
// records (tools/hil/circle_run.cpp): every sample with motion_tick >= 0
// goes through hil::ContourAccumulator. The contour value is the node's
// own S1 eq. (33) (channel "contour", float32 um) when captured, else it is
// computed from the captured reference and position.
#include <optional>
#include <string>
#include <vector>

#include "tools/can/capture_table.hpp"
#include "tools/score/circle_trace.hpp"
#include "tools/score/contour_stats.hpp"

namespace tnv::can_host {

// nullopt with `error` when the capture cannot score a circle (no
// motion_tick, neither contour nor ref/pos, or no sample in motion).
std::optional<hil::ContourStats> score_circle(const CaptureTable& table, std::string& error);

// The samples in motion as tnv-hil trace samples (t_s from motion_tick;
// reference/position when captured; contour), for hil::circle_figure.
std::vector<hil::TraceSample> circle_trace(const CaptureTable& table);

// The circle radius the reference runs on (its distance from the centre
// at the first sample in motion); 0 when ref_x / ref_y were not captured.
double reference_radius_mm(const CaptureTable& table);

}  // namespace tnv::can_host
