#include "tools/tnv-hil/cli_support.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "emulator/scenario_file.hpp"
#include "emulator/text_file.hpp"
#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_table.hpp"
#include "tools/can/param_assignments.hpp"
#include "tools/can/param_file.hpp"
#include "tools/can/param_text.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/cli/run_plotter.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::cli {

Progress::Progress(std::string label) : label_(std::move(label)), tty_(isatty(STDERR_FILENO) != 0) {}

void Progress::operator()(std::size_t done, std::size_t total) {
  std::lock_guard lock(mutex_);
  const auto quarter = std::max<std::size_t>(1, total / 4);
  if (tty_) {
    std::fprintf(stderr, "\r[%s] %zu/%zu runs", label_.c_str(), done, total);
    if (done == total) std::fputc('\n', stderr);
  } else if (done % quarter == 0 || done == total) {
    std::fprintf(stderr, "[%s] %zu/%zu runs\n", label_.c_str(), done, total);
  }
  std::fflush(stderr);
}

std::optional<emu::Scenario> resolve_scenario_or_report(const std::string& name_or_file) {
  emu::ScenarioResult found = emu::resolve_scenario(name_or_file);
  if (found.scenario) {
    warn_if_io_work_unmetered(*found.scenario);
    return std::move(found.scenario);
  }
  if (name_or_file.find_first_of("./") == std::string::npos && !std::filesystem::exists(name_or_file)) {
    std::string names;
    for (const std::string& n : emu::builtin_scenario_names()) names += (names.empty() ? "" : ", ") + n;
    std::fprintf(stderr, "tnv-hil: '%s' is neither a built-in scenario (%s) nor a file\n", name_or_file.c_str(),
                 names.c_str());
  } else {
    std::fprintf(stderr, "tnv-hil: %s\n", found.error.c_str());
  }
  return std::nullopt;
}

void warn_if_io_work_unmetered(const emu::Scenario& scenario) {
  if (!hil::io_work_unmetered(scenario)) return;
  std::fprintf(stderr,
               "tnv-hil: warning: scenario '%s' has [io] on, but this tnv-hil is built without the work meter "
               "(TNV_WORK_METER=OFF): each output write lands with no firmware work before it, so its timing "
               "differs from a metered build's (docs/performance.md)\n",
               scenario.name.c_str());
}

void note_io_work_unmetered(nlohmann::json& j, const emu::Scenario& scenario) {
  if (hil::io_work_unmetered(scenario)) j["io_work_unmetered"] = true;
}

std::optional<fw::ControllerKind> controller_or_report(const std::string& name) {
  for (const fw::ControllerKind kind : {fw::ControllerKind::pid, fw::ControllerKind::dvsc, fw::ControllerKind::rdvsc})
    if (name == fw::to_string(kind)) return kind;
  std::fprintf(stderr, "tnv-hil: controller '%s': not pid, dvsc or rdvsc\n", name.c_str());
  return std::nullopt;
}

std::optional<std::vector<emu::Scenario>> resolve_table3_scenarios_or_report() {
  std::vector<emu::Scenario> scenarios;
  for (const char* name : {"no-cut", "cut-900", "cut-1200", "cut-1500"}) {
    auto s = resolve_scenario_or_report(name);
    if (!s) return std::nullopt;
    scenarios.push_back(*s);
  }
  return scenarios;
}

bool write_text(const std::string& path, const std::string& content) {
  if (!write_file_replacing(path, content)) {
    std::fprintf(stderr, "tnv-hil: %s: cannot write\n", path.c_str());
    return false;
  }
  return true;
}

bool write_figure(const std::string& path, const nlohmann::json& plot_data) {
  return plot_json(path, plot_data, "tnv-hil");
}

bool write_plot(const std::string& path, const std::string& title, double radius_mm,
                const std::vector<hil::PlotRow>& rows) {
  return write_figure(path, hil::circle_plot_data(title, radius_mm, rows));
}

std::optional<fw::FirmwareConfig> firmware_config_or_report(const std::vector<std::string>& assignments) {
  can_host::AssignmentsResult r = can_host::firmware_config_from_assignments(assignments);
  if (!r.config) std::fprintf(stderr, "tnv-hil: --set %s\n", r.error.c_str());
  return r.config;
}

std::optional<fw::FirmwareConfig> firmware_config_or_report(const std::vector<std::string>& params_files,
                                                            const std::vector<std::string>& assignments) {
  constexpr std::size_t kMaxParamFileBytes = 1 << 20;
  std::vector<std::string> all;
  for (const std::string& path : params_files) {
    std::string text, error;
    if (!emu::read_text_file(path, kMaxParamFileBytes, text, error)) {
      std::fprintf(stderr, "tnv-hil: --params: %s\n", error.c_str());
      return std::nullopt;
    }
    const std::optional<can_host::ParamFile> file = can_host::read_param_file(text, error);
    if (!file) {
      std::fprintf(stderr, "tnv-hil: --params: %s: %s\n", path.c_str(), error.c_str());
      return std::nullopt;
    }
    for (const can_host::ParamValue& v : file->params)
      all.push_back(std::string(v.param->name) + "=" + can_host::format_param_value(*v.param, v.value));
  }
  all.insert(all.end(), assignments.begin(), assignments.end());  // --set after the files: it wins
  return firmware_config_or_report(all);
}

}  // namespace tnv::cli
