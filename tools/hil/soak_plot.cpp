#include "tools/hil/soak_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "tools/hil/plot_format.hpp"

namespace tnv::hil {

namespace {

constexpr double kWidthPx = 1120.0;
constexpr double kLeftPx = 90.0;
constexpr double kPlotWidthPx = 900.0;
constexpr double kTitlePx = 70.0;
constexpr double kPanelPx = 200.0;
constexpr double kGapPx = 60.0;
constexpr const char* kWrapColor = "#7b3fa0";

struct Series {
  std::string label;
  std::string color;
  std::function<double(const SoakCycle&)> value;
  bool joined = true;  // false: dots only (values that jump between two states)
};

// One panel: simulated time in minutes across, one linear value axis up.
class Panel {
 public:
  Panel(SvgWriter& svg, double top, double t_end_min, double lo, double hi)
      : svg_(svg), top_(top), t_end_min_(t_end_min), lo_(lo), hi_(hi) {}

  double x(double t_min) const { return kLeftPx + kPlotWidthPx * t_min / t_end_min_; }
  double y(double v) const { return top_ + kPanelPx - kPanelPx * std::clamp((v - lo_) / (hi_ - lo_), -0.02, 1.02); }

  void frame(std::string_view y_label, const std::vector<double>& wraps_s) const {
    svg_.rect(kLeftPx, top_, kPlotWidthPx, kPanelPx, "#888");
    const double step = nice_step(hi_ - lo_, 5);
    for (double v = std::ceil(lo_ / step) * step; v <= hi_ + 1e-12; v += step) {
      svg_.line(kLeftPx, y(v), kLeftPx + kPlotWidthPx, y(v), "#eee", 0.6);
      svg_.text(kLeftPx - 6, y(v) + 4, format_value("%g", std::fabs(v) < 1e-12 ? 0.0 : v), 10, "end", "#555");
    }
    const double t_step = nice_step(t_end_min_, 10);
    for (double t = 0.0; t <= t_end_min_ + 1e-9; t += t_step) {
      svg_.line(x(t), top_ + kPanelPx, x(t), top_ + kPanelPx + 4, "#888", 0.8);
      svg_.text(x(t), top_ + kPanelPx + 15, format_value("%g", t), 10, "middle", "#555");
    }
    for (double w : wraps_s) svg_.line(x(w / 60.0), top_, x(w / 60.0), top_ + kPanelPx, kWrapColor, 1.0, "4,3");
    svg_.text(kLeftPx - 58, top_ + kPanelPx / 2, y_label, 11, "middle", "#333", -90);
  }

  void plot(const std::vector<SoakCycle>& cycles, const Series& s) const {
    std::vector<std::pair<double, double>> pts;
    pts.reserve(cycles.size());
    for (const SoakCycle& c : cycles) pts.emplace_back(x(c.start_s / 60.0), y(s.value(c)));
    if (s.joined) svg_.polyline(pts, s.color, 1.3);
    if (cycles.size() <= 200 || !s.joined)
      for (const auto& [px, py] : pts) svg_.circle(px, py, s.joined ? 1.2 : 1.6, s.color, s.joined ? 2.4 : 3.2);
  }

  void legend(const std::vector<Series>& series, bool with_wrap) const {
    double lx = kLeftPx;
    for (const Series& s : series) {
      if (s.joined) {
        svg_.line(lx, top_ - 9, lx + 22, top_ - 9, s.color, 2.0);
      } else {
        svg_.circle(lx + 11, top_ - 9, 1.6, s.color, 3.2);
      }
      svg_.text(lx + 27, top_ - 5, s.label, 11, "start", "#333");
      lx += 44.0 + 6.3 * static_cast<double>(s.label.size());
    }
    if (with_wrap) {
      svg_.line(lx, top_ - 9, lx + 22, top_ - 9, kWrapColor, 1.0, "4,3");
      svg_.text(lx + 27, top_ - 5, "32-bit clock wrap", 11, "start", "#333");
    }
  }

 private:
  SvgWriter& svg_;
  double top_;
  double t_end_min_;
  double lo_;
  double hi_;
};

// A symmetric or zero-based range with head room, on a nice step.
std::pair<double, double> value_range(const std::vector<SoakCycle>& cycles, const std::vector<Series>& series) {
  double lo = 0.0, hi = 0.0;
  for (const SoakCycle& c : cycles)
    for (const Series& s : series) {
      lo = std::min(lo, s.value(c));
      hi = std::max(hi, s.value(c));
    }
  if (hi - lo <= 0.0) hi = lo + 1.0;
  const double pad = 0.15 * (hi - lo);
  const double step = nice_step(hi - lo + 2.0 * pad, 5);
  return {lo < 0.0 ? std::floor((lo - pad) / step) * step : 0.0, std::ceil((hi + pad) / step) * step};
}

}  // namespace

SvgWriter soak_figure(const SoakResult& r, std::string_view scenario_name) {
  const double height = kTitlePx + 3 * (kPanelPx + kGapPx) + 20;
  SvgWriter svg(kWidthPx, height);
  char title[200];
  std::snprintf(title, sizeof title, "Soak: %.2f h simulated, %zu cycles of the S1 circle + rest + 4 jogs (%.*s)",
                r.simulated_s / 3600.0, r.cycles.size(), static_cast<int>(scenario_name.size()), scenario_name.data());
  svg.text(kWidthPx / 2, 26, title, 17, "middle", "#111");
  char sub[300];
  std::snprintf(sub, sizeof sub,
                "missed ticks %llu, late %llu; %u clock wraps; encoder count drift %lld counts; stationary: %s",
                static_cast<unsigned long long>(r.counters.missed_ticks),
                static_cast<unsigned long long>(r.counters.late_ticks), r.clock_wraps,
                static_cast<long long>(r.max_encoder_drift_counts), r.stationary ? "yes" : "NO");
  svg.text(kWidthPx / 2, 48, sub, 12, "middle", "#444");
  const double t_end_min = std::max(r.simulated_s / 60.0, 1e-3);

  double top = kTitlePx + 24;
  const std::vector<Series> contour = {
      {"max contour error", "#d62728", [](const SoakCycle& c) { return c.circle.max_um; }},
      {"mean", "#1f77b4", [](const SoakCycle& c) { return c.circle.mean_um; }},
      {"std", "#2ca02c", [](const SoakCycle& c) { return c.circle.std_um; }}};
  auto [lo, hi] = value_range(r.cycles, contour);
  Panel p1(svg, top, t_end_min, lo, hi);
  p1.frame("contour error per circle (um)", r.clock_wrap_s);
  for (const Series& s : contour) p1.plot(r.cycles, s);
  p1.legend(contour, true);

  top += kPanelPx + kGapPx;
  const std::vector<Series> rest = {
      {"X reference - position at rest", "#1f77b4", [](const SoakCycle& c) { return c.rest_error_um[0]; }, false},
      {"Y", "#ff7f0e", [](const SoakCycle& c) { return c.rest_error_um[1]; }, false}};
  std::tie(lo, hi) = value_range(r.cycles, rest);
  Panel p2(svg, top, t_end_min, lo, hi);
  p2.frame("position error at rest (um)", r.clock_wrap_s);
  for (const Series& s : rest) p2.plot(r.cycles, s);
  p2.legend(rest, false);
  svg.text(kLeftPx + kPlotWidthPx - 6, top + 14, "one encoder count = 0.417 um", 10, "end", "#555");

  top += kPanelPx + kGapPx;
  const std::vector<Series> d_hat = {
      {"X d_hat at rest", "#1f77b4", [](const SoakCycle& c) { return c.rest_d_hat_mm_s[0]; }, false},
      {"Y d_hat at rest", "#ff7f0e", [](const SoakCycle& c) { return c.rest_d_hat_mm_s[1]; }, false},
      {"max |d_hat| X, whole cycle", "#9ecae1", [](const SoakCycle& c) { return c.max_abs_d_hat_mm_s[0]; }},
      {"Y", "#fdd0a2", [](const SoakCycle& c) { return c.max_abs_d_hat_mm_s[1]; }}};
  std::tie(lo, hi) = value_range(r.cycles, d_hat);
  Panel p3(svg, top, t_end_min, lo, hi);
  p3.frame("DDC estimate d_hat (mm/s)", r.clock_wrap_s);
  for (const Series& s : d_hat) p3.plot(r.cycles, s);
  p3.legend(d_hat, false);
  svg.text(kLeftPx + kPlotWidthPx - 6, top + 14,
           "at rest d_hat holds the stiction on whichever side the table stopped", 10, "end", "#555");
  svg.text(kLeftPx + kPlotWidthPx / 2, top + kPanelPx + 36, "simulated time (min); one point per cycle, at its start",
           12, "middle", "#333");
  return svg;
}

}  // namespace tnv::hil
