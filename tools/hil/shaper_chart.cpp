#include "tools/hil/shaper_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace tnv::hil {

namespace {

std::string fmt(double v) {
  char buf[32];
  if (v != 0.0 && (std::fabs(v) < 1e-3 || std::fabs(v) >= 1e5))
    std::snprintf(buf, sizeof buf, "%.0e", v);
  else
    std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// About `count` round tick values covering [lo, hi].
std::vector<double> linear_ticks(double lo, double hi, int count) {
  const double step = chart_nice_ceiling((hi - lo) / count);
  std::vector<double> out;
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step)
    out.push_back(std::fabs(t) < 1e-12 * step ? 0.0 : t);
  return out;
}

}  // namespace

double chart_nice_ceiling(double v) {
  if (!(v > 0.0)) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= v * (1.0 - 1e-12)) return m * p;
  return 10.0 * p;
}

void draw_chart(SvgWriter& svg, const ChartPanel& p, const std::vector<ChartSeries>& series) {
  const auto y_unit = [&](double y) {
    if (p.log_y)
      return (std::log10(std::max(y, p.y_min)) - std::log10(p.y_min)) / (std::log10(p.y_max) - std::log10(p.y_min));
    return (y - p.y_min) / (p.y_max - p.y_min);
  };
  const auto X = [&](double x) { return p.x_px + p.w_px * std::clamp((x - p.x_min) / (p.x_max - p.x_min), 0.0, 1.0); };
  const auto Y = [&](double y) { return p.y_px + p.h_px * (1.0 - std::clamp(y_unit(y), 0.0, 1.0)); };

  // grid and ticks
  std::vector<double> y_ticks;
  if (p.log_y) {
    for (double d = std::ceil(std::log10(p.y_min) - 1e-9); d <= std::log10(p.y_max) + 1e-9; d += 1.0)
      y_ticks.push_back(std::pow(10.0, d));
  } else {
    y_ticks = linear_ticks(p.y_min, p.y_max, 5);
  }
  for (double t : y_ticks) {
    svg.line(p.x_px, Y(t), p.x_px + p.w_px, Y(t), "#e6e6e6", 0.7);
    svg.text(p.x_px - 6, Y(t) + 4, fmt(t), 10, "end", "#555");
  }
  for (double t : linear_ticks(p.x_min, p.x_max, 8)) {
    svg.line(X(t), p.y_px, X(t), p.y_px + p.h_px, "#e6e6e6", 0.7);
    svg.text(X(t), p.y_px + p.h_px + 14, fmt(t), 10, "middle", "#555");
  }
  for (const auto& [value, label] : p.y_marks) {
    svg.line(p.x_px, Y(value), p.x_px + p.w_px, Y(value), "#888", 1.0, "6,4");
    svg.text(p.x_px + p.w_px - 4, Y(value) - 4, label, 10, "end", "#666");
  }
  svg.rect(p.x_px, p.y_px, p.w_px, p.h_px, "#999");
  svg.text(p.x_px + p.w_px / 2, p.y_px - 8, p.title, 13, "middle", "#222");
  svg.text(p.x_px + p.w_px / 2, p.y_px + p.h_px + 32, p.x_label, 11, "middle", "#333");
  svg.text(p.x_px - 44, p.y_px + p.h_px / 2, p.y_label, 11, "middle", "#333", -90);

  for (const ChartSeries& s : series) {
    std::vector<std::pair<double, double>> pts;
    const auto flush = [&] {
      if (pts.size() > 1) svg.polyline(pts, s.color, s.width);
      pts.clear();
    };
    for (const auto& [x, y] : s.points) {
      const double tol = 1e-9 * (p.y_max - p.y_min);
      const bool inside = std::isfinite(x) && std::isfinite(y) && x >= p.x_min && x <= p.x_max && y >= p.y_min - tol &&
                          y <= p.y_max + tol;
      if (inside) {
        pts.emplace_back(X(x), Y(y));
      } else {
        flush();
      }
    }
    flush();
  }
  // legend
  if (p.legend_below) {
    double lx = p.x_px, ly = p.y_px + p.h_px + 52;
    for (const ChartSeries& s : series) {
      if (s.label.empty()) continue;
      const double w = 40 + 6.2 * static_cast<double>(s.label.size());
      if (lx > p.x_px && lx + w > p.x_px + p.w_px) {  // wrap
        lx = p.x_px;
        ly += 16;
      }
      svg.line(lx, ly - 4, lx + 22, ly - 4, s.color, std::max(2.0, s.width));
      svg.text(lx + 28, ly, s.label, 11, "start", "#222");
      lx += w;
    }
    return;
  }
  double ly = p.y_px + 16;
  const double lx = p.x_px + 12 + std::clamp(p.legend_at, 0.0, 1.0) * (p.w_px - 190);
  for (const ChartSeries& s : series) {
    if (s.label.empty()) continue;
    svg.line(lx, ly - 4, lx + 22, ly - 4, s.color, std::max(2.0, s.width));
    svg.text(lx + 28, ly, s.label, 11, "start", "#222");
    ly += 16;
  }
}

}  // namespace tnv::hil
