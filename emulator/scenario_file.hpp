#pragma once
// Scenarios from TOML files (toml++) and the built-in set. Every key is
// optional; defaults come from scenario.hpp. Errors are one line:
//   "scen.toml:7:1: plant.x.tau_s: must be > 0 and finite (got -1)"
// and on error no Scenario is returned (nothing half-applied).
//
// Keys: name; [plant.x] / [plant.y]: tau_s gain coulomb_mm_s stiction_mm_s
// stribeck_mm_s mode_hz mode_zeta backlash_um lead_error_um_per_m
// pitch_error_um pitch_period_mm accel_limit_mm_s2; [cutting]: enabled spindle_rpm flutes
// mean_mm_s amplitude_mm_s exponent phase_rad; [encoder]: counts_per_rev
// lead_mm offset_counts_x offset_counts_y; [dac]: bits full_scale_v
// rpm_at_full_scale; [force_sensor]: volts_per_mm_s volts_per_n; [milling];
// [board]: clock_start; [noise]: seed force_adc_v_rms accel_g_rms
// accel_bias_g dac_offset_v dac_gain_error encoder_glitch_per_s
// encoder_glitch_counts bore_gauge_um_rms bore_gauge_resolution_um;
// [io]: read_latency_us write_latency_us jitter_us;
// [circle]: radius_mm feed_mm_s ramp_s dwell_s; [[fault]] (any number):
// kind start_s and, by kind, axis side duration_s code ticks delay_us
// (fault_schedule.hpp; errors name "fault[i].key", i from 0). Integers are
// accepted where numbers are expected, not the other way round.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "emulator/scenario.hpp"

namespace tnv::emu {

struct ScenarioResult {
  std::optional<Scenario> scenario;
  std::string error;  // empty on success
  bool unknown_key = false;  // the error is a key or section the format does not have
};

// A scenario is a few kB of TOML; past kMaxScenarioBytes (1 MiB) it is refused,
// as is anything but a regular file (text_file.hpp).
inline constexpr std::size_t kMaxScenarioBytes = std::size_t{1} << 20;
ScenarioResult load_scenario_file(const std::string& path);
ScenarioResult parse_scenario_text(std::string_view text, std::string_view source_name);
// `base` with the keys of `overlay` (this format, e.g. "plant.x.gain = 1.1")
// applied on top, then the whole scenario checked as a file is: a campaign
// run's scenario (tools/campaign).
ScenarioResult apply_scenario_text(const Scenario& base, std::string_view overlay, std::string_view source_name);

// Built-ins: no-cut, cut-900, cut-1200, cut-1500, flex-30, flex-100,
// bench-no-cut, bench-cut-1200.
std::optional<Scenario> builtin_scenario(std::string_view name);
std::vector<std::string> builtin_scenario_names();

// A built-in name if it is one, else a file path.
ScenarioResult resolve_scenario(std::string_view name_or_path);

}  // namespace tnv::emu
