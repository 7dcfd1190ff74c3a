// homing: the firmware's homing cycle of every axis (tnv-hil homing) from a
// power-up position and encoder phase drawn from the run's seed, on the
// run's table with the reference board's home switches and index marks
// where it has none of its own; judged against the machine's truth.
#include <algorithm>
#include <cmath>

#include "tools/campaign/experiment.hpp"
#include "tools/campaign/manifest.hpp"
#include "tools/hil/homing_json.hpp"
#include "tools/hil/homing_run.hpp"

namespace tnv::campaign {

namespace {

fw::can::NodeSettings homing_base_settings() {
  fw::can::NodeSettings s = fw::can::default_node_settings();
  s.firmware = hil::homing_firmware_config();
  return s;
}

void run_homing_row(const RunContext& c, nlohmann::ordered_json& row) {
  fw::FirmwareConfig config = *c.setup.config;
  for (fw::AxisConfig& a : config.axis) a.controller = *c.run.controller;
  // The power-up (position, count offset, phase) is drawn from the seed.
  const hil::HomingSeedResult r = hil::run_homing_seed(hil::with_homing_board(*c.setup.scenario), config,
                                                       static_cast<std::uint32_t>(c.run.seed));
  const nlohmann::json j = hil::homing_seed_json(r);
  // Where it started is known whether or not it homed.
  for (const std::string& k : hil::homing_start_keys()) row[k] = j.at(k);
  if (!r.homed) {
    row["status"] = r.timed_out ? "timeout" : r.faulted ? "fault" : "error";
    row["reason"] = r.failure;
    return;
  }
  row["status"] = "ok";
  for (const std::string& k : hil::homing_error_keys()) row[k] = j.at(k);
  row["time_s"] = j.at("time_s");
  // As tnv-hil homing's summary: the largest |home error|, here over the axes.
  double home_error_um_max = 0.0;
  for (const double e : r.home_error_um) home_error_um_max = std::max(home_error_um_max, std::fabs(e));
  row["home_error_um_max"] = home_error_um_max;
}

}  // namespace

const Experiment& homing_experiment() {
  static const Experiment e = [] {
    Experiment x;
    x.name = "homing";
    x.controllers = ControllerUse::choose;
    x.results.push_back({"home_error_um_max", "REAL"});
    for (const std::string& k : hil::homing_error_keys()) x.results.push_back({k, "REAL"});
    x.results.push_back({"time_s", "REAL"});
    for (const std::string& k : hil::homing_start_keys()) x.results.push_back({k, "REAL"});
    x.default_metric = "home_error_um_max";
    x.check_settings = [](const nlohmann::ordered_json&, const std::string&, std::string&) { return std::string(); };
    x.check_input = any_input;
    x.base_settings = homing_base_settings;
    x.run = run_homing_row;
    return x;
  }();
  return e;
}

}  // namespace tnv::campaign
