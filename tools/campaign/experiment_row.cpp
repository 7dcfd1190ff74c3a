#include "tools/campaign/experiment_row.hpp"

#include <exception>

#include "tools/hil/hil_rig.hpp"

namespace tnv::campaign {

const std::vector<ResultKey>& result_keys(const std::string& experiment) {
  static const std::vector<ResultKey> none;
  const Experiment* e = find_experiment(experiment);
  return e != nullptr ? e->results : none;
}

nlohmann::ordered_json run_row(const Manifest& manifest, const ManifestRun& run) {
  nlohmann::ordered_json row = {{"run_id", run.run_id}, {"status", "error"}, {"reason", ""}};
  const Experiment* experiment = find_experiment(manifest.experiment);
  if (experiment == nullptr) {
    row["reason"] = "experiment \"" + manifest.experiment + "\" is not one campaigns run";
    return row;
  }
  for (const ResultKey& k : experiment->results) row[k.name] = nullptr;
  const RunSetup setup = resolve_run_inputs(manifest.base, manifest.inputs, run.inputs, manifest.experiment);
  if (!setup.scenario) {
    row["reason"] = setup.error;
    return row;
  }
  try {
    experiment->run(RunContext{manifest, run, setup}, row);
    if (row["status"] != "ok")  // results only for a finished run
      for (const ResultKey& k : experiment->results) row[k.name] = nullptr;
  } catch (const std::exception& e) {
    for (const ResultKey& k : experiment->results) row[k.name] = nullptr;
    row["status"] = "error";
    row["reason"] = std::string("exception: ") + e.what();
  }
  // An [io] run on a build without the work meter lands each output write
  // sooner than a metered build would (docs/performance.md "What an
  // unmetered tnv-hil gives"): the row says so, as circle's and path's
  // --json do; the key is absent otherwise, so other rows keep their bytes.
  if (hil::io_work_unmetered(*setup.scenario)) row["io_work_unmetered"] = true;
  return row;
}

}  // namespace tnv::campaign
