#pragma once
// The data of the host figures, as JSON for the plotting package
// (tools/plot/tnvplot): "circle" rows for the S1 figure, "panels" (stacked
// panels of named series) for everything else. Layout, units on the axes,
// decimation and clipping are the plotter's; here only what is drawn.
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "firmware/shaper/shaper_design.hpp"
#include "tools/hil/arsc_run.hpp"
#include "tools/hil/arsc_tick_study.hpp"
#include "tools/hil/boring_sweep.hpp"
#include "tools/hil/circle_run.hpp"
#include "tools/hil/shaper_jog_run.hpp"
#include "tools/hil/shaper_move_compare.hpp"
#include "tools/hil/soak_run.hpp"

namespace tnv::hil {

struct PlotRow {
  std::string label;  // e.g. "rdvsc"
  ContourStats stats{};
  const std::vector<TraceSample>* trace = nullptr;
};

// The S1 figure: per row the polar plot (99.8% of R suppressed) and the contour error against time.
nlohmann::json circle_plot_data(std::string_view title, double radius_mm, const std::vector<PlotRow>& rows);

// S3: one reproduction run; faithful vs robust for the four pole sets; the machine study.
nlohmann::json arsc_run_plot_data(const ArscRunResult& run);
nlohmann::json arsc_compare_plot_data(const std::vector<ArscRunResult>& faithful, const std::vector<ArscRunResult>& robust);
nlohmann::json arsc_tick_plot_data(const std::vector<TickStudyResult>& runs);

// S4: seed 1 part by part, and the share of seeds with a bad part or a reset per part.
nlohmann::json boring_plot_data(std::string_view title, const BoringRunRequest& request, const BoringSweepResult& result);

// Per-cycle contour statistics, rest error and d_hat over the soak, with the clock wraps.
nlohmann::json soak_plot_data(const SoakResult& result, std::string_view scenario_name);

// Input shaper: sensitivity curves, residual by grid method, move and jog traces.
nlohmann::json shaper_sensitivity_plot_data(const fw::ShaperSpec& spec);
nlohmann::json grid_method_plot_data(const std::vector<fw::ShaperType>& types, double zeta);
nlohmann::json move_plot_data(const std::string& title, const MoveComparison& comparison);
nlohmann::json jog_plot_data(const std::string& title, const JogRunResult& unshaped, const JogRunResult& shaped);

// One series of a "panels" figure: style "line", "dashed", "reference", "steps", "dots", "rings" or "bars".
nlohmann::json plot_series(const std::string& label, std::vector<double> x, std::vector<double> y,
                           const char* style = "line", const char* color = nullptr);

}  // namespace tnv::hil
