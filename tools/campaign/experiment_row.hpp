#pragma once
// One run of a planned campaign and its row: status ("ok", "fault",
// "timeout" — the experiment's simulated time ran out —, "error" — the run
// could not start), the reason, and the experiment's results (null unless
// ok). Deterministic: the same manifest run gives the same bytes, which
// is what makes shards resumable and runs replayable.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/campaign/experiment.hpp"
#include "tools/campaign/manifest.hpp"

namespace tnv::campaign {

// The result keys of an experiment's rows, in row order ("max_um", ...);
// empty for an experiment no campaign runs.
const std::vector<ResultKey>& result_keys(const std::string& experiment);

nlohmann::ordered_json run_row(const Manifest& manifest, const ManifestRun& run);

}  // namespace tnv::campaign
