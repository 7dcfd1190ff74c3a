#include "tools/can/freq_response_cli.hpp"

#include <CLI/CLI.hpp>

namespace tnv::can_host {

void add_freq_response_options(CLI::App& cmd, FreqResponseOptions& o) {
  cmd.add_option_function<std::string>(
         "--loop", [&o](const std::string& v) { tune::parse_loop_kind(v, o.loop); },
         "plant, open or closed (plant: also the open-loop plant experiment)")
      ->check(CLI::IsMember({"plant", "open", "closed"}))
      ->default_str(tune::to_string(o.loop));
  cmd.add_option_function<std::string>(
         "--excitation",
         [&o](const std::string& v) {
           o.kind = v == "sweep" ? fw::ExcitationKind::sweep : fw::ExcitationKind::multisine;
         },
         "the closed-loop experiment: multisine or sweep")
      ->check(CLI::IsMember({"multisine", "sweep"}))
      ->default_str(o.kind == fw::ExcitationKind::sweep ? "sweep" : "multisine");
  cmd.add_option("--plant-level", o.plant_level_mm_s, "mm/s: the plant's open-loop multisine, RMS x sqrt(2)")
      ->capture_default_str();
  cmd.add_option_function<double>(
      "--loop-level", [&o](const double& v) { o.loop_level_mm_s = v; },
      "mm/s: the closed-loop excitation, sweep amplitude / multisine RMS x sqrt(2) (default: PID 20, DVSC / "
      "R-DVSC+DDC 2.4 x the axis' boundary layer phi)");
  cmd.add_option_function<double>(
      "--duration", [&o](const double& v) { o.duration_s = v; },
      "s of record per experiment, multisine: whole periods of 1 / f_min (default: PID 12, DVSC / R-DVSC+DDC 30)");
  cmd.add_option("--f-min", o.f_min_hz, "Hz, lowest frequency of the plant experiment")->capture_default_str();
  cmd.add_option("--f-max", o.f_max_hz, "Hz, highest frequency of the plant experiment")->capture_default_str();
  cmd.add_option("--loop-f-min", o.loop_f_min_hz, "Hz, lowest frequency of the closed-loop experiment")
      ->capture_default_str();
  cmd.add_option("--loop-f-max", o.loop_f_max_hz,
                 "Hz, highest frequency of the closed-loop experiment (<= 450; margins need the phase crossover)")
      ->capture_default_str();
  cmd.add_option("--tones", o.tones, "the plant experiment's tones")->capture_default_str();
  cmd.add_option_function<std::uint32_t>(
      "--loop-tones", [&o](const std::uint32_t& v) { o.loop_tones = v; },
      "the closed-loop experiment's tones / sweep points (default: every harmonic of 1 / period in the band)");
  cmd.add_option("--smooth", o.smooth_half_window,
                 "tones each side: the margins and bandwidth are read off the measured response smoothed by a local "
                 "quadratic fit over them (0: the raw points)")
      ->capture_default_str();
  cmd.add_option_function<double>(
      "--carrier", [&o](const double& v) { o.carrier_mm_s = v; },
      "mm/s: the closed-loop experiment runs while the holding reference moves at this speed (0: a standing "
      "table; default: about 3 mm/s, nudged so the encoder counts per tick and per period are far from whole "
      "numbers); it goes the other way when the soft limits leave no room, and the table moves back after");
}

}  // namespace tnv::can_host
