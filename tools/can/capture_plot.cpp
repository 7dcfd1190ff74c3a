#include "tools/can/capture_plot.hpp"

#include <algorithm>
#include <cmath>
#include <string_view>

#include "tools/can/capture_score.hpp"
#include "tools/hil/circle_plot.hpp"
#include "tools/hil/plot_format.hpp"

namespace tnv::can_host {

namespace {

constexpr double kWidthPx = 1120.0;
constexpr double kTitlePx = 46.0;
constexpr double kPanelPx = 150.0;  // plot height
constexpr double kGapPx = 44.0;     // between panels (tick labels, then the next label line)
constexpr double kLeftPx = 90.0;
constexpr double kRightPx = 30.0;
constexpr double kBottomPx = 50.0;  // time axis labels

constexpr const char* kColors[] = {"#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b"};

std::string axis_label(const can::ChannelDef& c) {
  std::string out = c.name;
  if (c.unit[0] != '\0') out.append(" (").append(c.unit).append(")");
  return out;
}

struct Series {
  std::vector<double> values;
  const char* color;
  double width;
};

struct Panel {
  std::string label;  // top left, with the unit
  std::string doc;    // top right
  std::vector<Series> series;
};

// Every series of a panel on one scale: a min/max envelope per pixel
// column, so every peak stays visible.
void draw_panel(hil::SvgWriter& svg, double x0, double y0, double w, double h, const Panel& panel, double period_s,
                double t_end_s) {
  double lo = 1e300;
  double hi = -1e300;
  for (const Series& s : panel.series)
    for (double v : s.values) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (lo > hi) lo = hi = 0.0;
  if (hi - lo < 1e-12 * std::max(1.0, std::fabs(hi))) {  // flat: give it some room
    lo -= 1.0;
    hi += 1.0;
  }
  const double step = hil::nice_step(hi - lo, 4);
  lo = std::floor(lo / step) * step;
  hi = std::ceil(hi / step) * step;
  svg.rect(x0, y0, w, h, "#888");
  const auto y_of = [&](double v) { return y0 + h - h * (v - lo) / (hi - lo); };
  for (double v = lo; v <= hi + step * 1e-6; v += step) {
    const double y = y_of(v);
    svg.line(x0, y, x0 + w, y, "#eee", 0.6);
    svg.text(x0 - 6, y + 4, hil::format_value("%.6g", std::fabs(v) < step * 1e-6 ? 0.0 : v), 10, "end", "#555");
  }
  const double span_s = std::max(t_end_s, 1e-3);
  const double t_step = hil::nice_step(span_s, 8);
  for (double t = 0.0; t <= span_s + 1e-9; t += t_step) {
    const double x = x0 + w * t / span_s;
    svg.line(x, y0, x, y0 + h, "#eee", 0.6);
    svg.text(x, y0 + h + 14, hil::format_value("%g", t), 10, "middle", "#555");
  }
  const int columns = static_cast<int>(w);
  for (const Series& s : panel.series) {
    std::vector<double> col_lo(static_cast<std::size_t>(columns), 1e300);
    std::vector<double> col_hi(static_cast<std::size_t>(columns), -1e300);
    for (std::size_t i = 0; i < s.values.size(); ++i) {
      const double t = static_cast<double>(i) * period_s;
      const auto c = static_cast<std::size_t>(std::clamp(static_cast<int>(t / span_s * (columns - 1)), 0, columns - 1));
      col_lo[c] = std::min(col_lo[c], s.values[i]);
      col_hi[c] = std::max(col_hi[c], s.values[i]);
    }
    std::vector<std::pair<double, double>> pts;
    for (int c = 0; c < columns; ++c) {
      const auto i = static_cast<std::size_t>(c);
      if (col_hi[i] < col_lo[i]) continue;
      pts.emplace_back(x0 + c, y_of(col_lo[i]));
      if (col_hi[i] != col_lo[i]) pts.emplace_back(x0 + c, y_of(col_hi[i]));
    }
    svg.polyline(pts, s.color, s.width);
  }
}

// Reference and position of an axis share a panel, followed by their
// difference (the following error, what a tuner looks at); every other
// channel gets a panel of its own.
std::vector<Panel> panels_of(const CaptureTable& t) {
  std::vector<Panel> panels;
  std::vector<bool> used(t.channels.size(), false);
  const auto index_of = [&](const char* name) -> int {
    for (std::size_t i = 0; i < t.channels.size(); ++i)
      if (std::string_view(t.channels[i]->name) == name) return static_cast<int>(i);
    return -1;
  };
  std::size_t color = 0;
  for (const char* axis : {"x", "y"}) {
    const int ref = index_of(axis[0] == 'x' ? "ref_x" : "ref_y");
    const int pos = index_of(axis[0] == 'x' ? "pos_x" : "pos_y");
    if (ref < 0 || pos < 0) continue;
    used[static_cast<std::size_t>(ref)] = used[static_cast<std::size_t>(pos)] = true;
    const auto& r = t.columns[static_cast<std::size_t>(ref)];
    const auto& p = t.columns[static_cast<std::size_t>(pos)];
    const char* c = kColors[color++ % std::size(kColors)];
    Panel both;
    both.label = "ref_";
    both.label.append(axis).append(" (grey), pos_").append(axis).append(" (mm)");
    both.doc = "reference the loop follows and encoder position";
    both.series = {{r, "#9a9a9a", 2.4}, {p, c, 1.0}};
    panels.push_back(both);
    Panel error;
    error.label = "following error ";
    error.label.append(axis).append(" = ref - pos (um)");
    error.doc = "positive: the table lags";
    std::vector<double> e(r.size());
    for (std::size_t i = 0; i < r.size(); ++i) e[i] = (r[i] - p[i]) * 1000.0;
    error.series = {{e, c, 1.0}};
    panels.push_back(error);
  }
  for (std::size_t i = 0; i < t.channels.size(); ++i) {
    if (used[i]) continue;
    panels.push_back({axis_label(*t.channels[i]), t.channels[i]->doc, {{t.columns[i], kColors[color++ % std::size(kColors)], 1.0}}});
  }
  return panels;
}

}  // namespace

bool is_circle_capture(const CaptureTable& t) {
  return t.column("motion_tick") && t.column("ref_x") && t.column("ref_y") && t.column("pos_x") &&
         t.column("pos_y") && !circle_trace(t).empty();
}

hil::SvgWriter channel_figure(const std::string& title, const CaptureTable& table) {
  const std::vector<Panel> panels = panels_of(table);
  const std::size_t n = std::max<std::size_t>(panels.size(), 1);
  const double height = kTitlePx + static_cast<double>(n) * (kPanelPx + kGapPx) + kBottomPx;
  hil::SvgWriter svg(kWidthPx, height);
  svg.text(kWidthPx / 2, 28, title, 18, "middle", "#111");
  const double t_end = table.samples() > 1 ? static_cast<double>(table.samples() - 1) * table.period_s() : 1e-3;
  const double w = kWidthPx - kLeftPx - kRightPx;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const double top = kTitlePx + static_cast<double>(i) * (kPanelPx + kGapPx) + kGapPx - 10;
    svg.text(kLeftPx, top - 8, panels[i].label, 13, "start", panels[i].series.back().color);
    svg.text(kLeftPx + w, top - 8, panels[i].doc, 11, "end", "#777");
    draw_panel(svg, kLeftPx, top, w, kPanelPx, panels[i], table.period_s(), t_end);
  }
  svg.text(kLeftPx + w / 2, height - 14, "time since the first sample (s)", 11, "middle", "#333");
  return svg;
}

hil::SvgWriter circle_comparison_figure(const std::string& title, const std::vector<LabelledCapture>& rows) {
  std::vector<std::vector<hil::TraceSample>> traces;
  std::vector<hil::ContourStats> stats;
  std::vector<std::string> labels;
  double radius_mm = 0.0;
  for (const LabelledCapture& row : rows) {
    if (row.table == nullptr || !is_circle_capture(*row.table)) continue;
    std::string error;
    const auto s = score_circle(*row.table, error);
    if (!s) continue;
    traces.push_back(circle_trace(*row.table));
    stats.push_back(*s);
    labels.push_back(row.label);
    if (radius_mm == 0.0) radius_mm = reference_radius_mm(*row.table);
  }
  std::vector<hil::PlotRow> plot_rows;
  for (std::size_t i = 0; i < traces.size(); ++i) plot_rows.push_back({labels[i], stats[i], &traces[i]});
  return hil::circle_figure(title, radius_mm, plot_rows);
}

hil::SvgWriter capture_figure(const std::string& title, const std::string& label, const CaptureTable& table) {
  if (is_circle_capture(table)) return circle_comparison_figure(title, {{label, &table}});
  return channel_figure(title, table);
}

}  // namespace tnv::can_host
