#include "tools/hil/boring_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>

#include "tools/hil/plot_format.hpp"

namespace tnv::hil {

namespace {

constexpr double kWidthPx = 1120.0;
constexpr double kLeftPx = 90.0;
constexpr double kPlotWidthPx = 900.0;
constexpr double kTitlePx = 64.0;
constexpr double kPanelPx = 190.0;
constexpr double kGapPx = 56.0;
constexpr const char* kPositionColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2",
                                           "#7f7f7f", "#bcbd22"};
constexpr const char* kResetColor = "#7b3fa0";
constexpr const char* kBadColor = "#d62728";

// One panel: part number across, a linear or log value axis up.
struct Panel {
  SvgWriter& svg;
  double top;
  int parts;
  double lo;
  double hi;
  bool log_y;

  double x(double part) const { return kLeftPx + kPlotWidthPx * (part - 0.5) / parts; }
  double y(double v) const {
    const double t = log_y ? (std::log10(std::max(v, 1e-12)) - std::log10(lo)) / (std::log10(hi) - std::log10(lo))
                           : (v - lo) / (hi - lo);
    return top + kPanelPx - kPanelPx * std::clamp(t, -0.02, 1.02);
  }
  void frame(std::string_view y_label, const BoringRunRequest& r) const {
    svg.rect(kLeftPx, top, kPlotWidthPx, kPanelPx, "#888");
    if (log_y) {
      for (double decade = std::pow(10.0, std::floor(std::log10(lo))); decade <= hi * 1.0001; decade *= 10.0)
        for (double m : {1.0, 2.0, 5.0}) {
          const double v = m * decade;
          if (v < lo * 0.9999 || v > hi * 1.0001) continue;
          svg.line(kLeftPx, y(v), kLeftPx + kPlotWidthPx, y(v), "#eee", 0.6);
          svg.text(kLeftPx - 6, y(v) + 4, format_value("%g", v), 10, "end", "#555");
        }
    } else {
      const double step = nice_step(hi - lo, 5);
      for (double v = std::ceil(lo / step) * step; v <= hi + 1e-12; v += step) {
        svg.line(kLeftPx, y(v), kLeftPx + kPlotWidthPx, y(v), "#eee", 0.6);
        svg.text(kLeftPx - 6, y(v) + 4, format_value("%g", std::fabs(v) < 1e-12 ? 0.0 : v), 10, "end", "#555");
      }
    }
    const double part_step = parts <= 40 ? 1.0 : nice_step(parts, 15);
    for (double p = part_step; p <= parts; p += part_step) {
      svg.line(x(p), top + kPanelPx, x(p), top + kPanelPx + 4, "#888", 0.8);
      svg.text(x(p), top + kPanelPx + 15, format_value("%g", p), 10, "middle", "#555");
    }
    for (int c : r.change_at)
      if (c <= parts) svg.line(x(c - 0.5), top, x(c - 0.5), top + kPanelPx, "#999", 1.0, "6,3");
    svg.text(kLeftPx - 56, top + kPanelPx / 2, y_label, 11, "middle", "#333", -90);
  }
  void dot(double part, double v, std::string_view color, double r = 2.6) const {
    svg.circle(x(part), y(v), r / 2, color, r);  // a filled disc: stroke as wide as the circle
  }
  void ring(double part, double v, std::string_view color) const { svg.circle(x(part), y(v), 3.2, color, 1.0); }
  void series(const std::vector<double>& values, std::string_view color, double width = 1.4, bool dots = true) const {
    std::vector<std::pair<double, double>> pts;
    for (std::size_t i = 0; i < values.size(); ++i) pts.emplace_back(x(static_cast<double>(i) + 1.0), y(values[i]));
    svg.polyline(pts, color, width);
    if (dots && values.size() <= 120)
      for (std::size_t i = 0; i < values.size(); ++i) dot(static_cast<double>(i) + 1.0, values[i], color);
  }
  // A step line at part boundaries (true parameters change between parts).
  void steps(const std::vector<double>& values, std::string_view color) const {
    for (std::size_t i = 0; i < values.size(); ++i) {
      const double p = static_cast<double>(i) + 1.0;
      svg.line(x(p - 0.5), y(values[i]), x(p + 0.5), y(values[i]), color, 1.3, "5,3");
      if (i > 0 && values[i] != values[i - 1]) svg.line(x(p - 0.5), y(values[i - 1]), x(p - 0.5), y(values[i]), color, 1.3, "5,3");
    }
  }
  void legend(double x0, const std::vector<std::pair<std::string, std::string>>& items, bool dashed_last = false) const {
    double lx = x0;
    for (std::size_t i = 0; i < items.size(); ++i) {
      const bool dashed = dashed_last && i + 1 == items.size();
      svg.line(lx, top - 8, lx + 22, top - 8, items[i].second, 2.0, dashed ? "5,3" : "");
      svg.text(lx + 27, top - 4, items[i].first, 11, "start", "#333");
      lx += 40.0 + 6.5 * static_cast<double>(items[i].first.size());
    }
  }
};

std::vector<double> collect(const std::vector<BoringPartRecord>& parts, const std::function<double(const BoringPartRecord&)>& f) {
  std::vector<double> v;
  v.reserve(parts.size());
  for (const BoringPartRecord& p : parts) v.push_back(f(p));
  return v;
}

}  // namespace

SvgWriter boring_figure(std::string_view title, const BoringRunRequest& r, const BoringSweepResult& s) {
  const std::vector<BoringPartRecord>& parts = s.seed1.parts;
  const int n = std::max(1, static_cast<int>(parts.size()));
  const std::size_t npos = parts.empty() ? 0 : parts.front().positions.size();
  const double height = kTitlePx + 5 * (kPanelPx + kGapPx) + 10;
  SvgWriter svg(kWidthPx, height);
  svg.text(kWidthPx / 2, 26, title, 17, "middle", "#111");
  const double d0 = r.planner.target_deflection_mm;
  const double band = r.planner.band_sigmas * r.band_sigma_mm;
  char sub[300];
  std::snprintf(sub, sizeof sub,
                "seed 1 of %d; bad parts %.2f mean / %d max, resets %.2f mean over seeds; gain form %s, reset after %d %s",
                s.seeds, s.bad_parts_mean, s.bad_parts_max, s.resets_mean, fw::to_string(r.planner.gain_form),
                r.planner.reset_after, fw::to_string(r.planner.reset_count));
  svg.text(kWidthPx / 2, 46, sub, 12, "middle", "#444");

  // Panel 1: deflection.
  double top = kTitlePx + 22;
  // Zoomed on the band: at most d0 +- 6 band; larger values sit on the frame.
  double d_hi = d0 + 1.6 * band;
  for (const BoringPartRecord& p : parts)
    for (const BoringPositionRecord& q : p.positions) d_hi = std::max({d_hi, q.true_deflection_mm, q.measured_deflection_mm});
  d_hi = std::min(d_hi, d0 + 6.0 * band);
  const double d_step = nice_step(d_hi - std::max(0.0, d0 - 6.0 * band), 5);
  d_hi = std::ceil(d_hi / d_step) * d_step;
  const double d_lo = std::max(0.0, std::floor((d0 - 6.0 * band) / d_step) * d_step);
  Panel deflection{svg, top, n, d_lo, d_hi, false};
  svg.rect(kLeftPx, deflection.y(d0 + band), kPlotWidthPx, deflection.y(d0 - band) - deflection.y(d0 + band), "none", "#e6f4e6");
  deflection.frame("deflection d (mm)", r);
  svg.line(kLeftPx, deflection.y(d0), kLeftPx + kPlotWidthPx, deflection.y(d0), "#2a7a2a", 1.0, "4,3");
  svg.text(kLeftPx + kPlotWidthPx + 6, deflection.y(d0) - 2, format_value("d0 = %.4g", d0), 10, "start", "#2a7a2a");
  svg.text(kLeftPx + kPlotWidthPx + 6, deflection.y(d0) + 10, format_value("+- %.3g mm", band), 10, "start", "#2a7a2a");
  std::vector<std::pair<std::string, std::string>> legend;
  for (std::size_t i = 0; i < npos; ++i) {
    const char* color = kPositionColors[i % std::size(kPositionColors)];
    deflection.series(collect(parts, [i](const BoringPartRecord& p) { return p.positions[i].true_deflection_mm; }), color);
    if (parts.size() <= 120)
      for (const BoringPartRecord& p : parts) deflection.ring(p.part, p.positions[i].measured_deflection_mm, color);
    legend.emplace_back(format_value("true d at L = %.0f mm", parts.front().positions[i].overhang_mm), color);
  }
  deflection.legend(kLeftPx, legend);
  svg.text(kLeftPx + kPlotWidthPx, top - 4, "rings: measured;  shaded: d0 +- 3 sigma;  x: bad part;  R: P reset;  beyond the frame: drawn on it", 10, "end", "#555");
  for (const BoringPartRecord& p : parts) {
    if (p.bad) svg.text(deflection.x(p.part), top + kPanelPx - 5, "x", 12, "middle", kBadColor);
    if (p.reset) {
      svg.line(deflection.x(p.part), top, deflection.x(p.part), top + kPanelPx, kResetColor, 1.0, "2,2");
      svg.text(deflection.x(p.part), top + 12, "R", 11, "middle", kResetColor);
    }
  }

  // Panel 2: infeed, log scale.
  top += kPanelPx + kGapPx;
  double s_lo = 1e9, s_hi = 0.0;
  for (const BoringPartRecord& p : parts)
    for (const BoringPositionRecord& q : p.positions) {
      s_lo = std::min({s_lo, q.infeed_mm_rev, q.optimal_infeed_mm_rev});
      s_hi = std::max({s_hi, q.infeed_mm_rev, q.optimal_infeed_mm_rev});
    }
  if (parts.empty()) s_lo = 0.01, s_hi = 1.0;
  Panel infeed{svg, top, n, std::pow(10.0, std::floor(std::log10(s_lo))), std::pow(10.0, std::ceil(std::log10(s_hi))), true};
  infeed.frame("infeed S (mm/rev)", r);
  legend.clear();
  for (std::size_t i = 0; i < npos; ++i) {
    const char* color = kPositionColors[i % std::size(kPositionColors)];
    infeed.steps(collect(parts, [i](const BoringPartRecord& p) { return p.positions[i].optimal_infeed_mm_rev; }), color);
    infeed.series(collect(parts, [i](const BoringPartRecord& p) { return p.positions[i].infeed_mm_rev; }), color);
    legend.emplace_back(format_value("S at L = %.0f mm", parts.front().positions[i].overhang_mm), color);
  }
  legend.emplace_back("optimal S (eq. 3, true set)", "#666");
  infeed.legend(kLeftPx, legend, true);

  // Panel 3: alpha, beta.
  top += kPanelPx + kGapPx;
  double e_lo = 0.0, e_hi = 1.0;
  for (const BoringPartRecord& p : parts) {
    e_lo = std::min({e_lo, p.alpha_hat, p.beta_hat});
    e_hi = std::max({e_hi, p.alpha_hat, p.beta_hat});
  }
  e_hi = std::min(e_hi, 3.0);
  e_lo = std::max(e_lo, -1.0);
  Panel exps{svg, top, n, std::floor(e_lo * 5.0) / 5.0, std::ceil(e_hi * 5.0) / 5.0, false};
  exps.frame("exponents", r);
  exps.steps(collect(parts, [](const BoringPartRecord& p) { return p.true_alpha; }), "#ff7f0e");
  exps.steps(collect(parts, [](const BoringPartRecord& p) { return p.true_beta; }), "#17becf");
  exps.series(collect(parts, [](const BoringPartRecord& p) { return p.alpha_hat; }), "#ff7f0e");
  exps.series(collect(parts, [](const BoringPartRecord& p) { return p.beta_hat; }), "#17becf");
  exps.legend(kLeftPx, {{"alpha estimate", "#ff7f0e"}, {"beta estimate", "#17becf"}, {"true values", "#666"}}, true);

  // Panel 4: C.
  top += kPanelPx + kGapPx;
  double c_hi = 0.0;
  for (const BoringPartRecord& p : parts) c_hi = std::max({c_hi, p.c_hat_mm, p.true_c_mm});
  c_hi = std::min(c_hi, 1.0);
  const double c_step = nice_step(std::max(c_hi, 1e-3), 5);
  Panel cpanel{svg, top, n, 0.0, std::ceil(c_hi / c_step) * c_step, false};
  cpanel.frame("C (mm)", r);
  cpanel.steps(collect(parts, [](const BoringPartRecord& p) { return p.true_c_mm; }), "#8c564b");
  cpanel.series(collect(parts, [](const BoringPartRecord& p) { return p.c_hat_mm; }), "#8c564b");
  cpanel.legend(kLeftPx, {{"C estimate", "#8c564b"}, {"true C", "#8c564b"}}, true);

  // Panel 5: over all seeds.
  top += kPanelPx + kGapPx;
  Panel share{svg, top, n, 0.0, 1.0, false};
  share.frame("share of seeds", r);
  const double bar = kPlotWidthPx / n * 0.36;
  for (std::size_t i = 0; i < s.bad_fraction_by_part.size(); ++i) {
    const double p = static_cast<double>(i) + 1.0;
    const double fb = s.bad_fraction_by_part[i];
    const double fr = s.reset_fraction_by_part[i];
    if (fb > 0) svg.rect(share.x(p) - bar, share.y(fb), bar, share.y(0) - share.y(fb), "none", kBadColor);
    if (fr > 0) svg.rect(share.x(p), share.y(fr), bar, share.y(0) - share.y(fr), "none", kResetColor);
  }
  share.legend(kLeftPx, {{format_value("bad part (%.0f seeds)", static_cast<double>(s.seeds)), kBadColor}, {"P reset", kResetColor}});
  svg.text(kLeftPx + kPlotWidthPx / 2, top + kPanelPx + 34, "part number  (grey dashed: process change)", 12, "middle", "#333");
  return svg;
}

}  // namespace tnv::hil
