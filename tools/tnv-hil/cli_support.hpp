#pragma once
// Shared pieces of the tnv-hil subcommands: exit codes, progress on
// stderr, scenario resolution, and writing outputs with clear errors.
#include <CLI/CLI.hpp>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/control/axis_controller.hpp"
#include "firmware/tick/firmware_config.hpp"
#include <nlohmann/json.hpp>

#include "tools/hil/plot_data.hpp"

namespace tnv::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;   // a run failed or an output could not be written
inline constexpr int kExitBadInput = 2;  // bad command line or scenario: nothing was run

// Set by the chosen subcommand's parse callback; main() calls it.
using Runner = std::function<int()>;

// Progress on stderr: a live line on a terminal, a few lines otherwise.
class Progress {
 public:
  explicit Progress(std::string label);
  void operator()(std::size_t done, std::size_t total);

 private:
  std::string label_;
  bool tty_;
  std::mutex mutex_;
};

// A built-in scenario name or a TOML file; prints a one-line error and
// returns nullopt when neither works.
std::optional<emu::Scenario> resolve_scenario_or_report(const std::string& name_or_file);

// A scenario with [io] in a build without the work meter (hil::io_work_unmetered):
// a warning on stderr, and "io_work_unmetered": true in a command's JSON
// (the key is absent otherwise). resolve_scenario_or_report() warns itself.
void warn_if_io_work_unmetered(const emu::Scenario& scenario);
void note_io_work_unmetered(nlohmann::json& j, const emu::Scenario& scenario);

// "pid", "dvsc" or "rdvsc" (fw::to_string's names); prints a one-line error
// and returns nullopt for anything else.
std::optional<fw::ControllerKind> controller_or_report(const std::string& name);

// The papers' firmware configuration with NAME=VALUE parameter assignments
// (the node's parameter names and ranges: x.screw.backlash_um=10), the
// whole set validated; nullopt after a one-line message on stderr.
std::optional<fw::FirmwareConfig> firmware_config_or_report(const std::vector<std::string>& assignments);
// The same with parameter files' [params] (tnvctl params export, tnv-hil
// screw-fit --params-out) applied first, in order.
std::optional<fw::FirmwareConfig> firmware_config_or_report(const std::vector<std::string>& params_files,
                                                            const std::vector<std::string>& assignments);

// The four scenarios of S1 Table 3 (no-cut, cut-900, cut-1200, cut-1500);
// nullopt, after the error is printed, when one cannot be built.
std::optional<std::vector<emu::Scenario>> resolve_table3_scenarios_or_report();

// Write helpers: print a one-line error on failure and return false.
bool write_text(const std::string& path, const std::string& content);
// A figure (SVG, PNG or PDF by its suffix) from its plot data (tools/hil/plot_data.hpp).
bool write_figure(const std::string& path, const nlohmann::json& plot_data);
bool write_plot(const std::string& path, const std::string& title, double radius_mm,
                const std::vector<hil::PlotRow>& rows);

}  // namespace tnv::cli
