// tnv-hil shaper design | move | jog | grid: the input shaper (issue 3).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "hal/axis.hpp"
#include "hal/axis_choice.hpp"
#include "emulator/text_file.hpp"
#include "firmware/shaper/grid_taps.hpp"
#include "firmware/shaper/residual_vibration.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/hil/shaper_design_report.hpp"
#include "tools/hil/shaper_jog_run.hpp"
#include "tools/hil/shaper_move_compare.hpp"
#include "tools/hil/plot_data.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

constexpr std::size_t kMaxCommandsBytes = 16u << 20;  // a jog command file of hours, far beyond a test

constexpr const char* kTypes = "zv | zvd | zvdd | ei | mzv";

// Prints "tnv-hil: <what>: <reason>" for a refused spec; false when refused.
bool check_spec(const fw::ShaperSpec& spec) {
  const fw::ParamCheck c = fw::validate(spec);
  if (c.ok) return true;
  std::string field = c.field;
  if (field == "mode.freq_hz") field = "--freq-hz";
  if (field == "mode.zeta") field = "--zeta";
  if (field == "second_mode.freq_hz") field = "--freq2-hz";
  if (field == "second_mode.zeta") field = "--zeta";
  std::fprintf(stderr, "tnv-hil: %s: %s\n", field.c_str(), c.reason);
  return false;
}

nlohmann::json optional_json(const std::optional<double>& v) {
  return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
}

std::string seconds_or_never(const std::optional<double>& v) {
  char buf[32];
  if (!v) return "never";
  std::snprintf(buf, sizeof buf, "%.3f", *v);
  return buf;
}

// --------------------------------------------------------------- design
struct ShaperDesignOptions {
  std::string type;
  double freq_hz = 0.0;
  double freq2_hz = 0.0;
  double zeta = 0.0;
  bool json = false;
  std::string plot;
};

int run_shaper_design(const ShaperDesignOptions& o) {
  const fw::ShaperSpec spec{*fw::parse_shaper_type(o.type), {o.freq_hz, o.zeta}, {o.freq2_hz, o.zeta}};
  if (!check_spec(spec)) return kExitBadInput;
  if (o.json)
    std::cout << hil::shaper_design_json(spec).dump(2) << '\n';
  else
    std::cout << hil::shaper_design_text(spec);
  if (!o.plot.empty() && !write_figure(o.plot, hil::shaper_sensitivity_plot_data(spec))) return kExitFailure;
  return kExitOk;
}

// ----------------------------------------------------------------- move
struct MoveOptions {
  std::string scenario;
  std::string axis = "x";
  double distance_mm = 0.0;
  std::string shaper;
  std::optional<double> freq_hz;
  std::optional<double> zeta;
  double speed_mm_s = 100.0;
  double ramp_s = 0.02;
  int seeds = 1;
  bool json = false;
  std::string plot;
};

nlohmann::json run_json(const hil::MoveRunResult& r) {
  return {{"residual_pp_um", r.residual_pp_um},
          {"settling_s", optional_json(r.settling_s)},
          {"command_end_s", r.command_end_s},
          {"final_error_um", r.final_tool_error_um},
          {"max_following_error_um", r.max_following_error_um},
          {"max_error_vs_unshaped_command_um", r.max_unshaped_error_um}};
}

int run_move_command(const MoveOptions& o) {
  const auto scenario = resolve_scenario_or_report(o.scenario);
  if (!scenario) return kExitBadInput;
  const hal::Axis axis = hal::axis_from_name(o.axis).value_or(hal::Axis::x);
  const emu::AxisPlantParams& plant = scenario->plant[hal::index(axis)];
  if (!o.freq_hz && plant.mode_hz <= 0.0) {
    std::fprintf(stderr, "tnv-hil: scenario %s has no structural mode on axis %s: give --freq-hz\n",
                 scenario->name.c_str(), o.axis.c_str());
    return kExitBadInput;
  }
  const fw::ShaperSpec spec{*fw::parse_shaper_type(o.shaper),
                            {o.freq_hz.value_or(plant.mode_hz), o.zeta.value_or(plant.mode_zeta)},
                            {0.0, 0.0}};
  if (!check_spec(spec)) return kExitBadInput;
  // The ramps must fit: lower the cruise speed if the move is short.
  double speed = o.speed_mm_s;
  if (std::isfinite(o.distance_mm) && speed * o.ramp_s > std::fabs(o.distance_mm) && o.ramp_s > 0.0)
    speed = std::fabs(o.distance_mm) / o.ramp_s;
  const fw::MoveSpec move{axis, o.distance_mm, speed, o.ramp_s, 0.0};
  if (const char* bad = fw::validate(move); bad[0] != '\0') {
    std::fprintf(stderr, "tnv-hil: move: %s\n", bad);
    return kExitBadInput;
  }
  hil::MoveRunRequest request;
  request.scenario = *scenario;
  request.move = move;
  request.shaper = spec;
  request.keep_trace = !o.plot.empty();
  const hil::MoveComparison c = hil::compare_move(request, fw::default_firmware_config(), o.seeds);
  if (!c.error.empty()) {
    std::fprintf(stderr, "tnv-hil: run failed: %s\n", c.error.c_str());
    return kExitFailure;
  }
  const hil::MovePair& p0 = c.pairs.front();
  const fw::ShaperDesign design = fw::design_shaper(spec, hil::kShaperPeriodS);
  const double move_time_s = p0.unshaped.move_time_s;
  if (o.json) {
    nlohmann::json per_seed = nlohmann::json::array();
    for (const hil::MovePair& p : c.pairs)
      per_seed.push_back({{"seed", p.seed}, {"unshaped", run_json(p.unshaped)}, {"shaped", run_json(p.shaped)}});
    nlohmann::json j = {{"scenario", scenario->name},
                        {"axis", o.axis},
                        {"distance_mm", o.distance_mm},
                        {"speed_mm_s", speed},
                        {"ramp_s", o.ramp_s},
                        {"move_time_s", move_time_s},
                        {"shaper",
                         {{"type", o.shaper},
                          {"freq_hz", spec.mode.freq_hz},
                          {"zeta", spec.mode.zeta},
                          {"delay_s", design.delay_s()},
                          {"duration_s", design.duration_s()}}},
                        {"seeds", o.seeds},
                        {"unshaped",
                         {{"residual_pp_um", c.median_unshaped_residual_um},
                          {"settling_s", optional_json(c.median_unshaped_settling_s)},
                          {"move_time_s", move_time_s},
                          {"command_end_s", p0.unshaped.command_end_s}}},
                        {"shaped",
                         {{"residual_pp_um", c.median_shaped_residual_um},
                          {"settling_s", optional_json(c.median_shaped_settling_s)},
                          {"move_time_s", move_time_s},
                          {"command_end_s", p0.shaped.command_end_s}}},
                        {"residual_ratio", c.median_residual_ratio},
                        {"worst_residual_ratio", c.worst_residual_ratio},
                        {"settling_ratio", c.median_settling_ratio},
                        {"per_seed", per_seed}};
    std::cout << j.dump(2) << '\n';
  } else {
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "%s, axis %s: %.4g mm at %.4g mm/s, raised-cosine ramps %.0f ms: move time %.3f s\n"
                  "shaper %s at %.4g Hz, zeta %.3g: delay %.1f ms, duration %.0f ms\n",
                  scenario->name.c_str(), o.axis.c_str(), o.distance_mm, speed, o.ramp_s * 1e3, move_time_s,
                  o.shaper.c_str(), spec.mode.freq_hz, spec.mode.zeta, design.delay_s() * 1e3,
                  design.duration_s() * 1e3);
    std::cout << buf;
    if (o.seeds > 1) std::cout << "medians over " << o.seeds << " encoder phases (seeds)\n";
    std::cout << "                                   unshaped      shaped\n";
    std::snprintf(buf, sizeof buf, "tool residual p-p after command (um) %9.3f   %9.3f   (%.2f %%)\n",
                  c.median_unshaped_residual_um, c.median_shaped_residual_um, 100.0 * c.median_residual_ratio);
    std::cout << buf;
    std::snprintf(buf, sizeof buf, "settling to +-1 um after the move (s)%9s   %9s   (x%.1f)\n",
                  seconds_or_never(c.median_unshaped_settling_s).c_str(),
                  seconds_or_never(c.median_shaped_settling_s).c_str(), c.median_settling_ratio);
    std::cout << buf;
    std::snprintf(buf, sizeof buf, "command end (s, seed 0)              %9.3f   %9.3f\n", p0.unshaped.command_end_s,
                  p0.shaped.command_end_s);
    std::cout << buf;
    std::snprintf(buf, sizeof buf,
                  "max following error (um, seed 0)     %9.2f   %9.2f   (shaped run vs the unshaped command: %.0f)\n",
                  p0.unshaped.max_following_error_um, p0.shaped.max_following_error_um,
                  p0.shaped.max_unshaped_error_um);
    std::cout << buf;
  }
  if (!o.plot.empty()) {
    char title[200];
    std::snprintf(title, sizeof title, "%s: %.4g mm on %s, unshaped vs %s at %.4g Hz (seed 0)", scenario->name.c_str(),
                  o.distance_mm, o.axis.c_str(), o.shaper.c_str(), spec.mode.freq_hz);
    if (!write_figure(o.plot, hil::move_plot_data(title, c))) return kExitFailure;
  }
  return kExitOk;
}

// ------------------------------------------------------------------ jog
struct JogOptions {
  std::string scenario;
  std::string commands;
  std::string shaper = "zvd";
  std::optional<double> freq_hz;
  std::optional<double> zeta;
  std::optional<double> path_accel_mm_s2;  // both axes' planner acceleration (default: the config's)
  std::optional<double> path_jerk_mm_s3;
  bool json = false;
  std::string plot;
};

int run_jog_command(const JogOptions& o) {
  const auto scenario = resolve_scenario_or_report(o.scenario);
  if (!scenario) return kExitBadInput;
  std::string text;
  std::string error;
  if (!emu::read_text_file(o.commands, kMaxCommandsBytes, text, error)) {
    std::fprintf(stderr, "tnv-hil: %s\n", error.c_str());
    return kExitBadInput;
  }
  const auto commands = hil::parse_jog_csv(text, error);
  if (!commands) {
    std::fprintf(stderr, "tnv-hil: %s: %s\n", o.commands.c_str(), error.c_str());
    return kExitBadInput;
  }
  hil::JogRunRequest request;
  request.scenario = *scenario;
  request.commands = *commands;
  request.keep_trace = !o.plot.empty();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    const emu::AxisPlantParams& plant = scenario->plant[i];
    const double f = o.freq_hz.value_or(plant.mode_hz);
    if (f <= 0.0) continue;  // no mode on this axis and none given: unshaped
    const fw::ShaperSpec spec{*fw::parse_shaper_type(o.shaper), {f, o.zeta.value_or(plant.mode_zeta)}, {0.0, 0.0}};
    if (!check_spec(spec)) return kExitBadInput;
    request.shaper[i] = spec;
  }
  if (std::none_of(request.shaper.begin(), request.shaper.end(), [](const auto& spec) { return spec.has_value(); })) {
    std::fprintf(stderr, "tnv-hil: scenario %s has no structural mode: give --freq-hz\n", scenario->name.c_str());
    return kExitBadInput;
  }
  // The jog runs through the planner: its acceleration and jerk set how hard the jog excites the mode.
  fw::FirmwareConfig config = fw::default_firmware_config();
  for (fw::AxisConfig& a : config.axis) {
    a.path.accel_mm_s2 = o.path_accel_mm_s2.value_or(a.path.accel_mm_s2);
    a.path.jerk_mm_s3 = o.path_jerk_mm_s3.value_or(a.path.jerk_mm_s3);
  }
  if (const fw::ConfigError e = fw::validate(config); !e.ok()) {
    std::fprintf(stderr, "tnv-hil: --path-accel / --path-jerk: %s: %s\n", e.section, e.reason);
    return kExitBadInput;
  }
  Progress progress("shaper jog");
  hil::JogRunRequest plain = request;
  plain.shaper = {};
  const hil::JogRunResult u = hil::run_jog(plain, config);
  progress(1, 2);
  const hil::JogRunResult s = hil::run_jog(request, config);
  progress(2, 2);
  for (const hil::JogRunResult* r : {&u, &s})
    if (!r->completed) {
      std::fprintf(stderr, "tnv-hil: run failed (%s): %s\n", r == &u ? "unshaped" : "shaped", r->error.c_str());
      return kExitFailure;
    }
  if (o.json) {
    nlohmann::json axes = nlohmann::json::object();
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const auto one = [&](const hil::JogRunResult& r) {
        const hil::JogAxisResult& a = r.axis[i];
        return nlohmann::json{{"start_mm", a.start_mm},
                              {"end_mm", a.end_mm},
                              {"travel_mm", a.end_mm - a.start_mm},
                              {"residual_pp_um", a.residual_pp_um},
                              {"settling_s", optional_json(a.settling_s)},
                              {"max_following_error_um", a.max_following_error_um},
                              {"shaper_delay_s", a.shaper_delay_s}};
      };
      nlohmann::json ax = {{"unshaped", one(u)}, {"shaped", one(s)}};
      if (request.shaper[i])
        ax["shaper"] = {
            {"type", o.shaper}, {"freq_hz", request.shaper[i]->mode.freq_hz}, {"zeta", request.shaper[i]->mode.zeta}};
      axes[hal::kAxisNames[i]] = ax;
    }
    nlohmann::json j = {{"scenario", scenario->name},
                        {"commands", commands->size()},
                        {"stop_s", {{"unshaped", u.stop_s}, {"shaped", s.stop_s}}},
                        {"deadman_stops", s.deadman_stops},
                        {"refused_commands", s.refused_commands},
                        {"axes", axes}};
    std::cout << j.dump(2) << '\n';
  } else {
    char buf[300];
    std::snprintf(buf, sizeof buf,
                  "%s: %zu jog rows; axes at rest after %.3f s unshaped, %.3f s shaped; dead-man stops %u\n",
                  scenario->name.c_str(), commands->size(), u.stop_s, s.stop_s, s.deadman_stops);
    std::cout << buf;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const hil::JogAxisResult& a = u.axis[i];
      const hil::JogAxisResult& b = s.axis[i];
      std::snprintf(
          buf, sizeof buf,
          "axis %c: travel %.4f mm (shaped %.4f mm, end difference %.3g um); shaper %s\n"
          "        tool residual p-p after the stop %.3f um unshaped, %.3f um shaped; settling +-1 um %s s / %s s\n",
          hal::axis_name(hal::axis_from_index(i)), a.end_mm - a.start_mm, b.end_mm - b.start_mm, (b.end_mm - a.end_mm) * 1e3,
          request.shaper[i]
              ? (o.shaper + " at " + std::to_string(request.shaper[i]->mode.freq_hz).substr(0, 5) + " Hz").c_str()
              : "off",
          a.residual_pp_um, b.residual_pp_um, seconds_or_never(a.settling_s).c_str(),
          seconds_or_never(b.settling_s).c_str());
      std::cout << buf;
    }
  }
  if (!o.plot.empty() &&
      !write_figure(o.plot, hil::jog_plot_data(scenario->name + ": operator jog through the real-time shaper", u, s)))
    return kExitFailure;
  return kExitOk;
}

// ----------------------------------------------------------------- grid
struct GridOptions {
  double zeta = 0.0;
  bool json = false;
  std::string plot;
};

int run_grid_command(const GridOptions& o) {
  if (!std::isfinite(o.zeta) || o.zeta < 0.0 || o.zeta > fw::kShaperMaxZeta) {
    std::fprintf(stderr, "tnv-hil: --zeta: must be finite, 0..0.3\n");
    return kExitBadInput;
  }
  nlohmann::json rows = nlohmann::json::array();
  for (fw::ShaperType t : fw::kShaperTypes) {
    double worst[3] = {0.0, 0.0, 0.0}, at[3] = {0.0, 0.0, 0.0}, band_ratio = 10.0;
    for (int i = 0; i <= 390; ++i) {
      const double f = 5.0 + 0.5 * i;
      const fw::ImpulseTrain cont = fw::design_impulses(t, {f, o.zeta});
      const fw::TapSet taps[3] = {fw::round_to_grid(cont, hil::kShaperPeriodS),
                                  fw::split_to_grid(cont, hil::kShaperPeriodS),
                                  fw::exact_grid_taps(t, {f, o.zeta}, hil::kShaperPeriodS)};
      const double v_cont = fw::residual_vibration(cont, f, o.zeta);
      for (int m = 0; m < 3; ++m) {
        const double v = fw::residual_vibration(taps[m], hil::kShaperPeriodS, f, o.zeta);
        const double excess = fw::zero_at_design_point(t) ? v : std::max(0.0, v - v_cont);
        if (excess > worst[m]) worst[m] = excess, at[m] = f;
      }
      band_ratio =
          std::min(band_ratio, fw::insensitivity_band(taps[2], hil::kShaperPeriodS, f, o.zeta, 0.05 + 1e-9).width() /
                                   fw::insensitivity_band(cont, f, o.zeta, 0.05 + 1e-9).width());
    }
    rows.push_back({{"type", fw::to_string(t)},
                    {"rounding_max_percent", 100.0 * worst[0]},
                    {"rounding_worst_hz", at[0]},
                    {"splitting_max_percent", 100.0 * worst[1]},
                    {"splitting_worst_hz", at[1]},
                    {"exact_max_percent", 100.0 * worst[2]},
                    {"exact_worst_hz", at[2]},
                    {"exact_min_band_ratio", band_ratio}});
  }
  if (o.json) {
    std::cout << nlohmann::json{{"zeta", o.zeta}, {"freq_hz", {5.0, 200.0, 0.5}}, {"types", rows}}.dump(2) << '\n';
  } else {
    char buf[240];
    std::snprintf(buf, sizeof buf,
                  "residual at the design frequency, worst over 5-200 Hz (0.5 Hz steps), zeta %.3g\n"
                  "(EI: what the grid adds to the continuous EI's own 5 %%)\n"
                  "type    rounding          splitting         exact taps        exact band / continuous (worst)\n",
                  o.zeta);
    std::cout << buf;
    for (const auto& r : rows) {
      std::snprintf(buf, sizeof buf, "%-6s %7.3f %% @%5.1f  %7.3f %% @%5.1f  %9.2e %% @%5.1f  %.4f\n",
                    r["type"].get<std::string>().c_str(), r["rounding_max_percent"].get<double>(),
                    r["rounding_worst_hz"].get<double>(), r["splitting_max_percent"].get<double>(),
                    r["splitting_worst_hz"].get<double>(), r["exact_max_percent"].get<double>(),
                    r["exact_worst_hz"].get<double>(), r["exact_min_band_ratio"].get<double>());
      std::cout << buf;
    }
  }
  if (!o.plot.empty() && !write_figure(o.plot, hil::grid_method_plot_data({fw::ShaperType::zv, fw::ShaperType::zvd,
                                                                     fw::ShaperType::zvdd, fw::ShaperType::mzv},
                                                                    o.zeta)))
    return kExitFailure;
  return kExitOk;
}

}  // namespace

void add_shaper_commands(CLI::App& app, Runner& run) {
  CLI::App* shaper =
      app.add_subcommand("shaper", "input shaper: design, HIL point-to-point move, HIL jog stream, grid methods");
  shaper->require_subcommand(1);

  auto d = std::make_shared<ShaperDesignOptions>();
  CLI::App* design =
      shaper->add_subcommand("design", "impulses, taps on the 1 ms grid, delay, residual vibration, 5 % band");
  design->add_option("--type", d->type, kTypes)->required()->check(CLI::IsMember({"zv", "zvd", "zvdd", "ei", "mzv"}));
  design->add_option("--freq-hz", d->freq_hz, "mode frequency, 5..200 Hz")->required();
  design->add_option("--freq2-hz", d->freq2_hz, "second mode (two-mode shaper by convolution), 5..200 Hz");
  design->add_option("--zeta", d->zeta, "damping ratio of the mode(s), 0..0.3")->capture_default_str();
  design->add_flag("--json", d->json, "print JSON on stdout");
  design->add_option("--plot", d->plot, "write the sensitivity curves (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  design->callback([&run, d] { run = [d] { return run_shaper_design(*d); }; });

  auto m = std::make_shared<MoveOptions>();
  CLI::App* move =
      shaper->add_subcommand("move", "HIL point-to-point move, unshaped and shaped, scored at the tool point");
  move->add_option("--scenario", m->scenario, "built-in name (flex-30, flex-100, ...) or TOML file")->required();
  move->add_option("--axis", m->axis, hal::kAxisChoices)
      ->check(CLI::IsMember(std::vector<std::string>(hal::kAxisNames.begin(), hal::kAxisNames.end())))->capture_default_str();
  move->add_option("--distance-mm", m->distance_mm, "signed move distance")->required();
  move->add_option("--shaper", m->shaper, kTypes)->required()->check(CLI::IsMember({"zv", "zvd", "zvdd", "ei", "mzv"}));
  move->add_option("--freq-hz", m->freq_hz, "shaper frequency (default: the scenario's mode on that axis)");
  move->add_option("--zeta", m->zeta, "shaper damping (default: the scenario's mode damping)");
  move->add_option("--speed-mm-s", m->speed_mm_s, "cruise speed (lowered if the ramps do not fit)")
      ->capture_default_str();
  move->add_option("--ramp-s", m->ramp_s, "raised-cosine speed ramp at each end")->capture_default_str();
  move->add_option("--seeds", m->seeds, "median over N encoder phases")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  move->add_flag("--json", m->json, "print JSON on stdout");
  move->add_option("--plot", m->plot, "write the seed-0 traces (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  move->callback([&run, m] { run = [m] { return run_move_command(*m); }; });

  auto j = std::make_shared<JogOptions>();
  CLI::App* jog =
      shaper->add_subcommand("jog", "HIL operator jog stream (CSV " + hil::jog_csv_header() + ") through the real-time shaper");
  jog->add_option("--scenario", j->scenario, "built-in name or TOML file")->required();
  jog->add_option("--commands", j->commands,
                  "CSV: " + hil::jog_csv_header() + "; each row held until the next, silence after the last")
      ->required();
  jog->add_option("--shaper", j->shaper, kTypes)
      ->check(CLI::IsMember({"zv", "zvd", "zvdd", "ei", "mzv"}))
      ->capture_default_str();
  jog->add_option("--freq-hz", j->freq_hz,
                  "shaper frequency on both axes (default: each axis' scenario mode; none: off)");
  jog->add_option("--zeta", j->zeta, "shaper damping (default: the scenario's mode damping)");
  jog->add_option("--path-accel", j->path_accel_mm_s2,
                  "the planner's acceleration on both axes, mm/s^2 (the jog gets half of it along its line)")
      ->check(CLI::Range(1.0, 1e6));
  jog->add_option("--path-jerk", j->path_jerk_mm_s3, "the planner's jerk limit on both axes, mm/s^3")
      ->check(CLI::Range(1.0, 1e9));
  jog->add_flag("--json", j->json, "print JSON on stdout");
  jog->add_option("--plot", j->plot, "write the traces (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  jog->callback([&run, j] { run = [j] { return run_jog_command(*j); }; });

  auto g = std::make_shared<GridOptions>();
  CLI::App* grid = shaper->add_subcommand(
      "grid", "residual left at the design frequency by rounding, splitting and the exact taps, 5-200 Hz");
  grid->add_option("--zeta", g->zeta, "damping ratio, 0..0.3")->capture_default_str();
  grid->add_flag("--json", g->json, "print JSON on stdout");
  grid->add_option("--plot", g->plot, "write the residual-vs-frequency figure (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  grid->callback([&run, g] { run = [g] { return run_grid_command(*g); }; });
}

}  // namespace tnv::cli
