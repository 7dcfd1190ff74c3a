#pragma once
// merge: every shard of a campaign checked (present, once, whole, this
// campaign's, one build), then DIR/campaign.sqlite written through a
// temporary file renamed over it. Any shard missing, duplicated (two
// shardings of one campaign) or corrupt is named and nothing is written.
//
// Table runs: run_id, sample, controller, seed, status, reason, one column
// per varied input named as in the campaign file, the experiment's result
// keys (result_keys()), io_work_unmetered (1: an [io] run on a build
// without the work meter), tool_version, build_id. Table campaign: key, value
// (the manifest's experiment, scenario, seed, sampling, limit_um, ...).
#include <cstddef>
#include <filesystem>
#include <string>

namespace tnv::campaign {

inline constexpr const char* kDatabaseName = "campaign.sqlite";

struct MergeResult {
  std::string error;  // empty: written
  std::size_t rows = 0;
  std::size_t shards = 0;
};
MergeResult merge_campaign(const std::filesystem::path& dir);

}  // namespace tnv::campaign
