#include "tools/hil/shaper_design_report.hpp"

#include <cmath>
#include <cstdio>

#include "firmware/shaper/residual_vibration.hpp"

namespace tnv::hil {

namespace {

// Ratios 0.50, 0.55, ..., 1.50 (integer steps: no drift).
nlohmann::json residual_table(const fw::ShaperDesign& d, const fw::ModeSpec& mode) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i <= 20; ++i) {
    const double ratio = std::round(50.0 + 5.0 * i) / 100.0;
    const double f = ratio * mode.freq_hz;
    rows.push_back({{"ratio", ratio},
                    {"percent", 100.0 * fw::residual_vibration(d.taps, d.period_s, f, mode.zeta)},
                    {"continuous_percent", 100.0 * fw::residual_vibration(d.impulses, f, mode.zeta)}});
  }
  return rows;
}

}  // namespace

nlohmann::json shaper_design_json(const fw::ShaperSpec& spec) {
  const fw::ShaperDesign d = fw::design_shaper(spec, kShaperPeriodS);
  nlohmann::json j;
  j["type"] = fw::to_string(spec.type);
  j["freq_hz"] = spec.mode.freq_hz;
  j["zeta"] = spec.mode.zeta;
  j["freq2_hz"] = spec.has_second_mode() ? nlohmann::json(spec.second_mode.freq_hz) : nlohmann::json(nullptr);
  j["period_s"] = d.period_s;
  nlohmann::json impulses = nlohmann::json::array();
  for (std::size_t i = 0; i < d.impulses.count; ++i)
    impulses.push_back({{"t_s", d.impulses.impulse[i].t_s}, {"a", d.impulses.impulse[i].a}});
  nlohmann::json taps = nlohmann::json::array();
  for (std::size_t i = 0; i < d.taps.count; ++i) taps.push_back({{"k", d.taps.tap[i].k}, {"a", d.taps.tap[i].a}});
  j["impulses"] = impulses;
  j["taps"] = taps;
  j["delay_s"] = d.delay_s();
  j["duration_s"] = d.duration_s();
  j["continuous_delay_s"] = d.impulses.centroid_s();
  j["continuous_duration_s"] = d.impulses.duration_s();
  j["residual"] = residual_table(d, spec.mode);
  j["band_5pct"] = fw::insensitivity_band(d.taps, d.period_s, spec.mode.freq_hz, spec.mode.zeta).width();
  j["band_5pct_continuous"] = fw::insensitivity_band(d.impulses, spec.mode.freq_hz, spec.mode.zeta).width();
  if (spec.has_second_mode()) {
    j["residual_second_mode"] = residual_table(d, spec.second_mode);
    j["band_5pct_second_mode"] =
        fw::insensitivity_band(d.taps, d.period_s, spec.second_mode.freq_hz, spec.second_mode.zeta).width();
  }
  return j;
}

std::string shaper_design_text(const fw::ShaperSpec& spec) {
  const nlohmann::json j = shaper_design_json(spec);
  std::string out;
  char buf[512];
  std::snprintf(buf, sizeof buf, "%s shaper, %.4g Hz, zeta %.4g", fw::to_string(spec.type), spec.mode.freq_hz,
                spec.mode.zeta);
  out += buf;
  if (spec.has_second_mode()) {
    std::snprintf(buf, sizeof buf, " x %.4g Hz, zeta %.4g", spec.second_mode.freq_hz, spec.second_mode.zeta);
    out += buf;
  }
  std::snprintf(buf, sizeof buf, " (grid %.0f us)\n\ncontinuous impulses:\n", j["period_s"].get<double>() * 1e6);
  out += buf;
  for (const auto& i : j["impulses"]) {
    std::snprintf(buf, sizeof buf, "  t = %9.4f ms   A = %.6f\n", i["t_s"].get<double>() * 1e3, i["a"].get<double>());
    out += buf;
  }
  out += "taps on the grid (exact at the mode):\n";
  for (const auto& t : j["taps"]) {
    std::snprintf(buf, sizeof buf, "  k = %4d        a = %.6f\n", t["k"].get<int>(), t["a"].get<double>());
    out += buf;
  }
  std::snprintf(buf, sizeof buf,
                "duration %.1f ms (continuous %.3f ms), delay (centroid) %.3f ms (continuous %.3f ms)\n"
                "5%% band: %.3f of the design frequency (continuous %.3f)\n\nresidual vibration, %% (at zeta %.4g):\n"
                "  ratio   taps   continuous\n",
                j["duration_s"].get<double>() * 1e3, j["continuous_duration_s"].get<double>() * 1e3,
                j["delay_s"].get<double>() * 1e3, j["continuous_delay_s"].get<double>() * 1e3,
                j["band_5pct"].get<double>(), j["band_5pct_continuous"].get<double>(), spec.mode.zeta);
  out += buf;
  for (const auto& r : j["residual"]) {
    std::snprintf(buf, sizeof buf, "  %5.2f %7.3f %8.3f\n", r["ratio"].get<double>(), r["percent"].get<double>(),
                  r["continuous_percent"].get<double>());
    out += buf;
  }
  if (spec.has_second_mode()) {
    std::snprintf(buf, sizeof buf, "second mode: residual at its design frequency %.3g %%, 5%% band %.3f\n",
                  j["residual_second_mode"][10]["percent"].get<double>(), j["band_5pct_second_mode"].get<double>());
    out += buf;
  }
  return out;
}

}  // namespace tnv::hil
