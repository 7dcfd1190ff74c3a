// tnv-hil screw-map / screw-fit: measure a ball screw's lead error against
// a table-side reference and turn it into the firmware's compensation
// parameters (tools/hil/screw_map_run.hpp, tools/tune/screw_fit.hpp;
// docs/robustness.md "Lead-error table").
#include <CLI/CLI.hpp>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "hal/axis_choice.hpp"
#include "emulator/text_file.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "tools/can/param_file.hpp"
#include "tools/can/param_text.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/hil/screw_map_run.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"
#include "tools/tune/screw_fit.hpp"

namespace tnv::cli {

namespace {

constexpr std::size_t kMaxGaugeFileBytes = 16u << 20;

struct FitOutputs {
  std::string axis = "x";
  double period_mm = 10.0;
  std::string params_out;
  bool json = false;
};

struct ScrewMapCliOptions {
  hil::ScrewMapOptions map;
  FitOutputs fit;
  std::string scenario = "bench-no-cut";
  std::string gauge_out;
  std::vector<std::string> params_files;
  std::vector<std::string> sets;
};

struct ScrewFitCliOptions {
  std::string gauge_file;
  FitOutputs fit;
};

// The fit as the axis' screw.* parameters (backlash_rate stays as the node has it).
std::vector<can_host::ParamValue> fit_params(const tune::ScrewFit& fit, const std::string& axis) {
  std::vector<can_host::ParamValue> out;
  const auto add = [&](const std::string& name, double value) {
    out.push_back({can_host::find_param_by_text(axis + ".screw." + name), value});
  };
  add("backlash_um", std::max(0.0, fit.backlash_um));
  add("lead_um_per_m", fit.lead_um_per_m);
  add("turn_period_mm", fit.turn_period_mm);
  for (std::size_t j = 0; j < fit.turn_error_um.size(); ++j)
    add("turn_error_um." + std::to_string(j), fit.turn_error_um[j]);
  return out;
}

int report_fit(const tune::ScrewFit& fit, const FitOutputs& o, const std::string& source) {
  const std::vector<can_host::ParamValue> params = fit_params(fit, o.axis);
  if (!o.params_out.empty()) {
    can_host::NodeIdentity identity;
    identity.protocol_version = fw::can::kProtocolVersion;
    const std::string text = can_host::write_param_file(0, identity, "", params, "tnv-hil screw-fit of " + source);
    if (!write_file_replacing(o.params_out, text)) {
      std::fprintf(stderr, "tnv-hil: cannot write %s\n", o.params_out.c_str());
      return kExitFailure;
    }
    std::fprintf(stderr, "[params] wrote %s (tnvctl params import, tnv-hil circle --params)\n", o.params_out.c_str());
  }
  if (o.json) {
    nlohmann::json p = nlohmann::json::object();
    for (const can_host::ParamValue& v : params) p[v.param->name] = v.value;
    const nlohmann::json out = {{"source", source},
                                {"axis", o.axis},
                                {"points", fit.points},
                                {"span_mm", fit.span_mm},
                                {"backlash_um", fit.backlash_um},
                                {"lead_um_per_m", fit.lead_um_per_m},
                                {"turn_period_mm", fit.turn_period_mm},
                                {"turn_error_um", fit.turn_error_um},
                                {"error_rms_um", fit.error_rms_um},
                                {"residual_rms_um", fit.residual_rms_um},
                                {"residual_max_um", fit.residual_max_um},
                                {"params", p}};
    std::cout << out.dump(2) << "\n";
    return kExitOk;
  }
  std::printf("screw fit of %s (%s axis): %zu points over %.3f mm\n", source.c_str(), o.axis.c_str(), fit.points,
              fit.span_mm);
  std::printf("  backlash        %8.3f um\n", fit.backlash_um);
  std::printf("  lead error      %8.3f um/m\n", fit.lead_um_per_m);
  std::printf("  per-turn table  (period %.3f mm, um):", fit.turn_period_mm);
  for (const double e : fit.turn_error_um) std::printf(" %.3f", e);
  std::printf("\n  reading error   %8.3f um rms before the fit, %.3f um rms (max %.3f) left\n", fit.error_rms_um,
              fit.residual_rms_um, fit.residual_max_um);
  return kExitOk;
}

std::optional<tune::ScrewFit> fit_or_report(const std::vector<hil::GaugePoint>& points, double period_mm,
                                           const std::string& source) {
  std::string error;
  std::optional<tune::ScrewFit> fit = tune::fit_screw(points, period_mm, error);
  if (!fit) std::fprintf(stderr, "tnv-hil: %s: %s\n", source.c_str(), error.c_str());
  return fit;
}

int run_screw_map(ScrewMapCliOptions o) {
  const std::optional<emu::Scenario> scenario = resolve_scenario_or_report(o.scenario);
  if (!scenario) return kExitBadInput;
  const std::optional<fw::FirmwareConfig> config = firmware_config_or_report(o.params_files, o.sets);
  if (!config) return kExitBadInput;
  o.map.axis = hal::axis_from_name(o.fit.axis).value_or(hal::Axis::y);
  if (const std::string why = hil::validate(o.map); !why.empty()) {
    std::fprintf(stderr, "tnv-hil: screw-map: %s\n", why.c_str());
    return kExitBadInput;
  }
  const hil::ScrewMapResult run = hil::run_screw_map(*scenario, *config, o.map);
  if (!run.completed) {
    std::fprintf(stderr, "tnv-hil: screw-map on %s: %s\n", scenario->name.c_str(), run.error.c_str());
    return kExitFailure;
  }
  const std::string source = "screw-map " + o.fit.axis + " on " + scenario->name;
  if (!o.gauge_out.empty()) {
    const std::string comment = o.fit.axis + " axis, " + scenario->name + ", tnv-hil screw-map seed " +
                                std::to_string(o.map.seed) + "\nthe table reading is the emulator's true table position"
                                " plus a reference noise of " + std::to_string(o.map.reference_noise_um_rms) + " um rms";
    if (!write_file_replacing(o.gauge_out, hil::write_gauge_file(comment, run.points))) {
      std::fprintf(stderr, "tnv-hil: cannot write %s\n", o.gauge_out.c_str());
      return kExitFailure;
    }
    std::fprintf(stderr, "[gauge] wrote %s (%zu points)\n", o.gauge_out.c_str(), run.points.size());
  }
  const std::optional<tune::ScrewFit> fit = fit_or_report(run.points, o.fit.period_mm, source);
  return fit ? report_fit(*fit, o.fit, source) : kExitFailure;
}

int run_screw_fit(const ScrewFitCliOptions& o) {
  std::string text, error;
  if (!emu::read_text_file(o.gauge_file, kMaxGaugeFileBytes, text, error)) {
    std::fprintf(stderr, "tnv-hil: %s\n", error.c_str());
    return kExitBadInput;
  }
  const std::optional<std::vector<hil::GaugePoint>> points = hil::read_gauge_file(text, error);
  if (!points) {
    std::fprintf(stderr, "tnv-hil: %s: %s\n", o.gauge_file.c_str(), error.c_str());
    return kExitBadInput;
  }
  const std::optional<tune::ScrewFit> fit = fit_or_report(*points, o.fit.period_mm, o.gauge_file);
  return fit ? report_fit(*fit, o.fit, o.gauge_file) : kExitBadInput;
}

void add_fit_outputs(CLI::App* cmd, FitOutputs& o) {
  cmd->add_option("--axis", o.axis, hal::kAxisChoices)
      ->check(CLI::IsMember(std::vector<std::string>(hal::kAxisNames.begin(), hal::kAxisNames.end())))->capture_default_str();
  cmd->add_option("--period-mm", o.period_mm, "the per-turn table's period: the screw's lead")
      ->check(CLI::Range(0.1, 1000.0))
      ->capture_default_str();
  cmd->add_option("--params-out", o.params_out, "write the axis' screw.* parameters as a parameter file")
      ->check(OutputFile());
  cmd->add_flag("--json", o.json, "print JSON on stdout");
}

}  // namespace

void add_screw_commands(CLI::App& app, Runner& run) {
  auto map = std::make_shared<ScrewMapCliOptions>();
  CLI::App* map_cmd = app.add_subcommand(
      "screw-map", "measure an axis' lead error against the table (a laser run on the emulated machine) and fit it");
  add_fit_outputs(map_cmd, map->fit);
  map_cmd->add_option("--scenario", map->scenario, "built-in name or TOML file")->capture_default_str();
  map_cmd->add_option("--start-mm", map->map.start_mm, "first point")->capture_default_str();
  map_cmd->add_option("--length-mm", map->map.length_mm, "travel covered forward, then back")->capture_default_str();
  map_cmd->add_option("--step-mm", map->map.step_mm, "between points")->capture_default_str();
  map_cmd->add_option("--reference-noise-um", map->map.reference_noise_um_rms, "the reference's noise, rms")
      ->capture_default_str();
  map_cmd->add_option("--seed", map->map.seed, "of the reference's noise")->capture_default_str();
  map_cmd->add_option("--gauge-out", map->gauge_out, "write the measured points (tnv-hil screw-fit reads them)")
      ->check(OutputFile());
  map_cmd->add_option("--params", map->params_files, "a parameter file applied before --set (measure what is left; repeatable)")
      ->check(CLI::ExistingFile);
  map_cmd->add_option("--set", map->sets, "NAME=VALUE: a firmware parameter as on the node (repeatable)");
  map_cmd->callback([&run, map] { run = [map] { return run_screw_map(*map); }; });

  auto fit = std::make_shared<ScrewFitCliOptions>();
  CLI::App* fit_cmd = app.add_subcommand(
      "screw-fit", "fit backlash, lead error and the per-turn table to a measured file (position_mm,direction,table_mm)");
  fit_cmd->add_option("file", fit->gauge_file, "the measurement (tnv-hil screw-map --gauge-out, or a laser's)")
      ->required();
  add_fit_outputs(fit_cmd, fit->fit);
  fit_cmd->callback([&run, fit] { run = [fit] { return run_screw_fit(*fit); }; });
}

}  // namespace tnv::cli
