#include "tools/hil/path_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "tools/gcode/path_distance.hpp"
#include "tools/hil/plot_format.hpp"

namespace tnv::hil {

namespace {

constexpr double kWidthPx = 1120.0;
constexpr double kLeftPx = 90.0;
constexpr double kPlotWidthPx = 940.0;
constexpr double kTitlePx = 60.0;
constexpr double kMapPx = 420.0;   // the XY panel's side
constexpr double kPanelPx = 170.0;
constexpr double kGapPx = 60.0;
constexpr const char* kProgramColor = "#9a9a9a";
constexpr const char* kErrorColor = "#c0392b";
constexpr const char* kSpeedColor = "#1f5fa8";

// A time panel: seconds across, one linear value axis up; values outside
// the range are clipped to the frame, never dropped.
class TimePanel {
 public:
  TimePanel(SvgWriter& svg, double top, double t_end_s, double hi)
      : svg_(svg), top_(top), t_end_s_(t_end_s), hi_(hi) {}
  double x(double t_s) const { return kLeftPx + kPlotWidthPx * std::clamp(t_s / t_end_s_, 0.0, 1.0); }
  double y(double v) const { return top_ + kPanelPx - kPanelPx * std::clamp(v / hi_, 0.0, 1.0); }
  void frame(const std::string& y_label) const {
    svg_.rect(kLeftPx, top_, kPlotWidthPx, kPanelPx, "#888");
    const double step = nice_step(hi_, 5);
    for (double v = 0.0; v <= hi_ + 1e-12; v += step) {
      svg_.line(kLeftPx, y(v), kLeftPx + kPlotWidthPx, y(v), "#eee", 0.6);
      svg_.text(kLeftPx - 6, y(v) + 4, format_value("%g", v), 12, "end", "#555");
    }
    const double t_step = nice_step(t_end_s_, 10);
    for (double t = 0.0; t <= t_end_s_ + 1e-9; t += t_step) {
      svg_.line(x(t), top_ + kPanelPx, x(t), top_ + kPanelPx + 4, "#888", 0.8);
      svg_.text(x(t), top_ + kPanelPx + 16, format_value("%g", t), 12, "middle", "#555");
    }
    svg_.text(kLeftPx + kPlotWidthPx / 2, top_ + kPanelPx + 34, "time (s)", 12, "middle", "#333");
    svg_.text(kLeftPx - 60, top_ + kPanelPx / 2, y_label, 13, "middle", "#333", -90);
  }
  // Min and max per pixel column, so a long trace keeps its peaks without a solid band of points.
  void trace(const std::vector<double>& values, double dt_s, const char* color) const {
    const auto columns = static_cast<std::size_t>(kPlotWidthPx);
    std::vector<double> lo(columns, 1e300), hi(columns, -1e300);
    for (std::size_t k = 0; k < values.size(); ++k) {
      const auto c = std::min(columns - 1, static_cast<std::size_t>((x(static_cast<double>(k) * dt_s) - kLeftPx)));
      lo[c] = std::min(lo[c], values[k]);
      hi[c] = std::max(hi[c], values[k]);
    }
    std::vector<std::pair<double, double>> pts;
    for (std::size_t c = 0; c < columns; ++c) {
      if (lo[c] > hi[c]) continue;
      pts.emplace_back(kLeftPx + static_cast<double>(c), y(lo[c]));
      if (hi[c] != lo[c]) pts.emplace_back(kLeftPx + static_cast<double>(c), y(hi[c]));
    }
    svg_.polyline(pts, color, 1.0);
  }

 private:
  SvgWriter& svg_;
  double top_;
  double t_end_s_;
  double hi_;
};

}  // namespace

SvgWriter path_figure(const std::string& title, const gcode::GcodeProgram& program, const PathRunResult& run) {
  const double height = kTitlePx + kMapPx + 2.0 * (kPanelPx + kGapPx) + 60.0;
  SvgWriter svg(kWidthPx, height);
  svg.text(kWidthPx / 2, 28, title, 17, "middle", "#111");
  const PathScore& s = run.score;
  svg.text(kWidthPx / 2, 48,
           format_value("contour error max %.3f \u00b5m", s.contour_error_max_um) +
               format_value(", mean %.3f \u00b5m", s.contour_error_mean_um) +
               format_value("; feed ratio %.3f", s.feed_ratio) + format_value(", cycle %.2f s", s.cycle_time_s),
           13, "middle", "#333");

  // XY panel: the program to scale, and the samples in the worst tenth of the contour error.
  const std::vector<PathSample>& samples = run.samples;
  double x_lo = 1e300, x_hi = -1e300, y_lo = 1e300, y_hi = -1e300;
  std::vector<std::vector<std::pair<double, double>>> elements;
  for (const fw::motion::SegmentGeometry& g : program.geometry) {
    if (g.kind == fw::motion::SegmentKind::dwell) continue;
    std::vector<std::pair<double, double>> pts;
    const int n = g.kind == fw::motion::SegmentKind::line ? 1 : 96;
    for (int i = 0; i <= n; ++i) {
      const fw::motion::PlanePoint p = g.point_at(g.length_mm * i / n);
      pts.emplace_back(p[0], p[1]);
      x_lo = std::min(x_lo, p[0]), x_hi = std::max(x_hi, p[0]);
      y_lo = std::min(y_lo, p[1]), y_hi = std::max(y_hi, p[1]);
    }
    elements.push_back(std::move(pts));
  }
  const double span = std::max({x_hi - x_lo, y_hi - y_lo, 1e-3});
  const double scale = 0.9 * kMapPx / span;
  const double cx = 0.5 * (x_lo + x_hi), cy = 0.5 * (y_lo + y_hi);
  const double map_left = kLeftPx + (kPlotWidthPx - kMapPx) / 2, map_top = kTitlePx + 10;
  const auto px = [&](double x) { return map_left + kMapPx / 2 + (x - cx) * scale; };
  const auto py = [&](double y) { return map_top + kMapPx / 2 - (y - cy) * scale; };
  svg.rect(map_left, map_top, kMapPx, kMapPx, "#888");
  for (const auto& e : elements) {
    std::vector<std::pair<double, double>> mapped;
    for (const auto& [x, y] : e) mapped.emplace_back(px(x), py(y));
    svg.polyline(mapped, kProgramColor, 1.4);
  }
  const gcode::ProgrammedPath path(program.geometry);
  std::vector<double> contour_um;
  const std::size_t first = std::min(s.window_begin, samples.size());
  for (std::size_t k = first; k < samples.size(); ++k) contour_um.push_back(path.distance_mm(samples[k].position_mm) * 1e3);
  const double worst = s.contour_error_max_um;
  for (std::size_t k = 0; k < contour_um.size(); ++k)
    if (worst > 0.0 && contour_um[k] >= 0.9 * worst)
      svg.circle(px(samples[first + k].position_mm[0]), py(samples[first + k].position_mm[1]), 3.0, kErrorColor, 1.5);
  svg.text(map_left, map_top + kMapPx + 18,
           format_value("programmed path (grey, %.0f mm across); red: contour error within 10 %% of its maximum", span),
           12, "start", "#333");

  const double t_end = std::max(1e-3, static_cast<double>(contour_um.size()) * 1e-3);
  double top = kTitlePx + kMapPx + kGapPx;
  TimePanel err(svg, top, t_end, nice_step(std::max(worst, 1e-3) * 1.1, 5) * 5);
  err.frame("contour error (\u00b5m)");
  err.trace(contour_um, 1e-3, kErrorColor);
  top += kPanelPx + kGapPx;
  std::vector<double> speed;
  for (std::size_t k = first; k < run.path_speed_mm_s.size(); ++k) speed.push_back(run.path_speed_mm_s[k]);
  double v_max = 1e-3;
  for (double v : speed) v_max = std::max(v_max, v);
  TimePanel spd(svg, top, t_end, nice_step(v_max * 1.1, 5) * 5);
  spd.frame("path speed (mm/s)");
  spd.trace(speed, 1e-3, kSpeedColor);
  return svg;
}

std::string path_csv(const gcode::GcodeProgram& program, const PathRunResult& run) {
  const gcode::ProgrammedPath path(program.geometry);
  std::string out = "t_s,x_ref_mm,y_ref_mm,x_mm,y_mm,contour_um,path_speed_mm_s\n";
  char line[256];
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    const PathSample& s = run.samples[k];
    const double speed = k > 0 && k - 1 < run.path_speed_mm_s.size() ? run.path_speed_mm_s[k - 1] : 0.0;
    std::snprintf(line, sizeof line, "%.3f,%.9f,%.9f,%.9f,%.9f,%.5f,%.6f\n", static_cast<double>(k) * 1e-3,
                  s.reference_mm[0], s.reference_mm[1], s.position_mm[0], s.position_mm[1],
                  path.distance_mm(s.position_mm) * 1e3, speed);
    out += line;
  }
  return out;
}

}  // namespace tnv::hil
