// The named scenarios every tool knows (scenario_file.hpp).
#include <array>

#include "emulator/scenario_file.hpp"

namespace tnv::emu {

namespace {

Scenario named(std::string_view name) {
  Scenario s;
  s.name = std::string(name);
  return s;
}

// S1 experiment: cutting at 900/1200/1500 rpm -> 30/40/50 Hz with 2 flutes.
Scenario cutting_at(std::string_view name, double spindle_rpm) {
  Scenario s = named(name);
  s.cutting.enabled = true;
  s.cutting.spindle_rpm = spindle_rpm;
  return s;
}

// S2 XY stage: lightly damped 30 Hz / 100 Hz mode on X, for input shaping.
Scenario flexible_x(std::string_view name, double mode_hz) {
  Scenario s = named(name);
  s.plant[0].mode_hz = mode_hz;
  s.plant[0].mode_zeta = 0.02;
  return s;
}

// The reference table as a real bench would show it: the magnitudes and
// their sources are in docs/scenarios.md "Bench profiles".
Scenario bench(Scenario s) {
  // A Linux board's SPI transport to the FPGA: snapshot read, output write, scheduling jitter.
  s.io = IoParams{.read_latency_us = 100.0, .write_latency_us = 50.0, .jitter_us = 50.0};
  s.noise.seed = 1;
  s.noise.force_adc_v_rms = 0.004;   // 12-bit 0-10 V channel (2.44 mV LSB): about 1.6 LSB rms
  s.noise.accel_g_rms = 0.0006;      // ADXL355 class: 22.5 ug/sqrt(Hz) over a 500 Hz band
  s.noise.accel_bias_g = 0.025;      // a MEMS part's zero-g offset: tens of mg
  s.noise.dac_offset_v = 0.005;      // 12-bit +-10 V DAC: about 1 LSB (4.88 mV)
  s.noise.dac_gain_error = 0.002;    // 0.2 %
  s.noise.bore_gauge_um_rms = 1.0;          // S4's post-process gauge: a bore gauge's repeatability (um class)
  s.noise.bore_gauge_resolution_um = 1.0;   // a 0.001 mm digital indicator
  for (AxisPlantParams& p : s.plant) {
    p.backlash_um = 10.0;        // a worn ball screw (5-20 um)
    p.pitch_error_um = 4.0;      // C5: v_2pi = 8 um peak to peak within one turn
    p.pitch_period_mm = 10.0;    // one turn of the 10 mm lead
  }
  // C5: v_300 = 18 um per 300 mm = 60 um/m, opposite signs (an ellipse, not a scale)
  s.plant[0].lead_error_um_per_m = 60.0;
  s.plant[1].lead_error_um_per_m = -60.0;
  return s;
}

constexpr std::array<std::string_view, 8> kNames{"no-cut",   "cut-900", "cut-1200",     "cut-1500",
                                                 "flex-30",  "flex-100", "bench-no-cut", "bench-cut-1200"};

}  // namespace

std::optional<Scenario> builtin_scenario(std::string_view name) {
  if (name == "no-cut") return named(name);
  if (name == "cut-900") return cutting_at(name, 900.0);
  if (name == "cut-1200") return cutting_at(name, 1200.0);
  if (name == "cut-1500") return cutting_at(name, 1500.0);
  if (name == "flex-30") return flexible_x(name, 30.0);
  if (name == "flex-100") return flexible_x(name, 100.0);
  if (name == "bench-no-cut") return bench(named(name));
  if (name == "bench-cut-1200") return bench(cutting_at(name, 1200.0));
  return std::nullopt;
}

std::vector<std::string> builtin_scenario_names() { return {kNames.begin(), kNames.end()}; }

ScenarioResult resolve_scenario(std::string_view name_or_path) {
  if (auto builtin = builtin_scenario(name_or_path)) return ScenarioResult{std::move(builtin), {}, false};
  return load_scenario_file(std::string(name_or_path));
}

}  // namespace tnv::emu
