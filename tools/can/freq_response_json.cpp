#include "tools/can/freq_response_json.hpp"

#include <cmath>

namespace tnv::can_host {

namespace {

nlohmann::json freq_number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json freq_margins_json(const tune::BodeMargins& m, double bandwidth_hz) {
  return {{"gain_db", freq_number_or_null(m.gain_margin_db)},
          {"phase_deg", m.crossover_found ? nlohmann::json(m.phase_margin_deg) : nlohmann::json(nullptr)},
          {"crossover_hz", m.crossover_found ? nlohmann::json(m.crossover_hz) : nlohmann::json(nullptr)},
          {"phase_crossover_hz", std::isfinite(m.gain_margin_db) ? nlohmann::json(m.phase_crossover_hz)
                                                                 : nlohmann::json(nullptr)},
          {"bandwidth_hz", freq_number_or_null(bandwidth_hz)}};
}

const char* freq_excitation_name(fw::ExcitationKind k) {
  return k == fw::ExcitationKind::multisine        ? "multisine"
         : k == fw::ExcitationKind::sweep          ? "sweep"
         : k == fw::ExcitationKind::multisine_open ? "multisine_open"
                                                   : "?";
}

}  // namespace

nlohmann::json freq_response_json(const FreqResponseResult& r) {
  nlohmann::json points = nlohmann::json::array();
  for (const FreqResponsePoint& p : r.points)
    points.push_back({{"freq_hz", p.freq_hz},
                      {"gain_db", tune::gain_db(p.measured)},
                      {"phase_deg", tune::phase_deg(p.measured)},
                      {"coherence", p.coherence},
                      {"model_gain_db", tune::gain_db(p.model)},
                      {"model_phase_deg", tune::phase_deg(p.model)}});
  return {{"axis", hal::axis_label(r.axis)},
          {"loop", tune::to_string(r.loop)},
          {"excitation", freq_excitation_name(r.kind)},
          {"controller", r.controller},
          {"plant_model", r.plant_model},
          {"observer_enabled", r.observer_enabled},
          {"points", points},
          {"margins", freq_margins_json(r.margins, r.bandwidth_hz)},
          {"model_margins", freq_margins_json(r.model.margins, r.model.bandwidth_hz)},
          {"design_margins", freq_margins_json(r.design.margins, r.design.bandwidth_hz)},
          {"loop_experiment", {{"tones", r.options.loop_tones.value_or(0)},
                               {"level_mm_s", r.options.loop_level_mm_s.value_or(0.0)},
                               {"carrier_mm_s", r.options.carrier_mm_s.value_or(0.0)},
                               {"duration_s", r.options.duration_s.value_or(0.0)}}},
          {"samples", r.samples},
          {"averages", r.averages},
          {"min_coherence", r.min_coherence}};
}

}  // namespace tnv::can_host
