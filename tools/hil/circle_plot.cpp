#include "tools/hil/circle_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tools/hil/plot_format.hpp"

namespace tnv::hil {

namespace {

constexpr double kWidthPx = 1120.0;
constexpr double kTitlePx = 46.0;
constexpr double kRowPx = 380.0;
constexpr double kPolarRadiusPx = 160.0;
constexpr double kSuppressed = 0.998;  // fraction of the radius removed in the polar plot

constexpr const char* kColors[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e"};

// 1, 2 or 5 times a power of ten, at least v.
double nice_ceiling(double v) { return v > 0.0 ? nice_step(v, 1) : 1.0; }

void polar_panel(SvgWriter& svg, double cx, double cy, double radius_mm, const std::vector<TraceSample>& trace,
                 const char* color) {
  const double target_um = (1.0 - kSuppressed) * radius_mm * 1000.0;  // where r = R lands
  const double px_per_um = kPolarRadiusPx / (2.0 * target_um);
  const double ring_step_um = target_um / 6.0;
  for (int k = -6; k <= 6; k += 2) {
    const double r_um = target_um + k * ring_step_um;
    if (r_um <= 0.0) continue;
    svg.circle(cx, cy, r_um * px_per_um, k == 0 ? "#444" : "#ddd", k == 0 ? 1.2 : 0.8, k == 0 ? "5,3" : "");
    if (k != 0) svg.text(cx + 3, cy - r_um * px_per_um + 11, format_value("%+.0f um", k * ring_step_um), 9, "start", "#999");
  }
  svg.line(cx - kPolarRadiusPx, cy, cx + kPolarRadiusPx, cy, "#ccc", 0.6);
  svg.line(cx, cy - kPolarRadiusPx, cx, cy + kPolarRadiusPx, "#ccc", 0.6);
  std::vector<std::pair<double, double>> pts;
  pts.reserve(trace.size());
  for (const TraceSample& t : trace) {
    const double r_mm = std::hypot(t.position_mm[0], t.position_mm[1]);
    const double theta = std::atan2(t.position_mm[1], t.position_mm[0]);
    const double r_px = std::max(0.0, (r_mm - kSuppressed * radius_mm) * 1000.0 * px_per_um);
    pts.emplace_back(cx + r_px * std::cos(theta), cy - r_px * std::sin(theta));
  }
  svg.polyline(pts, color, 0.9);
}

void time_panel(SvgWriter& svg, double x0, double y0, double w, double h, const std::vector<TraceSample>& trace,
                double y_max_um, const char* color) {
  svg.rect(x0, y0, w, h, "#888");
  const double t_end = trace.empty() ? 1.0 : std::max(trace.back().t_s, 1e-3);
  for (int i = 0; i <= 5; ++i) {
    const double y = y0 + h - h * i / 5.0;
    svg.line(x0, y, x0 + w, y, "#eee", 0.6);
    svg.text(x0 - 6, y + 4, format_value("%.2g", y_max_um * i / 5.0), 10, "end", "#555");
  }
  const double t_step = nice_ceiling(t_end / 8.0);
  for (double t = 0.0; t <= t_end + 1e-9; t += t_step) {
    const double x = x0 + w * t / t_end;
    svg.line(x, y0, x, y0 + h, "#eee", 0.6);
    svg.text(x, y0 + h + 14, format_value("%g", t), 10, "middle", "#555");
  }
  svg.text(x0 + w / 2, y0 + h + 30, "time since start of motion (s)", 11, "middle", "#333");
  svg.text(x0 - 40, y0 + h / 2, "contour error (um)", 11, "middle", "#333", -90);
  // Min/max envelope per pixel column: every peak stays visible.
  const int columns = static_cast<int>(w);
  std::vector<double> lo(static_cast<std::size_t>(columns), 1e300), hi(static_cast<std::size_t>(columns), -1.0);
  for (const TraceSample& t : trace) {
    const int c = std::clamp(static_cast<int>(t.t_s / t_end * (columns - 1)), 0, columns - 1);
    lo[static_cast<std::size_t>(c)] = std::min(lo[static_cast<std::size_t>(c)], t.contour_um);
    hi[static_cast<std::size_t>(c)] = std::max(hi[static_cast<std::size_t>(c)], t.contour_um);
  }
  std::vector<std::pair<double, double>> pts;
  for (int c = 0; c < columns; ++c) {
    const auto i = static_cast<std::size_t>(c);
    if (hi[i] < 0.0) continue;
    const auto y_of = [&](double v) { return y0 + h - h * std::min(v, y_max_um) / y_max_um; };
    pts.emplace_back(x0 + c, y_of(lo[i]));
    pts.emplace_back(x0 + c, y_of(hi[i]));
  }
  svg.polyline(pts, color, 0.8);
}

}  // namespace

SvgWriter circle_figure(std::string_view title, double radius_mm, const std::vector<PlotRow>& rows) {
  SvgWriter svg(kWidthPx, kTitlePx + kRowPx * static_cast<double>(std::max<std::size_t>(rows.size(), 1)));
  svg.text(kWidthPx / 2, 28, title, 18, "middle", "#111");
  double y_max = 0.0;
  for (const PlotRow& row : rows)
    if (row.trace)
      for (const TraceSample& t : *row.trace) y_max = std::max(y_max, t.contour_um);
  y_max = nice_ceiling(y_max * 1.05);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const PlotRow& row = rows[i];
    const char* color = kColors[i % std::size(kColors)];
    const double top = kTitlePx + kRowPx * static_cast<double>(i);
    const double cx = 30 + kPolarRadiusPx;
    const double cy = top + 20 + kPolarRadiusPx;
    svg.text(20, top + 14, row.label, 14, "start", color);
    if (row.trace) {
      polar_panel(svg, cx, cy, radius_mm, *row.trace, color);
      time_panel(svg, 450, top + 20, 640, 300, *row.trace, y_max, color);
    }
    char stats[160];
    std::snprintf(stats, sizeof stats, "%s: max %.3f um   mean %.3f um   std %.3f um", row.label.c_str(),
                  row.stats.max_um, row.stats.mean_um, row.stats.std_um);
    svg.text(770, top + 14, stats, 12, "middle", "#222");
  }
  return svg;
}

}  // namespace tnv::hil
