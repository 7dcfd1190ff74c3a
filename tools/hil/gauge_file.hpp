#pragma once
// A lead-error measurement as a file: what a laser interferometer (or a
// gauge against a table-side reference) reads at each stop of a
// forward-and-back run, beside where the machine's own encoder put the
// axis. The format (CSV, '#' comments, the header line required):
//
//   # x axis, bench-no-cut, laser zeroed at the first point
//   position_mm,direction,table_mm
//   -20.000000,1,-20.000000
//   -19.375000,1,-19.374712
//   ...
//
// position_mm: the axis' position as the control reads it (motor encoder);
// direction: +1 or -1, the direction the axis came from; table_mm: the
// reference's reading of the table (any zero: a constant offset is fitted).
#include <optional>
#include <string>
#include <vector>

#include "tools/tune/gauge_point.hpp"

namespace tnv::hil {

using tune::GaugePoint;

std::string write_gauge_file(const std::string& comment, const std::vector<GaugePoint>& points);

// nullopt with `error` ("line N: why") for a missing header, a wrong column
// count, a value that is not a finite number, a direction other than +1 or
// -1, or no points.
std::optional<std::vector<GaugePoint>> read_gauge_file(const std::string& text, std::string& error);

}  // namespace tnv::hil
