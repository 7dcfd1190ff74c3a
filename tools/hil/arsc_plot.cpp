#include "tools/hil/arsc_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tools/hil/plot_format.hpp"

namespace tnv::hil {

namespace {

constexpr double kWidthPx = 1000.0;
constexpr double kLeftPx = 90.0;
constexpr double kRightPx = 200.0;  // legend column
constexpr double kPanelPx = 170.0;
constexpr double kGapPx = 34.0;
constexpr double kTitlePx = 50.0;

void draw_panel(SvgWriter& svg, const Panel& panel, double top, double t_end, bool last, std::string_view x_label) {
  const double w = kWidthPx - kLeftPx - kRightPx;
  const double h = kPanelPx;
  const double span = panel.y_max - panel.y_min;
  const auto x_of = [&](double t) { return kLeftPx + w * std::clamp(t / t_end, 0.0, 1.0); };
  const auto y_of = [&](double v) { return top + h - h * (std::clamp(v, panel.y_min, panel.y_max) - panel.y_min) / span; };
  if (panel.band_high > panel.band_low)
    svg.rect(kLeftPx, y_of(panel.band_high), w, y_of(panel.band_low) - y_of(panel.band_high), "none", "#e8f4e8");
  const double y_step = nice_step(span, 4);
  for (double v = std::ceil(panel.y_min / y_step) * y_step; v <= panel.y_max + 1e-9; v += y_step) {
    svg.line(kLeftPx, y_of(v), kLeftPx + w, y_of(v), "#e4e4e4", 0.7);
    svg.text(kLeftPx - 6, y_of(v) + 4, format_value("%g", std::fabs(v) < 1e-12 ? 0.0 : v), 10, "end", "#555");
  }
  const double t_step = nice_step(t_end, 8);
  for (double t = 0.0; t <= t_end + 1e-9; t += t_step) {
    svg.line(x_of(t), top, x_of(t), top + h, "#eeeeee", 0.7);
    if (last) svg.text(x_of(t), top + h + 14, format_value("%g", t), 10, "middle", "#555");
  }
  svg.rect(kLeftPx, top, w, h, "#888");
  svg.text(kLeftPx - 50, top + h / 2, panel.y_label, 11, "middle", "#333", -90);
  if (last) svg.text(kLeftPx + w / 2, top + h + 30, x_label, 11, "middle", "#333");
  bool clipped = false;
  double legend_y = top + 14;
  for (const Series& s : panel.series) {
    std::vector<std::pair<double, double>> pts;
    pts.reserve(s.t_s.size());
    for (std::size_t i = 0; i < s.t_s.size() && i < s.value.size(); ++i) {
      const double v = s.value[i];
      if (!std::isfinite(v)) continue;
      if (v < panel.y_min || v > panel.y_max) clipped = true;
      pts.emplace_back(x_of(s.t_s[i]), y_of(v));
    }
    if (s.dashed) {
      for (std::size_t i = 1; i < pts.size(); i += 2)
        svg.line(pts[i - 1].first, pts[i - 1].second, pts[i].first, pts[i].second, s.color, 1.2);
    } else {
      svg.polyline(pts, s.color, 1.4);
    }
    svg.line(kWidthPx - kRightPx + 12, legend_y - 4, kWidthPx - kRightPx + 32, legend_y - 4, s.color, 2.0,
             s.dashed ? "4,3" : "");
    svg.text(kWidthPx - kRightPx + 38, legend_y, s.label, 11, "start", "#222");
    legend_y += 16;
  }
  if (clipped) svg.text(kLeftPx + w - 4, top + 12, "values beyond this range are drawn at its edge", 10, "end", "#b22");
}

Series series(std::string label, std::string color, const std::vector<ArscTracePoint>& trace,
              double (*get)(const ArscTracePoint&), bool dashed = false) {
  Series s{std::move(label), {}, {}, std::move(color), dashed};
  for (const ArscTracePoint& p : trace) {
    s.t_s.push_back(p.t_s);
    s.value.push_back(get(p));
  }
  return s;
}

std::pair<double, double> range_of(const std::vector<Series>& all, double pad_fraction, double lo_cap, double hi_cap) {
  double lo = 1e300, hi = -1e300;
  for (const Series& s : all)
    for (double v : s.value)
      if (std::isfinite(v)) {
        lo = std::min(lo, std::clamp(v, lo_cap, hi_cap));
        hi = std::max(hi, std::clamp(v, lo_cap, hi_cap));
      }
  if (!(hi > lo)) return {lo - 1.0, lo + 1.0};
  const double pad = (hi - lo) * pad_fraction;
  return {lo - pad, hi + pad};
}

}  // namespace

SvgWriter panel_figure(std::string_view title, const std::vector<Panel>& panels, double t_end_s,
                       std::string_view x_label) {
  const double height = kTitlePx + static_cast<double>(panels.size()) * (kPanelPx + kGapPx) + 30.0;
  SvgWriter svg(kWidthPx, height);
  svg.text(kWidthPx / 2, 30, title, 17, "middle", "#111");
  for (std::size_t i = 0; i < panels.size(); ++i)
    draw_panel(svg, panels[i], kTitlePx + static_cast<double>(i) * (kPanelPx + kGapPx), t_end_s,
               i + 1 == panels.size(), x_label);
  return svg;
}

SvgWriter arsc_run_figure(const ArscRunResult& run) {
  const auto& tr = run.trace;
  const double t_end = run.config.duration_s;
  const double ref = run.config.force_ref;
  std::vector<Panel> panels;
  {
    Panel p{"force f (normalised)", 0.0, 2.0 * ref, {}, 0.9 * ref, 1.1 * ref};
    p.series.push_back(series("f", "#d62728", tr, [](const ArscTracePoint& q) { return q.force; }));
    Series fs{"f* and +-10%", {0.0, t_end}, {ref, ref}, "#2ca02c", true};
    p.series.push_back(fs);
    panels.push_back(p);
  }
  {
    Panel p{"feed v / depth (mm)", 0.0, 4.0, {}, 0.0, 0.0};
    p.series.push_back(series("feed v", "#1f77b4", tr, [](const ArscTracePoint& q) { return q.feed; }));
    p.series.push_back(series("depth (mm)", "#7f7f7f", tr, [](const ArscTracePoint& q) { return q.depth_mm; }, true));
    panels.push_back(p);
  }
  {
    Panel p{"input u", -2.0, 8.0, {}, 0.0, 0.0};
    p.series.push_back(series("u applied", "#9467bd", tr, [](const ArscTracePoint& q) { return q.u; }));
    panels.push_back(p);
  }
  {
    Panel p{"gains", 0, 1, {}, 0.0, 0.0};
    p.series.push_back(series("k", "#d62728", tr, [](const ArscTracePoint& q) { return q.gains.k; }));
    p.series.push_back(series("gamma01", "#1f77b4", tr, [](const ArscTracePoint& q) { return q.gains.gamma01; }));
    p.series.push_back(series("gamma11", "#2ca02c", tr, [](const ArscTracePoint& q) { return q.gains.gamma11; }));
    p.series.push_back(series("gamma31", "#ff7f0e", tr, [](const ArscTracePoint& q) { return q.gains.gamma31; }));
    const auto [lo, hi] = range_of(p.series, 0.08, -100.0, 100.0);
    p.y_min = lo;
    p.y_max = hi;
    panels.push_back(p);
  }
  {
    Panel p{"cutting gain", 0, 1, {}, 0.0, 0.0};
    const char* est = run.config.variant == ArscVariant::robust ? "g^ (estimate)" : "-phi112^ (ARV(2) estimate)";
    p.series.push_back(series(est, "#d62728", tr, [](const ArscTracePoint& q) { return q.cutting_gain; }));
    p.series.push_back(series("b21 delta (process)", "#444444", tr,
                              [](const ArscTracePoint& q) { return q.true_cutting_gain; }, true));
    const auto [lo, hi] = range_of(p.series, 0.08, -2.0, 3.0);
    p.y_min = std::min(lo, 0.0);
    p.y_max = hi;
    panels.push_back(p);
  }
  char title[200];
  std::snprintf(title, sizeof title, "S3 ARSC %s, %s (T = %.2f s): force error after %.0f s max %.1f%%, rms %.1f%%%s",
                to_string(run.config.variant), fw::arsc::to_string(run.config.poles), run.config.process.sample_s,
                run.config.settle_s, run.force_error_max_pct, run.force_error_rms_pct,
                run.diverged ? ", DIVERGED" : "");
  return panel_figure(title, panels, t_end, "time (s)");
}

SvgWriter arsc_compare_figure(const std::vector<ArscRunResult>& faithful, const std::vector<ArscRunResult>& robust) {
  std::vector<Panel> panels;
  const char* colors[] = {"#d62728", "#1f77b4", "#2ca02c", "#ff7f0e"};
  double t_end = 30.0;
  for (int v = 0; v < 2; ++v) {
    const auto& runs = v == 0 ? faithful : robust;
    Panel p{v == 0 ? "faithful: force f" : "robust: force f", 0.0, 2.0, {}, 0.9, 1.1};
    for (std::size_t i = 0; i < runs.size(); ++i) {
      char label[96];
      std::snprintf(label, sizeof label, "%s %s%.0f%%", fw::arsc::to_string(runs[i].config.poles),
                    runs[i].diverged ? "diverged, " : "max ", runs[i].force_error_max_pct);
      if (runs[i].diverged) std::snprintf(label, sizeof label, "%s diverged", fw::arsc::to_string(runs[i].config.poles));
      if (!runs[i].first_gains_s)
        std::snprintf(label, sizeof label, "%s no gains ever", fw::arsc::to_string(runs[i].config.poles));
      p.series.push_back(series(label, colors[i % 4], runs[i].trace, [](const ArscTracePoint& q) { return q.force; }));
      t_end = runs[i].config.duration_s;
    }
    panels.push_back(p);
  }
  return panel_figure("S3 ARSC, four pole sets: the paper's loop (top) and the robust variant (bottom), f* = 1 +-10%",
                      panels, t_end, "time (s)");
}

SvgWriter arsc_tick_figure(const std::vector<TickStudyResult>& runs) {
  const char* loop_colors[] = {"#d62728", "#ff7f0e", "#1f77b4", "#2ca02c", "#9467bd", "#8c564b"};
  std::size_t loops = 0;
  double ref_n = 150.0, t_end = 1.0;
  for (const TickStudyResult& r : runs) {
    ref_n = r.config.force_ref_n;
    t_end = std::max(t_end, r.config.duration_s);
  }
  Panel force{"force (N)", 0.0, 2.0 * ref_n, {}, 0.9 * ref_n, 1.1 * ref_n};
  Panel error{"force error (% of f*), scored part", -10.0, 10.0, {}, -1.0, 1.0};
  Panel feed{"table feed along the path (mm/s)", 0.0, 100.0, {}, 0.0, 0.0};
  Panel gain{"cutting gain G (N per mm/s)", 0.0, 18.0, {}, 0.0, 0.0};
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const TickStudyResult& r = runs[i];
    char label[96];
    if (r.diverged)
      std::snprintf(label, sizeof label, "%s: diverged", r.config.label.c_str());
    else
      std::snprintf(label, sizeof label, "%s: max %.1f%%", r.config.label.c_str(), r.force_error_max_pct);
    const std::string color = r.config.outer_loop ? loop_colors[loops++ % 6] : "#7f7f7f";  // baseline grey
    Series f{label, {}, {}, color, false}, e{label, {}, {}, color, false}, v{label, {}, {}, color, false};
    Series g{std::string(r.config.label) + " estimate", {}, {}, color, false};
    for (const TickStudyPoint& p : r.trace) {
      f.t_s.push_back(p.t_s);
      f.value.push_back(p.force_n);
      v.t_s.push_back(p.t_s);
      v.value.push_back(p.feed_mm_s);
      if (p.t_s >= r.config.settle_s) {
        e.t_s.push_back(p.t_s);
        e.value.push_back((p.force_n - p.force_ref_n) / ref_n * 100.0);
      }
      g.t_s.push_back(p.t_s);
      g.value.push_back(p.cutting_gain_n_per_mm_s);
    }
    force.series.push_back(f);
    feed.series.push_back(v);
    if (r.config.outer_loop) {
      error.series.push_back(e);
      // Estimates of the first and the last force loop only (in the comparison 0.15 s and
      // 1 ms with 4x poles): the others lie between them.
      if (gain.series.empty() || i + 1 == runs.size()) gain.series.push_back(g);
    }
  }
  Series ref{"f* and +-10%", {0.0, t_end}, {ref_n, ref_n}, "#2ca02c", true};
  force.series.push_back(ref);
  if (!runs.empty()) {
    Series truth{"true gain, constant-feed run", {}, {}, "#222222", false};
    for (const TickStudyPoint& p : runs.front().trace) {
      truth.t_s.push_back(p.t_s);
      truth.value.push_back(p.true_cutting_gain_n_per_mm_s);
    }
    gain.series.push_back(truth);
  }
  return panel_figure(
      "Robust ARSC as the firmware's feed-override source (emulated TNV-40), 150 N, depth 0.2-1.0-0.2 mm",
      {force, error, feed, gain}, t_end, "time (s)");
}

}  // namespace tnv::hil
