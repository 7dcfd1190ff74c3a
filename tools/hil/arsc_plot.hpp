#pragma once
// Time-series figures for the S3 reproduction: stacked panels with a
// shared time axis (force with the +-10% band, feed and depth, input,
// gains, estimates). Values outside a panel's range are clipped to its
// edge and the panel says so.
#include <string>
#include <string_view>
#include <vector>

#include "tools/hil/arsc_run.hpp"
#include "tools/hil/arsc_tick_study.hpp"
#include "tools/hil/svg_writer.hpp"

namespace tnv::hil {

struct Series {
  std::string label;
  std::vector<double> t_s;
  std::vector<double> value;
  std::string color;
  bool dashed = false;
};

struct Panel {
  std::string y_label;
  double y_min = 0.0, y_max = 1.0;
  std::vector<Series> series;
  double band_low = 0.0, band_high = 0.0;  // shaded band if band_high > band_low
};

SvgWriter panel_figure(std::string_view title, const std::vector<Panel>& panels, double t_end_s,
                       std::string_view x_label);

// One reproduction run: force, feed + depth, input, gains, estimates.
SvgWriter arsc_run_figure(const ArscRunResult& run);
// Faithful vs robust force for the four pole sets (8 runs).
SvgWriter arsc_compare_figure(const std::vector<ArscRunResult>& faithful, const std::vector<ArscRunResult>& robust);
// The machine study: force, force error, feed and cutting-gain estimate per configuration.
SvgWriter arsc_tick_figure(const std::vector<TickStudyResult>& runs);

}  // namespace tnv::hil
