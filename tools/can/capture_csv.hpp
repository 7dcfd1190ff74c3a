#pragma once
// A capture as CSV: "t_s" (since the first sample) then one column per
// channel with its unit in the name (pos_x_mm, contour_um, motion_tick).
// Values print exactly: positions to the nm, float32 channels with 9
// significant digits, integers whole. read_capture_csv() reads it back
// (for comparison plots).
#include <optional>
#include <string>

#include "tools/can/capture_table.hpp"

namespace tnv::can_host {

std::string capture_csv(const CaptureTable& table);

// nullopt with `error` (line number and what is wrong) for anything that
// is not a capture_csv() file.
std::optional<CaptureTable> read_capture_csv(const std::string& text, std::string& error);

}  // namespace tnv::can_host
