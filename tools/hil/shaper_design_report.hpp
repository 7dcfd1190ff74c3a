#pragma once
// `tnv-hil shaper design`: the continuous impulses, the taps as implemented
// on the 1 kHz grid, duration, delay, residual vibration at frequency
// ratios 0.5..1.5 and the 5 % band (as a fraction of the design frequency).
#include <nlohmann/json.hpp>
#include <string>

#include "firmware/shaper/shaper_design.hpp"

namespace tnv::hil {

inline constexpr double kShaperPeriodS = 1e-3;

// Requires fw::validate(spec).ok.
// Keys: impulses [{t_s, a}], taps [{k, a}], delay_s, duration_s,
// residual [{ratio, percent, continuous_percent}] (actual / design
// frequency of the first mode, at the design damping), band_5pct,
// band_5pct_continuous, and the spec (type, freq_hz, zeta, freq2_hz);
// with a second mode also residual_second_mode and band_5pct_second_mode.
nlohmann::json shaper_design_json(const fw::ShaperSpec& spec);
std::string shaper_design_text(const fw::ShaperSpec& spec);

}  // namespace tnv::hil
