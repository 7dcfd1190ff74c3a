#include "tools/can/freq_response_text.hpp"

#include <cmath>
#include <cstdio>

namespace tnv::can_host {

namespace {

std::string freq_value_text(bool exists, double v, const char* format) {
  if (!exists || !std::isfinite(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

std::string freq_margins_row(const char* label, const tune::BodeMargins& m, double bandwidth_hz) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "%-22s %10s %10s %12s %12s\n", label,
                freq_value_text(std::isfinite(m.gain_margin_db), m.gain_margin_db, "%.2f").c_str(),
                freq_value_text(m.crossover_found, m.phase_margin_deg, "%.2f").c_str(),
                freq_value_text(m.crossover_found, m.crossover_hz, "%.2f").c_str(),
                freq_value_text(true, bandwidth_hz, "%.2f").c_str());
  return buf;
}

}  // namespace

std::string freq_response_text(const FreqResponseResult& r) {
  std::string out;
  char buf[200];
  std::snprintf(buf, sizeof buf, "axis %s, %s loop, %s excitation, controller %s; model: %s\n",
                hal::axis_label(r.axis), tune::to_string(r.loop),
                r.kind == fw::ExcitationKind::multisine        ? "multisine"
                : r.kind == fw::ExcitationKind::multisine_open ? "open-loop multisine"
                                                               : "sweep",
                r.controller.c_str(),
                r.plant_model.c_str());
  out += buf;
  const FreqResponseOptions& o = r.options;
  std::snprintf(buf, sizeof buf, "closed-loop experiment: %u tones, level %.3g mm/s, carrier %.6g mm/s, %.3g s\n",
                o.loop_tones.value_or(0), o.loop_level_mm_s.value_or(0.0), o.carrier_mm_s.value_or(0.0),
                o.duration_s.value_or(0.0));
  out += buf;
  std::snprintf(buf, sizeof buf, "%zu ticks recorded, %d averages, lowest coherence %.3f%s\n", r.samples, r.averages,
                r.min_coherence, r.observer_enabled ? " (speed observer on: the model leaves it out)" : "");
  out += buf;
  std::snprintf(buf, sizeof buf, "%10s %10s %10s %10s %12s %12s\n", "freq_hz", "gain_db", "phase_deg", "coherence",
                "model_db", "model_deg");
  out += buf;
  for (const FreqResponsePoint& p : r.points) {
    std::snprintf(buf, sizeof buf, "%10.3f %10.3f %10.2f %10.4f %12.3f %12.2f\n", p.freq_hz, tune::gain_db(p.measured),
                  tune::phase_deg(p.measured), p.coherence, tune::gain_db(p.model), tune::phase_deg(p.model));
    out += buf;
  }
  out += "\nmargins (open loop)      gain_db  phase_deg crossover_hz bandwidth_hz\n";
  out += freq_margins_row("measured", r.margins, r.bandwidth_hz);
  out += freq_margins_row("model (implemented)", r.model.margins, r.model.bandwidth_hz);
  out += freq_margins_row("model (design)", r.design.margins, r.design.bandwidth_hz);
  return out;
}

}  // namespace tnv::can_host
