#include "tools/hil/plot_data.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <string>

#include "hal/axis.hpp"

namespace tnv::hil {

using nlohmann::json;

namespace {

constexpr const char* kBoringPositionColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#8c564b", "#e377c2"};

// Eight significant digits: a plot's data needs no more (1 nm at 10 mm),
// and nlohmann writes each value in its shortest form, a third of the
// seventeen digits of an unrounded double.
std::vector<double> rounded(std::vector<double> v) {
  for (double& x : v)
    if (std::isfinite(x) && x != 0.0) {
      const double scale = std::pow(10.0, 7 - static_cast<int>(std::floor(std::log10(std::fabs(x)))));
      x = std::round(x * scale) / scale;
    }
  return v;
}

std::string printf_text(const char* pattern, double v) {
  char buf[160];
  std::snprintf(buf, sizeof buf, pattern, v);
  return buf;
}

template <typename Sample, typename Get>
json arsc_series(const std::string& label, const std::vector<Sample>& trace, Get get, const char* style = "line",
                 const char* color = nullptr) {
  std::vector<double> t, v;
  t.reserve(trace.size());
  v.reserve(trace.size());
  for (const Sample& p : trace) {
    t.push_back(p.t_s);
    v.push_back(get(p));
  }
  return plot_series(label, std::move(t), std::move(v), style, color);
}

template <typename Get>
std::vector<double> per_part(const std::vector<BoringPartRecord>& parts, Get get) {
  std::vector<double> out;
  out.reserve(parts.size());
  for (const BoringPartRecord& p : parts) out.push_back(get(p));
  return out;
}

template <typename Get>
json per_cycle(const std::string& label, const std::vector<SoakCycle>& cycles, Get get, const char* style) {
  std::vector<double> t, v;
  for (const SoakCycle& c : cycles) {
    t.push_back(c.start_s / 60.0);
    v.push_back(get(c));
  }
  return plot_series(label, std::move(t), std::move(v), style);
}

}  // namespace

json plot_series(const std::string& label, std::vector<double> x, std::vector<double> y, const char* style,
                 const char* color) {
  json s = {{"label", label}, {"x", rounded(std::move(x))}, {"y", rounded(std::move(y))}, {"style", style}};
  if (color != nullptr) s["color"] = color;
  return s;
}

json circle_plot_data(std::string_view title, double radius_mm, const std::vector<PlotRow>& rows) {
  json out = {{"kind", "circle"}, {"title", title}, {"radius_mm", radius_mm}, {"suppressed", 0.998}, {"rows", json::array()}};
  for (const PlotRow& row : rows) {
    std::vector<double> t, x, y, rx, ry, e;
    if (row.trace != nullptr)
      for (const TraceSample& s : *row.trace) {
        t.push_back(s.t_s);
        x.push_back(s.position_mm[0]);
        y.push_back(s.position_mm[1]);
        rx.push_back(s.reference_mm[0]);
        ry.push_back(s.reference_mm[1]);
        e.push_back(s.contour_um);
      }
    out["rows"].push_back({{"label", row.label},
                           {"stats", {{"max_um", row.stats.max_um}, {"mean_um", row.stats.mean_um}, {"std_um", row.stats.std_um}}},
                           {"t_s", rounded(t)}, {"x_mm", rounded(x)}, {"y_mm", rounded(y)}, {"ref_x_mm", rounded(rx)},
                           {"ref_y_mm", rounded(ry)}, {"contour_um", rounded(e)}});
  }
  return out;
}

json arsc_run_plot_data(const ArscRunResult& run) {
  const auto& tr = run.trace;
  const double t_end = run.config.duration_s;
  const double ref = run.config.force_ref;
  const char* est = run.config.variant == ArscVariant::robust ? "g^ (estimate)" : "-phi112^ (ARV(2) estimate)";
  json panels = json::array();
  panels.push_back({{"y_label", "force f (normalised)"}, {"y_range", {0.0, 2.0 * ref}}, {"band", {0.9 * ref, 1.1 * ref}},
                    {"band_label", "f* +-10%"},
                    {"series", {arsc_series("f", tr, [](const ArscTracePoint& q) { return q.force; }),
                                plot_series("f*", {0.0, t_end}, {ref, ref}, "dashed", "#2ca02c")}}});
  panels.push_back({{"y_label", "feed v, depth (mm)"}, {"y_range", {0.0, 4.0}},
                    {"series", {arsc_series("feed v", tr, [](const ArscTracePoint& q) { return q.feed; }),
                                arsc_series("depth (mm)", tr, [](const ArscTracePoint& q) { return q.depth_mm; }, "dashed", "#7f7f7f")}}});
  panels.push_back({{"y_label", "input u"}, {"y_range", {-2.0, 8.0}},
                    {"series", {arsc_series("u applied", tr, [](const ArscTracePoint& q) { return q.u; }, "line", "#9467bd")}}});
  panels.push_back({{"y_label", "gains"}, {"y_cap", {-100.0, 100.0}},
                    {"series", {arsc_series("k", tr, [](const ArscTracePoint& q) { return q.gains.k; }),
                                arsc_series("gamma01", tr, [](const ArscTracePoint& q) { return q.gains.gamma01; }),
                                arsc_series("gamma11", tr, [](const ArscTracePoint& q) { return q.gains.gamma11; }),
                                arsc_series("gamma31", tr, [](const ArscTracePoint& q) { return q.gains.gamma31; })}}});
  panels.push_back({{"y_label", "cutting gain"}, {"y_cap", {-2.0, 3.0}},
                    {"series", {arsc_series("b21 delta (process)", tr, [](const ArscTracePoint& q) { return q.true_cutting_gain; },
                                            "reference", "#444444"),
                                arsc_series(est, tr, [](const ArscTracePoint& q) { return q.cutting_gain; })}}});
  char title[200];
  std::snprintf(title, sizeof title, "S3 ARSC %s, %s (T = %.2f s): force error after %.0f s max %.1f%%, rms %.1f%%%s",
                to_string(run.config.variant), fw::arsc::to_string(run.config.poles), run.config.process.sample_s,
                run.config.settle_s, run.force_error_max_pct, run.force_error_rms_pct, run.diverged ? ", DIVERGED" : "");
  return {{"kind", "panels"}, {"title", title}, {"x_label", "time (s)"}, {"panels", panels}};
}

json arsc_compare_plot_data(const std::vector<ArscRunResult>& faithful, const std::vector<ArscRunResult>& robust) {
  json panels = json::array();
  for (int v = 0; v < 2; ++v) {
    const auto& runs = v == 0 ? faithful : robust;
    json series = json::array();
    for (const ArscRunResult& r : runs) {
      std::string label = fw::arsc::to_string(r.config.poles);
      if (!r.first_gains_s) label += " no gains ever";
      else if (r.diverged) label += " diverged";
      else label += printf_text(" max %.0f%%", r.force_error_max_pct);
      series.push_back(arsc_series(label, r.trace, [](const ArscTracePoint& q) { return q.force; }));
    }
    panels.push_back({{"y_label", v == 0 ? "faithful: force f" : "robust: force f"}, {"y_range", {0.0, 2.0}},
                      {"band", {0.9, 1.1}}, {"band_label", "f* = 1 +-10%"}, {"series", series}});
  }
  return {{"kind", "panels"},
          {"title", "S3 ARSC, four pole sets: the paper's loop (top) and the robust variant (bottom)"},
          {"x_label", "time (s)"},
          {"panels", panels}};
}

json arsc_tick_plot_data(const std::vector<TickStudyResult>& runs) {
  double ref_n = 150.0, t_end = 1.0;
  for (const TickStudyResult& r : runs) {
    ref_n = r.config.force_ref_n;
    t_end = std::max(t_end, r.config.duration_s);
  }
  json force = json::array(), error = json::array(), feed = json::array(), gain = json::array();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const TickStudyResult& r = runs[i];
    const std::string label = r.config.label + (r.diverged ? ": diverged" : printf_text(": max %.1f%%", r.force_error_max_pct));
    const char* style = r.config.outer_loop ? "line" : "reference";  // the constant-feed baseline underneath
    const char* color = r.config.outer_loop ? nullptr : "#7f7f7f";
    force.push_back(arsc_series(label, r.trace, [](const TickStudyPoint& p) { return p.force_n; }, style, color));
    feed.push_back(arsc_series(label, r.trace, [](const TickStudyPoint& p) { return p.feed_mm_s; }, style, color));
    if (!r.config.outer_loop) continue;
    std::vector<double> t, e;
    for (const TickStudyPoint& p : r.trace)
      if (p.t_s >= r.config.settle_s) {
        t.push_back(p.t_s);
        e.push_back((p.force_n - p.force_ref_n) / ref_n * 100.0);
      }
    error.push_back(plot_series(label, std::move(t), std::move(e)));
    // Estimates of the first and the last force loop only: the others lie between them.
    if (gain.empty() || i + 1 == runs.size())
      gain.push_back(arsc_series(r.config.label + " estimate", r.trace,
                                 [](const TickStudyPoint& p) { return p.cutting_gain_n_per_mm_s; }));
  }
  force.push_back(plot_series("f*", {0.0, t_end}, {ref_n, ref_n}, "dashed", "#2ca02c"));
  if (!runs.empty())
    gain.insert(gain.begin(), arsc_series("true gain, constant-feed run", runs.front().trace,
                                          [](const TickStudyPoint& p) { return p.true_cutting_gain_n_per_mm_s; },
                                          "reference", "#222222"));
  json panels = json::array();
  panels.push_back({{"y_label", "force (N)"}, {"y_range", {0.0, 2.0 * ref_n}}, {"band", {0.9 * ref_n, 1.1 * ref_n}},
                    {"band_label", "f* +-10%"}, {"series", force}});
  panels.push_back({{"y_label", "force error (% of f*)"}, {"y_range", {-10.0, 10.0}}, {"band", {-1.0, 1.0}},
                    {"band_label", "+-1%"}, {"note", "scored part of each run"}, {"series", error}});
  panels.push_back({{"y_label", "table feed (mm/s)"}, {"y_range", {0.0, 100.0}}, {"series", feed}});
  panels.push_back({{"y_label", "cutting gain G (N per mm/s)"}, {"y_range", {0.0, 18.0}}, {"series", gain}});
  return {{"kind", "panels"},
          {"title", "Robust ARSC as the firmware's feed-override source (emulated TNV-40), 150 N, depth 0.2-1.0-0.2 mm"},
          {"x_label", "time (s)"},
          {"panels", panels}};
}

json boring_plot_data(std::string_view title, const BoringRunRequest& r, const BoringSweepResult& s) {
  const std::vector<BoringPartRecord>& parts = s.seed1.parts;
  const std::size_t npos = parts.empty() ? 0 : parts.front().positions.size();
  const double d0 = r.planner.target_deflection_mm;
  const double band = r.planner.band_sigmas * r.band_sigma_mm;
  const std::vector<double> part_no = per_part(parts, [](const BoringPartRecord& p) { return static_cast<double>(p.part); });
  char sub[300];
  std::snprintf(sub, sizeof sub,
                "seed 1 of %d; bad parts %.2f mean / %d max, resets %.2f mean over seeds; gain form %s, reset after %d %s",
                s.seeds, s.bad_parts_mean, s.bad_parts_max, s.resets_mean, fw::to_string(r.planner.gain_form),
                r.planner.reset_after, fw::to_string(r.planner.reset_count));
  json deflection = json::array(), infeed = json::array();
  for (std::size_t i = 0; i < npos; ++i) {
    const std::string at = printf_text("L = %.0f mm", parts.front().positions[i].overhang_mm);
    const char* color = kBoringPositionColors[i % std::size(kBoringPositionColors)];
    deflection.push_back(plot_series("true d at " + at, part_no,
                                     per_part(parts, [i](const BoringPartRecord& p) { return p.positions[i].true_deflection_mm; }),
                                     "line", color));
    deflection.back()["markers"] = true;
    deflection.push_back(plot_series("measured at " + at, part_no,
                                     per_part(parts, [i](const BoringPartRecord& p) { return p.positions[i].measured_deflection_mm; }),
                                     "rings", color));
    infeed.push_back(plot_series("optimal S at " + at, part_no,
                                 per_part(parts, [i](const BoringPartRecord& p) { return p.positions[i].optimal_infeed_mm_rev; }),
                                 "steps", color));
    infeed.push_back(plot_series("S at " + at, part_no,
                                 per_part(parts, [i](const BoringPartRecord& p) { return p.positions[i].infeed_mm_rev; }), "line", color));
    infeed.back()["markers"] = true;
  }
  std::vector<double> bad_parts, reset_parts, bad_d, reset_d;
  for (const BoringPartRecord& p : parts) {
    if (p.bad) bad_parts.push_back(p.part), bad_d.push_back(d0 + 6.0 * band);
    if (p.reset) reset_parts.push_back(p.part), reset_d.push_back(d0 - 6.0 * band);
  }
  deflection.push_back(plot_series("bad part", bad_parts, bad_d, "dots", "#d62728"));
  deflection.push_back(plot_series("P reset", reset_parts, reset_d, "dots", "#7b3fa0"));
  json exps = {plot_series("true alpha", part_no, per_part(parts, [](const BoringPartRecord& p) { return p.true_alpha; }), "steps", "#ff7f0e"),
               plot_series("alpha estimate", part_no, per_part(parts, [](const BoringPartRecord& p) { return p.alpha_hat; }), "line", "#ff7f0e"),
               plot_series("true beta", part_no, per_part(parts, [](const BoringPartRecord& p) { return p.true_beta; }), "steps", "#17becf"),
               plot_series("beta estimate", part_no, per_part(parts, [](const BoringPartRecord& p) { return p.beta_hat; }), "line", "#17becf")};
  json c = {plot_series("true C", part_no, per_part(parts, [](const BoringPartRecord& p) { return p.true_c_mm; }), "steps", "#8c564b"),
            plot_series("C estimate", part_no, per_part(parts, [](const BoringPartRecord& p) { return p.c_hat_mm; }), "line", "#8c564b")};
  std::vector<double> all_parts;
  for (std::size_t i = 0; i < s.bad_fraction_by_part.size(); ++i) all_parts.push_back(static_cast<double>(i) + 1.0);
  json bad = plot_series(printf_text("bad part (%.0f seeds)", s.seeds), all_parts, s.bad_fraction_by_part, "bars", "#d62728");
  bad["width"] = 0.38;
  bad["offset"] = -0.38;
  json reset = plot_series("P reset", all_parts, s.reset_fraction_by_part, "bars", "#7b3fa0");
  reset["width"] = 0.38;
  reset["offset"] = 0.0;
  std::vector<double> changes;
  for (int at : r.change_at) changes.push_back(at - 0.5);
  json panels = json::array();
  panels.push_back({{"y_label", "deflection d (mm)"}, {"y_range", {std::max(0.0, d0 - 6.0 * band), d0 + 6.0 * band}},
                    {"band", {d0 - band, d0 + band}}, {"band_label", printf_text("d0 ± %.3g mm", band)},
                    {"series", deflection}, {"legend_columns", 3}});
  panels.push_back({{"y_label", "infeed S (mm/rev)"}, {"log_y", true}, {"series", infeed}, {"legend_columns", 2}});
  panels.push_back({{"y_label", "exponents"}, {"y_cap", {-1.0, 3.0}}, {"series", exps}});
  panels.push_back({{"y_label", "C (mm)"}, {"y_cap", {0.0, 1.0}}, {"series", c}});
  panels.push_back({{"y_label", "share of seeds"}, {"y_range", {0.0, 1.0}}, {"series", {bad, reset}}});
  return {{"kind", "panels"}, {"title", title}, {"subtitle", sub}, {"x_label", "part number"},
          {"vlines", {{"x", changes}, {"label", "process change"}, {"color", "#999999"}}}, {"panels", panels}};
}

json soak_plot_data(const SoakResult& r, std::string_view scenario_name) {
  char title[200];
  std::snprintf(title, sizeof title, "Soak: %.2f h simulated, %zu cycles of the S1 circle + rest + 4 jogs (%.*s)",
                r.simulated_s / 3600.0, r.cycles.size(), static_cast<int>(scenario_name.size()), scenario_name.data());
  char sub[300];
  std::snprintf(sub, sizeof sub, "missed ticks %llu, late %llu; %u clock wraps; encoder count drift %lld counts; stationary: %s",
                static_cast<unsigned long long>(r.counters.missed_ticks), static_cast<unsigned long long>(r.counters.late_ticks),
                r.clock_wraps, static_cast<long long>(r.max_encoder_drift_counts), r.stationary ? "yes" : "NO");
  const auto& cy = r.cycles;
  const char* joined = "line";
  json contour = {per_cycle("max contour error", cy, [](const SoakCycle& c) { return c.circle.max_um; }, joined),
                  per_cycle("mean", cy, [](const SoakCycle& c) { return c.circle.mean_um; }, joined),
                  per_cycle("std", cy, [](const SoakCycle& c) { return c.circle.std_um; }, "dashed")};
  for (auto& s : contour) s["markers"] = true;
  // One colour per axis, light for the whole cycle's max and dark at rest.
  struct AxisColours {
    const char* dark;
    const char* light;
  };
  constexpr AxisColours kColours[] = {{"#1f77b4", "#9ecae1"}, {"#ff7f0e", "#fdd0a2"}, {"#2ca02c", "#a1d99b"},
                                      {"#d62728", "#fcbba1"}};
  static_assert(hal::kAxisCount <= std::size(kColours), "the soak figure needs a colour for every axis");
  json rest = json::array();
  json d_hat_max = json::array();
  json d_hat_rest = json::array();
  for (const hal::Axis axis : hal::kAxes) {
    const std::size_t i = hal::index(axis);
    const std::string upper(1, hal::axis_upper_name(axis));
    rest.push_back(per_cycle(i == 0 ? upper + " reference - position" : upper, cy,
                             [i](const SoakCycle& c) { return c.rest_error_um[i]; }, "dots"));
    d_hat_max.push_back(per_cycle("max |d_hat| " + upper + ", whole cycle", cy,
                                  [i](const SoakCycle& c) { return c.max_abs_d_hat_mm_s[i]; }, "reference"));
    d_hat_max.back()["color"] = kColours[i].light;
    d_hat_rest.push_back(per_cycle(upper + " d_hat at rest", cy,
                                   [i](const SoakCycle& c) { return c.rest_d_hat_mm_s[i]; }, "dots"));
    d_hat_rest.back()["color"] = kColours[i].dark;
  }
  json d_hat = d_hat_max;
  for (const json& series : d_hat_rest) d_hat.push_back(series);
  std::vector<double> wraps;
  for (double w : r.clock_wrap_s) wraps.push_back(w / 60.0);
  json panels = json::array();
  panels.push_back({{"y_label", "contour error per circle (um)"}, {"series", contour}});
  panels.push_back({{"y_label", "position error at rest (um)"}, {"note", "one encoder count = 0.417 um"}, {"series", rest}});
  panels.push_back({{"y_label", "DDC estimate d_hat (mm/s)"},
                    {"note", "at rest d_hat holds the stiction on whichever side the table stopped"},
                    {"series", d_hat}, {"legend_columns", 2}});
  return {{"kind", "panels"}, {"title", title}, {"subtitle", sub},
          {"x_label", "simulated time (min); one point per cycle, at its start"},
          {"vlines", {{"x", wraps}, {"label", "32-bit clock wrap"}, {"color", "#7b3fa0"}}}, {"panels", panels}};
}

}  // namespace tnv::hil
