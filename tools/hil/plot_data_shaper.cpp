// The input shaper's figures as "panels" plot data (tools/hil/plot_data.hpp).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "firmware/shaper/grid_taps.hpp"
#include "hal/axis.hpp"
#include "firmware/shaper/residual_vibration.hpp"
#include "tools/hil/plot_data.hpp"
#include "tools/hil/shaper_design_report.hpp"

namespace tnv::hil {

using nlohmann::json;

namespace {

const char* shaper_type_color(fw::ShaperType t) {
  switch (t) {
    case fw::ShaperType::zv: return "#1f77b4";
    case fw::ShaperType::zvd: return "#ff7f0e";
    case fw::ShaperType::zvdd: return "#2ca02c";
    case fw::ShaperType::ei: return "#9467bd";
    case fw::ShaperType::mzv: return "#8c564b";
  }
  return "#333333";
}

std::string shaper_upper(const char* s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::string shaper_text(const char* pattern, double v) {
  char buf[160];
  std::snprintf(buf, sizeof buf, pattern, v);
  return buf;
}

json residual_series(const fw::TapSet& taps, double design_hz, double zeta, double r_lo, double r_hi, const char* color,
                     const std::string& label, const char* style = "line") {
  std::vector<double> r, v;
  for (int i = 0; i <= 600; ++i) {
    r.push_back(r_lo + (r_hi - r_lo) * i / 600.0);
    v.push_back(100.0 * fw::residual_vibration(taps, kShaperPeriodS, r.back() * design_hz, zeta));
  }
  return plot_series(label, std::move(r), std::move(v), style, color);
}

const json kFivePercent = json::array({json{{"y", 5.0}, {"label", "5 %"}}});

}  // namespace

json shaper_sensitivity_plot_data(const fw::ShaperSpec& spec) {
  const bool two = spec.has_second_mode();
  std::string title = shaper_upper(fw::to_string(spec.type)) + " input shaper at " +
                      shaper_text("%.4g Hz", spec.mode.freq_hz) + shaper_text(", zeta %.3g", spec.mode.zeta);
  if (two) title += shaper_text(" and %.4g Hz", spec.second_mode.freq_hz) + shaper_text(", zeta %.3g", spec.second_mode.zeta);
  json families = json::array();
  for (fw::ShaperType t : fw::kShaperTypes) {
    const fw::ShaperDesign d = fw::design_shaper({t, spec.mode, {0.0, 0.0}}, kShaperPeriodS);
    char label[96];
    std::snprintf(label, sizeof label, "%s %.0f ms, band %.2f%s", shaper_upper(fw::to_string(t)).c_str(), d.duration_s() * 1e3,
                  fw::insensitivity_band(d.taps, kShaperPeriodS, spec.mode.freq_hz, spec.mode.zeta).width(),
                  t == spec.type ? " (this one)" : "");
    families.push_back(residual_series(d.taps, spec.mode.freq_hz, spec.mode.zeta, 0.0, 2.0, shaper_type_color(t), label,
                                       t == spec.type ? "reference" : "line"));
  }
  const fw::ShaperDesign one = fw::design_shaper({spec.type, spec.mode, {0.0, 0.0}}, kShaperPeriodS);
  json damping = json::array();
  const char* colors[] = {"#08306b", "#2171b5", "#6baed6", "#e6550d", "#a50f15"};
  const double zetas[] = {0.0, spec.mode.zeta, 0.05, 0.1, 0.2};
  for (int i = 0; i < 5; ++i) {
    if (i == 1 && (spec.mode.zeta == 0.0 || spec.mode.zeta == 0.05 || spec.mode.zeta == 0.1)) continue;
    damping.push_back(residual_series(one.taps, spec.mode.freq_hz, zetas[i], 0.5, 1.5, colors[i],
                                      shaper_text("actual zeta %.3g", zetas[i]) + (i == 1 ? " (design)" : ""),
                                      i == 1 ? "dashed" : "line"));
  }
  json panels = json::array();
  panels.push_back({{"y_label", "residual vibration (%)"}, {"x_label", "actual / design frequency"},
                    {"y_range", {0.0, 100.0}}, {"x_range", {0.0, 2.0}}, {"hlines", kFivePercent},
                    {"note", "design damping, all five types"}, {"series", families}, {"legend_columns", 3}});
  panels.push_back({{"y_label", "residual vibration (%)"}, {"x_label", "actual / design frequency"},
                    {"y_range", {0.0, 30.0}}, {"x_range", {0.5, 1.5}}, {"hlines", kFivePercent},
                    {"note", shaper_upper(fw::to_string(spec.type)) + " under other damping"}, {"series", damping},
                    {"legend_columns", 3}});
  if (two) {
    const fw::ShaperDesign d = fw::design_shaper(spec, kShaperPeriodS);
    const double f_max = 1.6 * std::max(spec.mode.freq_hz, spec.second_mode.freq_hz);
    std::vector<double> f, both, first;
    for (int i = 1; i <= 800; ++i) {
      f.push_back(f_max * i / 800.0);
      both.push_back(100.0 * fw::residual_vibration(d.taps, kShaperPeriodS, f.back(), spec.mode.zeta));
      first.push_back(100.0 * fw::residual_vibration(one.taps, kShaperPeriodS, f.back(), spec.mode.zeta));
    }
    panels.push_back({{"y_label", "residual vibration (%)"}, {"x_label", "actual frequency (Hz)"},
                      {"y_range", {0.0, 100.0}}, {"x_range", {0.0, f_max}}, {"hlines", kFivePercent},
                      {"note", "two modes by convolution: both zeros on the grid"},
                      {"series", {plot_series("first mode only", f, first, "reference", "#999999"),
                                  plot_series("two-mode shaper (taps)", f, both, "line", shaper_type_color(spec.type))}}});
  }
  return {{"kind", "panels"}, {"title", title}, {"sharex", false}, {"panels", panels}};
}

json grid_method_plot_data(const std::vector<fw::ShaperType>& types, double zeta) {
  constexpr double kFloor = 1e-6;  // percent; the exact taps sit ~1e-12 % (rounding), drawn at this floor
  json panels = json::array();
  for (fw::ShaperType t : types) {
    std::vector<double> f, rounding, split, exact;
    for (int i = 0; i <= 390; ++i) {
      f.push_back(5.0 + 0.5 * i);
      const fw::ImpulseTrain cont = fw::design_impulses(t, {f.back(), zeta});
      const auto pct = [&](const fw::TapSet& taps) {
        return std::max(kFloor, 100.0 * fw::residual_vibration(taps, kShaperPeriodS, f.back(), zeta));
      };
      rounding.push_back(pct(fw::round_to_grid(cont, kShaperPeriodS)));
      split.push_back(pct(fw::split_to_grid(cont, kShaperPeriodS)));
      exact.push_back(pct(fw::exact_grid_taps(t, {f.back(), zeta}, kShaperPeriodS)));
    }
    panels.push_back({{"y_label", "residual at design (%)"}, {"log_y", true}, {"y_range", {kFloor, 100.0}},
                      {"hlines", json::array({json{{"y", 0.5}, {"label", "0.5 %"}}})},
                      {"note", shaper_upper(fw::to_string(t))},
                      {"series", {plot_series("exact taps (this firmware), below 1e-12 %, drawn at 1e-6 %", f, exact,
                                              "reference", "#2ca02c"),
                                  plot_series("rounding to the nearest sample", f, rounding, "line", "#d62728"),
                                  plot_series("splitting between neighbours", f, split, "dashed", "#ff7f0e")}}});
  }
  return {{"kind", "panels"},
          {"title", shaper_text("Residual left at the design frequency by the grid method (zeta %.3g, 1 kHz taps)", zeta)},
          {"x_label", "design frequency (Hz)"},
          {"panels", panels}};
}

json move_plot_data(const std::string& title, const MoveComparison& c) {
  if (c.pairs.empty()) return {{"kind", "panels"}, {"title", title}, {"panels", json::array()}};
  const MovePair& p = c.pairs.front();
  const MoveRunResult& u = p.unshaped;
  const MoveRunResult& s = p.shaped;
  const double target = u.target_mm;
  std::vector<double> tu, ref_u, tool_u, ts, ref_s, tool_s, teu, eu, tes, es;
  double err_max = 1.0;
  for (const MoveTraceSample& t : u.trace) {
    tu.push_back(t.t_s), ref_u.push_back(t.unshaped_mm), tool_u.push_back(t.tool_mm);
    if (t.t_s >= u.command_end_s) teu.push_back(t.t_s), eu.push_back((t.tool_mm - target) * 1e3);
  }
  for (const MoveTraceSample& t : s.trace) {
    ts.push_back(t.t_s), ref_s.push_back(t.reference_mm), tool_s.push_back(t.tool_mm);
    if (t.t_s >= s.command_end_s) tes.push_back(t.t_s), es.push_back((t.tool_mm - target) * 1e3);
  }
  for (double v : eu) err_max = std::max(err_max, std::fabs(v));
  for (double v : es) err_max = std::max(err_max, std::fabs(v));
  char sub[200];
  std::snprintf(sub, sizeof sub, "unshaped: residual %.1f µm p-p, settles (±1 µm) %.3f s after the move;  shaped: %.2f µm p-p, %s",
                u.residual_pp_um, u.settling_s.value_or(-1.0), s.residual_pp_um,
                s.settling_s ? shaper_text("%.3f s", *s.settling_s).c_str() : "not settled");
  const json errors = {plot_series("unshaped", teu, eu, "line", "#d62728"), plot_series("shaped", tes, es, "line", "#2ca02c")};
  const double t_end = u.trace.empty() ? 1.0 : u.trace.back().t_s;
  json panels = json::array();
  panels.push_back({{"y_label", "position (mm)"}, {"x_range", {0.0, u.move_time_s + 0.35}},
                    {"note", "command and tool point (zoom on the move)"},
                    {"series", {plot_series("command (unshaped)", tu, ref_u, "reference", "#999999"),
                                plot_series("command (shaped)", ts, ref_s, "dashed", "#1f77b4"),
                                plot_series("tool point, unshaped", tu, tool_u, "line", "#d62728"),
                                plot_series("tool point, shaped", ts, tool_s, "line", "#2ca02c")}},
                    {"legend_columns", 2}});
  panels.push_back({{"y_label", "tool - target (um)"}, {"x_range", {0.0, t_end}}, {"y_range", {-err_max * 1.05, err_max * 1.05}},
                    {"note", "each after its own command has ended"}, {"series", errors}});
  panels.push_back({{"y_label", "tool - target (um)"}, {"x_range", {0.0, t_end}}, {"y_range", {-5.0, 5.0}},
                    {"band", {-1.0, 1.0}}, {"band_label", "±1 µm settling band"}, {"series", errors}});
  return {{"kind", "panels"}, {"title", title}, {"subtitle", sub}, {"sharex", false},
          {"x_label", "time since the start of the move (s)"}, {"panels", panels}};
}

json jog_plot_data(const std::string& title, const JogRunResult& u, const JogRunResult& s) {
  json panels = json::array();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    std::vector<double> t, cmd, ref, teu, eu, tes, es;
    for (const JogTraceSample& q : s.trace) t.push_back(q.t_s), cmd.push_back(q.unshaped_mm[i]), ref.push_back(q.reference_mm[i]);
    for (const JogTraceSample& q : u.trace)
      if (q.t_s >= u.stop_s) teu.push_back(q.t_s), eu.push_back((q.tool_mm[i] - u.axis[i].end_mm) * 1e3);
    for (const JogTraceSample& q : s.trace)
      if (q.t_s >= s.stop_s) tes.push_back(q.t_s), es.push_back((q.tool_mm[i] - s.axis[i].end_mm) * 1e3);
    const std::string axis = hal::kAxisNames[i];
    panels.push_back({{"y_label", axis + " position (mm)"},
                      {"series", {plot_series("operator stream (unshaped)", t, cmd, "reference", "#999999"),
                                  plot_series("shaped reference", t, ref, "line", "#1f77b4")}}});
    panels.push_back({{"y_label", axis + ": tool - end (um)"}, {"y_range", {-10.0, 10.0}}, {"band", {-1.0, 1.0}},
                      {"band_label", "±1 µm"}, {"note", "after the stop"},
                      {"series", {plot_series("unshaped", teu, eu, "line", "#d62728"),
                                  plot_series("shaped", tes, es, "line", "#2ca02c")}}});
  }
  return {{"kind", "panels"}, {"title", title}, {"x_label", "time (s)"}, {"panels", panels}};
}

}  // namespace tnv::hil
