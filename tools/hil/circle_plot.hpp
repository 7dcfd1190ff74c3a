#pragma once
// The S1 figures a person wants to see: the polar plot with 99.8% of the
// radius suppressed (so the target circle is drawn at 0.2% of R: 12 um for
// R = 6 mm) and the contour error against time, one row per run.
#include <string>
#include <string_view>
#include <vector>

#include "tools/hil/circle_run.hpp"
#include "tools/hil/svg_writer.hpp"

namespace tnv::hil {

struct PlotRow {
  std::string label;  // e.g. "rdvsc"
  ContourStats stats{};
  const std::vector<TraceSample>* trace = nullptr;
};

SvgWriter circle_figure(std::string_view title, double radius_mm, const std::vector<PlotRow>& rows);

}  // namespace tnv::hil
