#pragma once
// Shards: run I of N (I from 1) takes a contiguous block of the run ids
// and writes DIR/shards/shard-IIII-of-NNNN.jsonl, a header line, then one
// row a line (experiment_row.hpp), each flushed as its run ends: a worker
// holds one run in memory however many it does. A shard killed and run
// again keeps its complete rows, drops a torn last line and continues;
// a finished shard run again changes nothing: the file's bytes depend
// only on the manifest, the shard and the build.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tools/campaign/manifest.hpp"

namespace tnv::campaign {

inline constexpr const char* kShardFormat = "tnv-campaign-shard 1";
inline constexpr int kMaxShards = 9999;

struct ShardRange {
  std::uint64_t first_run = 1;  // inclusive
  std::uint64_t last_run = 0;   // inclusive; last < first: an empty shard
  std::size_t size() const noexcept { return last_run >= first_run ? last_run - first_run + 1 : 0; }
};
ShardRange shard_range(std::size_t runs, int shard, int shards) noexcept;

std::string shard_file_name(int shard, int shards);  // "shard-0001-of-0004.jsonl"
// shard and shards from such a name; nullopt for any other name.
std::optional<std::pair<int, int>> parse_shard_file_name(const std::string& name);

struct ShardChoice {
  int shard = 0;  // from 1
  int shards = 0;
  std::string error;
};
// "I/N" (I from 1), e.g. "3/8".
ShardChoice parse_shard_text(const std::string& text);
// A job array's index: SLURM_ARRAY_TASK_ID (the shard is the id minus
// SLURM_ARRAY_TASK_MIN, plus 1; N is SLURM_ARRAY_TASK_COUNT unless given)
// or JOB_COMPLETION_INDEX (Kubernetes Indexed Job, from 0; N must be given).
// `get_env` is getenv in the tool, a map in tests.
ShardChoice shard_from_environment(std::optional<int> shards, const std::function<const char*(const char*)>& get_env);

// The version and build that ran a shard: the header names them, merge
// refuses a campaign whose shards disagree.
std::string tool_version_text();
std::string tool_build_id_text();

std::string shard_header_line(const Manifest& manifest, int shard, int shards);

// What a shard file holds, checked against its manifest. `complete`: every
// row of the range is there. A torn last line (no newline) is reported in
// `torn_bytes`, not as an error; any other damage is an error.
struct ShardScan {
  std::string error;
  std::size_t valid_bytes = 0;  // the header and the whole rows
  std::size_t rows = 0;
  std::size_t torn_bytes = 0;
  bool complete = false;
};
// `on_row` (may be empty) sees each whole row in order.
ShardScan scan_shard_text(const std::string& text, const std::string& expected_header, const ShardRange& range,
                          const std::function<void(const nlohmann::ordered_json&)>& on_row = {});

struct ShardRunResult {
  std::string error;  // empty: the shard is complete
  std::size_t already_done = 0;
  std::size_t ran = 0;
  std::size_t total = 0;
  std::size_t not_ok = 0;  // rows written this time whose status is not "ok"
};
ShardRunResult run_shard(const std::filesystem::path& dir, const Manifest& manifest, int shard, int shards,
                         const std::function<void(std::size_t done, std::size_t total)>& progress = {});

}  // namespace tnv::campaign
