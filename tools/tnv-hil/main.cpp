// tnv-hil: hardware-in-the-loop runs of the TNV-40 firmware on the emulated
// I/O board and table: the S1 circle, Table 3, and the plant check.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/circle_plot.hpp"
#include "tools/hil/plant_check.hpp"
#include "tools/hil/report.hpp"
#include "tools/hil/seed_sweep.hpp"

namespace {

using namespace tnv;

constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;  // a run failed or an output could not be written
constexpr int kExitBadInput = 2; // bad command line or scenario: nothing was run

// Progress on stderr: a live line on a terminal, a few lines otherwise.
class Progress {
 public:
  explicit Progress(std::string label) : label_(std::move(label)), tty_(isatty(STDERR_FILENO) != 0) {}
  void operator()(std::size_t done, std::size_t total) {
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

 private:
  std::string label_;
  bool tty_;
  std::mutex mutex_;
};

std::optional<fw::ControllerKind> parse_controller(const std::string& name) {
  if (name == "pid") return fw::ControllerKind::pid;
  if (name == "dvsc") return fw::ControllerKind::dvsc;
  if (name == "rdvsc") return fw::ControllerKind::rdvsc;
  return std::nullopt;
}

std::optional<emu::Scenario> resolve(const std::string& name_or_file) {
  emu::ScenarioResult found = emu::resolve_scenario(name_or_file);
  if (found.scenario) return std::move(found.scenario);
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

bool write_text(const std::string& path, const std::string& content) {
  std::ofstream out(path, std::ios::trunc);
  out << content;
  out.close();
  if (!out) {
    std::fprintf(stderr, "tnv-hil: %s: cannot write\n", path.c_str());
    return false;
  }
  return true;
}

bool write_plot(const std::string& path, const std::string& title, double radius_mm,
                const std::vector<hil::PlotRow>& rows) {
  std::string error;
  if (!hil::circle_figure(title, radius_mm, rows).save(path, error)) {
    std::fprintf(stderr, "tnv-hil: %s\n", error.c_str());
    return false;
  }
  std::fprintf(stderr, "[plot] wrote %s\n", path.c_str());
  return true;
}

std::string trace_csv(const std::vector<hil::TraceSample>& trace) {
  std::string out = "t_s,x_ref_mm,y_ref_mm,x_mm,y_mm,contour_um,u_x_mm_s,u_y_mm_s,s_x,s_y,d_hat_x_mm_s,d_hat_y_mm_s\n";
  char buf[320];
  for (const hil::TraceSample& t : trace) {
    std::snprintf(buf, sizeof buf, "%.3f,%.9f,%.9f,%.9f,%.9f,%.5f,%.5f,%.5f,%.6g,%.6g,%.6g,%.6g\n", t.t_s,
                  t.reference_mm[0], t.reference_mm[1], t.position_mm[0], t.position_mm[1], t.contour_um,
                  t.command_mm_s[0], t.command_mm_s[1], t.s[0], t.s[1], t.d_hat_mm_s[0], t.d_hat_mm_s[1]);
    out += buf;
  }
  return out;
}

struct CircleOptions {
  std::string controller = "rdvsc";
  std::string scenario = "no-cut";
  int seeds = 1;
  bool json = false;
  std::string plot;
  std::string csv;
};

int run_circle_command(const CircleOptions& o) {
  const auto kind = parse_controller(o.controller);
  const auto scenario = resolve(o.scenario);
  if (!kind || !scenario) return kExitBadInput;
  const fw::FirmwareConfig config = fw::default_firmware_config();
  Progress progress("circle");
  hil::SweepRequest request{{*scenario}, {*kind}, o.seeds, !o.plot.empty() || !o.csv.empty(), 0, {}};
  if (o.seeds > 1) request.progress = std::ref(progress);
  const std::vector<hil::SweepCell> cells = hil::run_sweep(request, config);
  const hil::SweepCell& cell = cells.front();
  if (o.json) {
    nlohmann::json j = {{"results", hil::results_json(cells, o.seeds)}, {"pid_gains", hil::pid_gains_json(config)}};
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << hil::circle_text(cell, o.seeds);
    if (*kind == fw::ControllerKind::pid) std::cout << hil::pid_gains_text(config);
  }
  bool ok = cell.error.empty();
  if (!o.plot.empty()) {
    const std::string title = "S1 circle, " + cell.scenario + ", " + fw::to_string(cell.controller) + " (seed 0)";
    ok = write_plot(o.plot, title, scenario->circle.radius_mm,
                    {{fw::to_string(cell.controller), cell.seed0.stats, &cell.seed0.trace}}) && ok;
  }
  if (!o.csv.empty()) ok = write_text(o.csv, trace_csv(cell.seed0.trace)) && ok;
  if (!cell.error.empty()) std::fprintf(stderr, "tnv-hil: run failed: %s\n", cell.error.c_str());
  return ok ? kExitOk : kExitFailure;
}

struct Table3Options {
  int seeds = 8;
  bool json = false;
  std::string plot_dir;
};

int run_table3_command(const Table3Options& o) {
  std::vector<emu::Scenario> scenarios;
  for (const char* name : {"no-cut", "cut-900", "cut-1200", "cut-1500"}) {
    auto s = resolve(name);
    if (!s) return kExitFailure;
    scenarios.push_back(*s);
  }
  const fw::FirmwareConfig config = fw::default_firmware_config();
  Progress progress("table3");
  const auto started = std::chrono::steady_clock::now();
  hil::SweepRequest request{scenarios,
                            {fw::ControllerKind::pid, fw::ControllerKind::dvsc, fw::ControllerKind::rdvsc},
                            o.seeds,
                            !o.plot_dir.empty(),
                            0,
                            std::ref(progress)};
  const std::vector<hil::SweepCell> cells = hil::run_sweep(request, config);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  std::fprintf(stderr, "[table3] %zu runs in %.1f s wall\n", cells.size() * static_cast<std::size_t>(o.seeds), wall_s);

  if (o.json) {
    nlohmann::json j = {{"results", hil::results_json(cells, o.seeds)},
                        {"ratios", hil::table3_ratios_json(cells)},
                        {"pid_gains", hil::pid_gains_json(config)}};
    std::cout << j.dump(2) << '\n';
  } else {
    std::cout << hil::table3_text(cells, o.seeds, config);
  }
  bool ok = true;
  for (const auto& c : cells) ok = ok && c.error.empty();
  if (!o.plot_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.plot_dir, ec);
    if (ec) {
      std::fprintf(stderr, "tnv-hil: %s: %s\n", o.plot_dir.c_str(), ec.message().c_str());
      return kExitFailure;
    }
    for (std::size_t s = 0; s < scenarios.size(); ++s) {
      std::vector<hil::PlotRow> rows;
      for (std::size_t c = 0; c < 3; ++c) {
        const hil::SweepCell& cell = cells[s * 3 + c];
        rows.push_back({fw::to_string(cell.controller), cell.seed0.stats, &cell.seed0.trace});
      }
      const std::string path = (std::filesystem::path(o.plot_dir) / ("circle-" + scenarios[s].name + ".svg")).string();
      ok = write_plot(path, "S1 circle, " + scenarios[s].name + " (seed 0): polar plot with 99.8% of R suppressed",
                      scenarios[s].circle.radius_mm, rows) && ok;
    }
  }
  return ok ? kExitOk : kExitFailure;
}

int run_plant_check_command(const std::string& scenario_name, bool json) {
  const auto scenario = resolve(scenario_name);
  if (!scenario) return kExitBadInput;
  const auto axes = hil::plant_check(*scenario);
  if (json)
    std::cout << hil::plant_check_json(axes).dump(2) << '\n';
  else
    std::cout << hil::plant_check_text(axes);
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"tnv-hil: run the TNV-40 firmware against the emulated I/O board and table"};
  app.require_subcommand(1);

  CircleOptions circle;
  CLI::App* circle_cmd = app.add_subcommand("circle", "one S1 circle (radius 6 mm, 2 mm/s) and its contour error");
  circle_cmd->add_option("--controller", circle.controller, "pid | dvsc | rdvsc")
      ->check(CLI::IsMember({"pid", "dvsc", "rdvsc"}))
      ->capture_default_str();
  circle_cmd->add_option("--scenario", circle.scenario, "built-in name (no-cut, cut-900, cut-1200, cut-1500) or TOML file")
      ->capture_default_str();
  circle_cmd->add_option("--seeds", circle.seeds, "average over N encoder offsets / cutting phases")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  circle_cmd->add_flag("--json", circle.json, "print JSON on stdout");
  circle_cmd->add_option("--plot", circle.plot, "write the polar + contour-error plot (SVG)");
  circle_cmd->add_option("--csv", circle.csv, "write the seed-0 trace (CSV)");

  Table3Options table3;
  CLI::App* table3_cmd = app.add_subcommand("table3", "S1 Table 3: 4 scenarios x 3 controllers beside the paper");
  table3_cmd->add_option("--seeds", table3.seeds, "average over N encoder offsets / cutting phases")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  table3_cmd->add_flag("--json", table3.json, "print JSON on stdout");
  table3_cmd->add_option("--plot-dir", table3.plot_dir, "write one SVG figure per scenario here");

  std::string plant_scenario = "no-cut";
  bool plant_json = false;
  CLI::App* plant_cmd = app.add_subcommand("plant-check", "identify the emulated axes' 1 ms A, B beside exact and paper");
  plant_cmd->add_option("--scenario", plant_scenario, "built-in name or TOML file")->capture_default_str();
  plant_cmd->add_flag("--json", plant_json, "print JSON on stdout");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kExitBadInput;
  }

  if (*circle_cmd) return run_circle_command(circle);
  if (*table3_cmd) return run_table3_command(table3);
  if (*plant_cmd) return run_plant_check_command(plant_scenario, plant_json);
  return kExitBadInput;
}
