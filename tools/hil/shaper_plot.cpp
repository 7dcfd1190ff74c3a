#include "tools/hil/shaper_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "firmware/shaper/grid_taps.hpp"
#include "firmware/shaper/residual_vibration.hpp"
#include "tools/hil/shaper_chart.hpp"
#include "tools/hil/shaper_design_report.hpp"

#include "tools/hil/plot_format.hpp"

namespace tnv::hil {

namespace {

constexpr double kWidthPx = 1100.0;

const char* type_color(fw::ShaperType t) {
  switch (t) {
    case fw::ShaperType::zv: return "#1f77b4";
    case fw::ShaperType::zvd: return "#ff7f0e";
    case fw::ShaperType::zvdd: return "#2ca02c";
    case fw::ShaperType::ei: return "#9467bd";
    case fw::ShaperType::mzv: return "#8c564b";
  }
  return "#333";
}

std::string upper(const char* s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

ChartSeries residual_curve(const fw::TapSet& taps, double design_hz, double zeta, double r_lo, double r_hi,
                           const char* color, double width, std::string label) {
  ChartSeries s{{}, color, width, std::move(label)};
  for (int i = 0; i <= 600; ++i) {
    const double r = r_lo + (r_hi - r_lo) * i / 600.0;
    s.points.emplace_back(r, 100.0 * fw::residual_vibration(taps, kShaperPeriodS, r * design_hz, zeta));
  }
  return s;
}

}  // namespace

SvgWriter shaper_sensitivity_figure(const fw::ShaperSpec& spec) {
  const bool two = spec.has_second_mode();
  const double panel_h = 330.0;
  SvgWriter svg(kWidthPx, 70.0 + panel_h + 110.0 + (two ? panel_h + 80.0 : 0.0));
  std::string title = upper(fw::to_string(spec.type)) + " input shaper at " + format_value("%.4g Hz", spec.mode.freq_hz) +
                      format_value(", zeta %.3g", spec.mode.zeta);
  if (two) title += format_value(" and %.4g Hz", spec.second_mode.freq_hz) + format_value(", zeta %.3g", spec.second_mode.zeta);
  svg.text(kWidthPx / 2, 26, title + " (taps as implemented on the 1 ms grid)", 17, "middle", "#111");

  // Left: the five families, same mode (S2 Fig. 3 style).
  std::vector<ChartSeries> families;
  for (fw::ShaperType t : fw::kShaperTypes) {
    const fw::ShaperDesign d = fw::design_shaper({t, spec.mode, {0.0, 0.0}}, kShaperPeriodS);
    const bool mine = t == spec.type;
    char label[96];
    std::snprintf(label, sizeof label, "%s %.0f ms, band %.2f", upper(fw::to_string(t)).c_str(), d.duration_s() * 1e3,
                  fw::insensitivity_band(d.taps, kShaperPeriodS, spec.mode.freq_hz, spec.mode.zeta).width());
    families.push_back(
        residual_curve(d.taps, spec.mode.freq_hz, spec.mode.zeta, 0.0, 2.0, type_color(t), mine ? 3.0 : 1.4, label));
  }
  ChartPanel left{70,
                  70,
                  450,
                  panel_h,
                  0.0,
                  2.0,
                  0.0,
                  100.0,
                  false,
                  "residual vibration vs modelling error (design damping)",
                  "actual / design frequency",
                  "residual vibration (%)",
                  {{5.0, "5 %"}},
                  1.0};
  left.legend_below = true;  // every corner of this panel has curves in it
  draw_chart(svg, left, families);

  // Right: the chosen shaper under other actual damping (S2 Fig. 4 surface, as curves).
  const fw::ShaperDesign one = fw::design_shaper({spec.type, spec.mode, {0.0, 0.0}}, kShaperPeriodS);
  std::vector<ChartSeries> damping;
  const char* colors[] = {"#08306b", "#2171b5", "#6baed6", "#e6550d", "#a50f15"};
  const double zetas[] = {0.0, spec.mode.zeta, 0.05, 0.1, 0.2};
  for (int i = 0; i < 5; ++i) {
    if (i == 1 && (spec.mode.zeta == 0.0 || spec.mode.zeta == 0.05 || spec.mode.zeta == 0.1)) continue;
    damping.push_back(residual_curve(one.taps, spec.mode.freq_hz, zetas[i], 0.5, 1.5, colors[i], i == 1 ? 2.6 : 1.6,
                                     format_value("actual zeta %.3g", zetas[i]) + (i == 1 ? " (design)" : "")));
  }
  ChartPanel right{600,
                   70,
                   450,
                   panel_h,
                   0.5,
                   1.5,
                   0.0,
                   30.0,
                   false,
                   upper(fw::to_string(spec.type)) + ": residual vs frequency and damping error",
                   "actual / design frequency",
                   "residual vibration (%)",
                   {{5.0, "5 %"}},
                   1.0};
  right.legend_at = 0.5;  // the curves leave through the top corners
  draw_chart(svg, right, damping);

  if (two) {
    const fw::ShaperDesign d = fw::design_shaper(spec, kShaperPeriodS);
    const double f_max = 1.6 * std::max(spec.mode.freq_hz, spec.second_mode.freq_hz);
    ChartSeries both{{}, type_color(spec.type), 2.4, "two-mode shaper (taps)"};
    ChartSeries first{{}, "#999", 1.2, "first mode only"};
    for (int i = 1; i <= 800; ++i) {
      const double f = f_max * i / 800.0;
      both.points.emplace_back(f, 100.0 * fw::residual_vibration(d.taps, kShaperPeriodS, f, spec.mode.zeta));
      first.points.emplace_back(f, 100.0 * fw::residual_vibration(one.taps, kShaperPeriodS, f, spec.mode.zeta));
    }
    ChartPanel bottom{70,
                      70 + panel_h + 120,
                      980,
                      panel_h,
                      0.0,
                      f_max,
                      0.0,
                      100.0,
                      false,
                      "two modes by convolution: both zeros on the grid",
                      "actual frequency (Hz)",
                      "residual vibration (%)",
                      {{5.0, "5 %"}},
                      1.0};
    draw_chart(svg, bottom, {first, both});
  }
  return svg;
}

SvgWriter grid_method_figure(const std::vector<fw::ShaperType>& types, double zeta) {
  const double panel_h = 230.0, gap = 70.0;
  SvgWriter svg(kWidthPx, 60.0 + (panel_h + gap) * static_cast<double>(types.size()) + 50.0);
  svg.text(kWidthPx / 2, 26, format_value("Residual vibration left at the design frequency by the 1 ms grid (zeta %.3g)", zeta),
           17, "middle", "#111");
  constexpr double kFloor = 1e-6;  // percent; the exact taps sit ~1e-12 % (rounding), drawn here
  double top = 70.0;
  for (std::size_t n = 0; n < types.size(); ++n) {
    const fw::ShaperType t = types[n];
    const bool last = n + 1 == types.size();  // the legend goes once, under the last panel
    ChartSeries rounding{{}, "#d62728", 1.3, last ? "rounding to the nearest sample" : ""};
    ChartSeries split{{}, "#ff7f0e", 1.3, last ? "splitting between neighbours" : ""};
    ChartSeries exact{
        {}, "#2ca02c", 2.6, last ? "exact taps (this firmware): below 1e-12 %, drawn at the 1e-6 % floor" : ""};
    for (int i = 0; i <= 390; ++i) {
      const double f = 5.0 + 0.5 * i;
      const fw::ImpulseTrain cont = fw::design_impulses(t, {f, zeta});
      rounding.points.emplace_back(
          f, std::max(kFloor, 100.0 * fw::residual_vibration(fw::round_to_grid(cont, kShaperPeriodS), kShaperPeriodS, f,
                                                             zeta)));
      split.points.emplace_back(
          f, std::max(kFloor, 100.0 * fw::residual_vibration(fw::split_to_grid(cont, kShaperPeriodS), kShaperPeriodS, f,
                                                             zeta)));
      exact.points.emplace_back(
          f, std::max(kFloor, 100.0 * fw::residual_vibration(fw::exact_grid_taps(t, {f, zeta}, kShaperPeriodS),
                                                             kShaperPeriodS, f, zeta)));
    }
    ChartPanel p{80,
                 top,
                 980,
                 panel_h,
                 0.0,
                 200.0,
                 kFloor,
                 100.0,
                 true,
                 upper(fw::to_string(t)),
                 "design frequency (Hz)",
                 "residual at design (%)",
                 {{0.5, "0.5 %"}},
                 0.0};
    p.legend_below = true;
    draw_chart(svg, p, {rounding, split, exact});
    top += panel_h + gap;
  }
  return svg;
}

SvgWriter move_figure(const std::string& title, const MoveComparison& c) {
  SvgWriter svg(kWidthPx, 1060.0);
  svg.text(kWidthPx / 2, 26, title, 17, "middle", "#111");
  if (c.pairs.empty()) return svg;
  const MovePair& p = c.pairs.front();
  const MoveRunResult& u = p.unshaped;
  const MoveRunResult& s = p.shaped;
  const double target = u.target_mm;
  const double start = s.trace.empty() ? 0.0 : s.trace.front().unshaped_mm;
  const double t_zoom = u.move_time_s + 0.35;
  ChartSeries ref_u{{}, "#999", 1.4, "command (unshaped)"};
  ChartSeries ref_s{{}, "#1f77b4", 1.6, "command (shaped)"};
  ChartSeries tool_u{{}, "#d62728", 1.4, "tool point, unshaped"};
  ChartSeries tool_s{{}, "#2ca02c", 1.8, "tool point, shaped"};
  ChartSeries err_u{{}, "#d62728", 1.0, "unshaped"};
  ChartSeries err_s{{}, "#2ca02c", 1.4, "shaped"};
  double err_max = 1.0;
  for (const MoveTraceSample& t : u.trace) {
    ref_u.points.emplace_back(t.t_s, t.unshaped_mm);
    tool_u.points.emplace_back(t.t_s, t.tool_mm);
    if (t.t_s >= u.command_end_s) {
      err_u.points.emplace_back(t.t_s, (t.tool_mm - target) * 1e3);
      err_max = std::max(err_max, std::fabs((t.tool_mm - target) * 1e3));
    }
  }
  for (const MoveTraceSample& t : s.trace) {
    ref_s.points.emplace_back(t.t_s, t.reference_mm);
    tool_s.points.emplace_back(t.t_s, t.tool_mm);
    if (t.t_s >= s.command_end_s) {
      err_s.points.emplace_back(t.t_s, (t.tool_mm - target) * 1e3);
      err_max = std::max(err_max, std::fabs((t.tool_mm - target) * 1e3));
    }
  }
  const double lo = std::min(start, target), hi = std::max(start, target), pad = 0.08 * (hi - lo);
  char sub[200];
  std::snprintf(sub, sizeof sub,
                "unshaped: residual %.1f um p-p, settles (+-1 um) %.3f s after the move;  shaped: %.2f um p-p, %s",
                u.residual_pp_um, u.settling_s.value_or(-1.0), s.residual_pp_um,
                s.settling_s ? format_value("%.3f s", *s.settling_s).c_str() : "not settled");
  svg.text(kWidthPx / 2, 48, sub, 12, "middle", "#333");
  draw_chart(svg,
             {80,
              90,
              980,
              250,
              0.0,
              t_zoom,
              lo - pad,
              hi + pad,
              false,
              "command and tool point",
              "time since the start of the move (s)",
              "position (mm)",
              {},
              0.0},
             {ref_u, ref_s, tool_u, tool_s});
  const double t_end = u.trace.empty() ? 1.0 : u.trace.back().t_s;
  const double e = chart_nice_ceiling(err_max);
  draw_chart(svg,
             {80,
              420,
              980,
              250,
              0.0,
              t_end,
              -e,
              e,
              false,
              "tool point - target, each after its own command has ended",
              "time since the start of the move (s)",
              "error (um)",
              {},
              1.0},
             {err_u, err_s});
  draw_chart(svg,
             {80,
              750,
              980,
              250,
              0.0,
              t_end,
              -5.0,
              5.0,
              false,
              "the same, +-5 um (dashed: the +-1 um settling band)",
              "time since the start of the move (s)",
              "error (um)",
              {{1.0, "+1 um"}, {-1.0, "-1 um"}},
              1.0},
             {err_u, err_s});
  return svg;
}

SvgWriter jog_figure(const std::string& title, const JogRunResult& u, const JogRunResult& s) {
  SvgWriter svg(kWidthPx, 740.0);
  svg.text(kWidthPx / 2, 26, title, 17, "middle", "#111");
  double t_end = 1.0;
  if (!s.trace.empty()) t_end = s.trace.back().t_s;
  for (std::size_t i = 0; i < 2; ++i) {
    const double top = 70.0 + 330.0 * static_cast<double>(i);
    ChartSeries cmd{{}, "#999", 1.3, "operator stream (unshaped)"};
    ChartSeries ref{{}, "#1f77b4", 1.6, "shaped reference"};
    ChartSeries err_u{{}, "#d62728", 1.0, "tool - end, unshaped run (um, right scale)"};
    ChartSeries err_s{{}, "#2ca02c", 1.4, "tool - end, shaped run (um, right scale)"};
    double lo = 1e300, hi = -1e300;
    for (const JogTraceSample& t : s.trace) {
      cmd.points.emplace_back(t.t_s, t.unshaped_mm[i]);
      ref.points.emplace_back(t.t_s, t.reference_mm[i]);
      lo = std::min(lo, t.unshaped_mm[i]);
      hi = std::max(hi, t.unshaped_mm[i]);
    }
    for (const JogTraceSample& t : u.trace)
      if (t.t_s >= u.stop_s) err_u.points.emplace_back(t.t_s, (t.tool_mm[i] - u.axis[i].end_mm) * 1e3);
    for (const JogTraceSample& t : s.trace)
      if (t.t_s >= s.stop_s) err_s.points.emplace_back(t.t_s, (t.tool_mm[i] - s.axis[i].end_mm) * 1e3);
    const double pad = std::max(0.05 * (hi - lo), 0.01);
    const char axis = i == 0 ? 'x' : 'y';
    draw_chart(svg,
               {80,
                top,
                560,
                250,
                0.0,
                t_end,
                lo - pad,
                hi + pad,
                false,
                std::string("axis ") + axis + ": operator stream and shaped reference",
                "time (s)",
                "position (mm)",
                {},
                0.0},
               {cmd, ref});
    draw_chart(svg,
               {720,
                top,
                340,
                250,
                std::min(u.stop_s, s.stop_s),
                t_end,
                -10.0,
                10.0,
                false,
                std::string("axis ") + axis + ": tool - end after the stop",
                "time (s)",
                "error (um)",
                {{1.0, "+1"}, {-1.0, "-1"}},
                1.0},
               {ChartSeries{err_u.points, err_u.color, err_u.width, "unshaped"},
                ChartSeries{err_s.points, err_s.color, err_s.width, "shaped"}});
  }
  return svg;
}

}  // namespace tnv::hil
