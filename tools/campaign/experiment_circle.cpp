// circle: the S1 circle (tnv-hil circle), scored by the encoders (S1 eq.
// (33), as the paper scored) and by the emulator's truth at the table and
// at the tool point.
#include "tools/campaign/experiment.hpp"
#include "tools/campaign/manifest.hpp"
#include "tools/hil/circle_run.hpp"
#include "tools/hil/seeded_scenario.hpp"

namespace tnv::campaign {

namespace {

void run_circle_row(const RunContext& c, nlohmann::ordered_json& row) {
  const hil::CircleRunResult r =
      hil::run_circle(hil::seeded(*c.setup.scenario, c.run.seed), *c.setup.config, *c.run.controller);
  if (!r.completed) {
    row["status"] = r.timed_out ? "timeout" : r.fault.reason != fw::FaultReason::none ? "fault" : "error";
    row["reason"] = r.error;
    return;
  }
  row["status"] = "ok";
  row["max_um"] = r.stats.max_um;
  row["mean_um"] = r.stats.mean_um;
  row["std_um"] = r.stats.std_um;
  row["true_table_max_um"] = r.true_table_stats.max_um;
  row["true_table_mean_um"] = r.true_table_stats.mean_um;
  row["true_tool_max_um"] = r.true_tool_stats.max_um;
  row["true_tool_mean_um"] = r.true_tool_stats.mean_um;
}

}  // namespace

const Experiment& circle_experiment() {
  static const Experiment e = [] {
    Experiment x;
    x.name = "circle";
    x.controllers = ControllerUse::choose;
    for (const char* k : {"max_um", "mean_um", "std_um", "true_table_max_um", "true_table_mean_um", "true_tool_max_um",
                          "true_tool_mean_um"})
      x.results.push_back({k, "REAL"});
    x.default_metric = "max_um";
    x.check_settings = [](const nlohmann::ordered_json&, const std::string&, std::string&) { return std::string(); };
    x.check_input = any_input;
    x.base_settings = default_base_settings;
    x.run = run_circle_row;
    return x;
  }();
  return e;
}

}  // namespace tnv::campaign
