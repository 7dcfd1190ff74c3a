#pragma once
// Plots of a capture, in the house style of tools/hil/circle_plot.cpp: a
// circle capture (motion_tick, contour, ref_x/y, pos_x/y) is drawn as the
// tnv-hil circle figure (polar plot with 99.8% of R suppressed, contour
// error against time); anything else as one time panel per channel.
#include <string>
#include <vector>

#include "tools/can/capture_table.hpp"
#include "tools/hil/svg_writer.hpp"

namespace tnv::can_host {

struct LabelledCapture {
  std::string label;
  const CaptureTable* table = nullptr;
};

// True when the capture holds what the circle figure needs.
bool is_circle_capture(const CaptureTable& table);

hil::SvgWriter capture_figure(const std::string& title, const std::string& label, const CaptureTable& table);

// Several circle captures, one row each, on a common contour-error scale
// (for before/after comparisons). Rows that are not circle captures are skipped.
hil::SvgWriter circle_comparison_figure(const std::string& title, const std::vector<LabelledCapture>& rows);

// One panel per channel against time since the first sample.
hil::SvgWriter channel_figure(const std::string& title, const CaptureTable& table);

}  // namespace tnv::can_host
