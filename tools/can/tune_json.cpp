#include "tools/can/tune_json.hpp"

#include <algorithm>

namespace tnv::can_host {

nlohmann::json identification_json(const tune::AxisIdentification& id) {
  nlohmann::json steps = nlohmann::json::array();
  for (std::size_t i = 0; i < id.steps.size(); ++i)
    steps.push_back({{"level_mm_s", id.step_records[i].level_mm_s},
                     {"tau_s", id.steps[i].tau_s},
                     {"speed_mm_s", id.steps[i].speed_mm_s},
                     {"rms_residual_um", id.steps[i].rms_residual_mm * 1000.0}});
  nlohmann::json ramps = nlohmann::json::array();
  for (const tune::RampRecord& r : id.ramps) ramps.push_back({{"broke_away", r.broke_away}, {"breakaway_mm_s", r.breakaway_mm_s}});
  return {{"axis", hal::axis_label(id.axis)},
          {"ok", id.ok},
          {"error", id.error},
          {"tau_s", id.tau_s},
          {"gain", id.gain},
          {"coulomb_mm_s", id.coulomb_mm_s},
          {"stiction_mm_s", id.stiction_mm_s},
          {"stribeck_mm_s_assumed", tune::kAssumedStribeck_mm_s},
          {"A", {{id.model.A(0, 0), id.model.A(0, 1)}, {id.model.A(1, 0), id.model.A(1, 1)}}},
          {"B", {id.model.B(0), id.model.B(1)}},
          {"steps", steps},
          {"ramps", ramps},
          {"mode", mode_fit_json(id.mode_fit)}};
}

nlohmann::json design_json(const tune::AxisDesign& d) {
  const fw::SlidingModeParams& p = d.sliding;
  return {{"ok", d.ok},
          {"error", d.error},
          {"model", {{"a12", d.model.A(0, 1)}, {"a22", d.model.A(1, 1)}, {"b1", d.model.B(0)}, {"b2", d.model.B(1)}}},
          {"sliding",
           {{"G_position_1_s", p.G_position_1_s},
            {"G_speed", p.G_speed},
            {"eta_mm_s", p.eta_mm_s},
            {"phi_mm_s", p.phi_mm_s},
            {"q", p.q},
            {"g", p.g},
            {"gamma", p.gamma}}},
          {"theorem2_phi_bound_mm_s", p.eta_mm_s / (p.q + 1.0)},
          {"theorem5_gamma_bound", std::min(1.0 - p.g, p.q)},
          {"pid", {{"kp", d.pid.kp}, {"ki", d.pid.ki}, {"kd", d.pid.kd}}},
          {"friction",
           {{"coulomb_mm_s", d.friction.coulomb_mm_s},
            {"stiction_mm_s", d.friction.stiction_mm_s},
            {"stribeck_mm_s", d.friction.stribeck_mm_s},
            {"gain", d.friction.gain}}},
          {"observer",
           {{"enabled", d.observer.enabled},
            {"use_position", d.observer.use_position},
            {"sigma_speed_mm_s", d.observer_noise.speed_mm_s},
            {"sigma_disturbance_mm_s", d.observer_noise.disturbance_mm_s},
            {"gain_position", d.observer.gain_position},
            {"gain_speed_1_s", d.observer.gain_speed_1_s},
            {"gain_disturbance_1_s", d.observer.gain_disturbance_1_s},
            {"friction_mm_s", d.observer.friction_mm_s},
            {"friction_deadband_mm_s", d.observer.friction_deadband_mm_s}}},
          {"shaper", shaper_choice_json(d.shaper)},
          {"spectral_radius", {{"rdvsc", d.rdvsc_spectral_radius}, {"dvsc", d.dvsc_spectral_radius}, {"pid", d.pid_spectral_radius}}}};
}

nlohmann::json mode_fit_json(const tune::ModeFit& fit) {
  return {{"found", fit.found},
          {"note", fit.note},
          {"freq_hz", fit.freq_hz},
          {"zeta", fit.zeta},
          {"ring_amplitude_mm_s2", fit.ring_amplitude_mm_s2},
          {"explained_share", fit.explained_share},
          {"residual_rms_mm_s2", fit.residual_rms_mm_s2},
          {"samples", fit.samples}};
}

nlohmann::json shaper_choice_json(const tune::ShaperChoice& choice) {
  return {{"enable", choice.enabled},
          {"type", choice.enabled ? fw::to_string(choice.spec.type) : "none"},
          {"freq_hz", choice.enabled ? choice.spec.mode.freq_hz : 0.0},
          {"zeta", choice.enabled ? choice.spec.mode.zeta : 0.0},
          {"note", choice.note}};
}

}  // namespace tnv::can_host
