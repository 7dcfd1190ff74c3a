#include "tools/campaign/experiment_row.hpp"

#include <exception>

#include "tools/hil/circle_run.hpp"
#include "tools/hil/seeded_scenario.hpp"

namespace tnv::campaign {

const std::vector<std::string>& result_keys(const std::string& experiment) {
  // circle: the encoder-measured contour error (S1 eq. 33, as the paper
  // scored), and the same from the emulator's truth: the table and the tool point.
  static const std::vector<std::string> circle = {"max_um",          "mean_um",          "std_um",
                                                  "true_table_max_um", "true_table_mean_um", "true_tool_max_um",
                                                  "true_tool_mean_um"};
  static const std::vector<std::string> none;
  return experiment == "circle" ? circle : none;
}

nlohmann::ordered_json run_row(const Manifest& manifest, const ManifestRun& run) {
  nlohmann::ordered_json row = {{"run_id", run.run_id}, {"status", "error"}, {"reason", ""}};
  const std::vector<std::string>& keys = result_keys(manifest.experiment);
  for (const std::string& k : keys) row[k] = nullptr;
  const RunSetup setup = resolve_run_inputs(manifest.base, manifest.inputs, run.inputs);
  if (!setup.scenario) {
    row["reason"] = setup.error;
    return row;
  }
  try {
    const hil::CircleRunResult r = hil::run_circle(hil::seeded(*setup.scenario, run.seed), *setup.config, run.controller);
    if (r.completed) {
      row["status"] = "ok";
      row["max_um"] = r.stats.max_um;
      row["mean_um"] = r.stats.mean_um;
      row["std_um"] = r.stats.std_um;
      row["true_table_max_um"] = r.true_table_stats.max_um;
      row["true_table_mean_um"] = r.true_table_stats.mean_um;
      row["true_tool_max_um"] = r.true_tool_stats.max_um;
      row["true_tool_mean_um"] = r.true_tool_stats.mean_um;
    } else {
      row["status"] = r.timed_out ? "timeout" : r.fault.reason != fw::FaultReason::none ? "fault" : "error";
      row["reason"] = r.error;
    }
  } catch (const std::exception& e) {
    row["status"] = "error";
    row["reason"] = std::string("exception: ") + e.what();
  }
  return row;
}

}  // namespace tnv::campaign
