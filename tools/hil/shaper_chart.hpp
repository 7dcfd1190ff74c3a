#pragma once
// A small line-chart panel for the shaper figures: axes, grid, ticks,
// labels, a legend, and series drawn only inside the panel (a curve that
// leaves it is broken there, not flattened against the border).
#include <string>
#include <utility>
#include <vector>

#include "tools/hil/svg_writer.hpp"

namespace tnv::hil {

struct ChartSeries {
  std::vector<std::pair<double, double>> points;
  std::string color = "#1f77b4";
  double width = 1.5;
  std::string label;  // empty: not in the legend
};

struct ChartPanel {
  double x_px = 0.0, y_px = 0.0, w_px = 400.0, h_px = 300.0;
  double x_min = 0.0, x_max = 1.0, y_min = 0.0, y_max = 1.0;
  bool log_y = false;  // y_min > 0 required
  std::string title, x_label, y_label;
  std::vector<std::pair<double, std::string>> y_marks;  // horizontal reference lines (value, label)
  double legend_at = 1.0;     // legend inside the panel: 0 left edge, 0.5 centre, 1 right edge
  bool legend_below = false;  // one row under the x label instead of inside the panel
};

void draw_chart(SvgWriter& svg, const ChartPanel& panel, const std::vector<ChartSeries>& series);

// 1, 2 or 5 times a power of ten, at least v.
double chart_nice_ceiling(double v);

}  // namespace tnv::hil
