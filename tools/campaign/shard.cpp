#include "tools/campaign/shard.hpp"

#include <cstdio>
#include <cstdlib>
#include <system_error>

#include "emulator/text_file.hpp"
#include "firmware/can/firmware_identity.hpp"
#include "tools/campaign/experiment_row.hpp"
#include "tools/can/node_identity.hpp"

namespace tnv::campaign {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

ShardRange shard_range(std::size_t runs, int shard, int shards) noexcept {
  const auto n = static_cast<std::uint64_t>(runs);
  const auto i = static_cast<std::uint64_t>(shard - 1);
  const auto k = static_cast<std::uint64_t>(shards);
  return {i * n / k + 1, (i + 1) * n / k};
}

std::string shard_file_name(int shard, int shards) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "shard-%04d-of-%04d.jsonl", shard, shards);
  return buf;
}

std::optional<std::pair<int, int>> parse_shard_file_name(const std::string& name) {
  int shard = 0, shards = 0;
  char tail[8] = {};
  if (name.size() != std::string("shard-0001-of-0001.jsonl").size()) return std::nullopt;
  if (std::sscanf(name.c_str(), "shard-%4d-of-%4d.%5s", &shard, &shards, tail) != 3) return std::nullopt;
  if (std::string(tail) != "jsonl" || shard < 1 || shards < 1 || shard > shards) return std::nullopt;
  if (shard_file_name(shard, shards) != name) return std::nullopt;
  return std::pair{shard, shards};
}

namespace {

std::optional<int> parse_positive(const std::string& text, int max) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  const int v = std::stoi(text);
  if (v > max) return std::nullopt;
  return v;
}

}  // namespace

ShardChoice parse_shard_text(const std::string& text) {
  const auto slash = text.find('/');
  const auto i = slash == std::string::npos ? std::nullopt : parse_positive(text.substr(0, slash), kMaxShards);
  const auto n = slash == std::string::npos ? std::nullopt : parse_positive(text.substr(slash + 1), kMaxShards);
  if (!i || !n || *i < 1 || *i > *n)
    return {0, 0, "--shard " + text + ": expected I/N with 1 <= I <= N <= " + std::to_string(kMaxShards)};
  return {*i, *n, {}};
}

ShardChoice shard_from_environment(std::optional<int> shards, const std::function<const char*(const char*)>& get_env) {
  const auto env = [&](const char* name) -> std::optional<std::string> {
    const char* v = get_env(name);
    return v != nullptr && *v != '\0' ? std::optional<std::string>(v) : std::nullopt;
  };
  if (const auto id = env("SLURM_ARRAY_TASK_ID")) {
    const auto task = parse_positive(*id, 1'000'000'000);
    const auto min = parse_positive(env("SLURM_ARRAY_TASK_MIN").value_or("0"), 1'000'000'000);
    std::optional<int> count = shards;
    if (!count) count = parse_positive(env("SLURM_ARRAY_TASK_COUNT").value_or(""), kMaxShards);
    if (!task || !min || *task < *min) return {0, 0, "SLURM_ARRAY_TASK_ID=" + *id + ": not an array index"};
    if (!count || *count < 1) return {0, 0, "SLURM_ARRAY_TASK_ID is set but neither --shards nor SLURM_ARRAY_TASK_COUNT"};
    const int shard = *task - *min + 1;
    if (shard > *count)
      return {0, 0, "SLURM_ARRAY_TASK_ID=" + *id + " is past the " + std::to_string(*count) + " shards"};
    return {shard, *count, {}};
  }
  if (const auto index = env("JOB_COMPLETION_INDEX")) {
    const auto i = parse_positive(*index, kMaxShards - 1);
    if (!i) return {0, 0, "JOB_COMPLETION_INDEX=" + *index + ": not an index"};
    if (!shards) return {0, 0, "JOB_COMPLETION_INDEX is set: give the shard count with --shards N"};
    if (*i + 1 > *shards) return {0, 0, "JOB_COMPLETION_INDEX=" + *index + " is past the " + std::to_string(*shards) + " shards"};
    return {*i + 1, *shards, {}};
  }
  return {0, 0, "no shard: give --shard I/N, or run in a Slurm job array or a Kubernetes Indexed Job"};
}

std::string tool_version_text() { return can_host::firmware_version_text(fw::can::firmware_version()); }
std::string tool_build_id_text() { return can_host::build_id_text(fw::can::firmware_build_id()); }

std::string shard_header_line(const Manifest& manifest, int shard, int shards) {
  const ShardRange range = shard_range(manifest.runs.size(), shard, shards);
  char campaign[24];
  std::snprintf(campaign, sizeof campaign, "%016llx", static_cast<unsigned long long>(manifest.fingerprint));
  const ojson header = {{"format", kShardFormat},       {"campaign", campaign},
                        {"shard", shard},               {"shards", shards},
                        {"first_run", range.first_run}, {"last_run", range.last_run},
                        {"tool_version", tool_version_text()}, {"build_id", tool_build_id_text()}};
  return header.dump() + "\n";
}

ShardScan scan_shard_text(const std::string& text, const std::string& expected_header, const ShardRange& range,
                          const std::function<void(const ojson&)>& on_row) {
  ShardScan scan;
  const std::size_t header_end = text.find('\n');
  if (header_end == std::string::npos) {  // killed while writing the header: start again
    scan.torn_bytes = text.size();
    return scan;
  }
  const std::string header = text.substr(0, header_end + 1);
  if (header != expected_header) {
    std::string what = "its header is not this campaign's, shard and build";
    try {
      const ojson h = ojson::parse(header);
      if (h.value("build_id", "") != tool_build_id_text() || h.value("tool_version", "") != tool_version_text())
        what = "written by tool " + h.value("tool_version", "?") + " build " + h.value("build_id", "?") + ", this is " +
               tool_version_text() + " build " + tool_build_id_text();
      else if (h.value("format", "") == kShardFormat)
        what = "written for another campaign or sharding";
    } catch (const std::exception&) {
      what = "corrupt header";
    }
    scan.error = what;
    return scan;
  }
  std::size_t at = header_end + 1;
  scan.valid_bytes = at;
  while (at < text.size()) {
    const std::size_t end = text.find('\n', at);
    if (end == std::string::npos) {
      scan.torn_bytes = text.size() - at;
      break;
    }
    const std::uint64_t expected_id = range.first_run + scan.rows;
    ojson row;
    try {
      row = ojson::parse(std::string_view(text).substr(at, end - at));
    } catch (const std::exception&) {
      scan.error = "line " + std::to_string(scan.rows + 2) + " is corrupt";
      return scan;
    }
    if (!row.is_object() || !row.contains("run_id") || row["run_id"] != expected_id || !row.contains("status")) {
      scan.error = "line " + std::to_string(scan.rows + 2) + " is not run " + std::to_string(expected_id);
      return scan;
    }
    if (scan.rows == range.size()) {
      scan.error = "more rows than its " + std::to_string(range.size()) + " runs";
      return scan;
    }
    if (on_row) on_row(row);
    ++scan.rows;
    at = end + 1;
    scan.valid_bytes = at;
  }
  scan.complete = scan.rows == range.size() && scan.torn_bytes == 0;
  return scan;
}

ShardRunResult run_shard(const fs::path& dir, const Manifest& manifest, int shard, int shards,
                         const std::function<void(std::size_t, std::size_t)>& progress) {
  ShardRunResult result;
  const ShardRange range = shard_range(manifest.runs.size(), shard, shards);
  result.total = range.size();
  const fs::path path = dir / "shards" / shard_file_name(shard, shards);
  const std::string header = shard_header_line(manifest, shard, shards);
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  std::size_t keep = 0;
  if (fs::exists(path, ec)) {
    std::string text, error;
    if (!emu::read_text_file(path.string(), std::size_t{1} << 34, text, error)) {
      result.error = emu::one_line(error);
      return result;
    }
    const ShardScan scan = scan_shard_text(text, header, range);
    if (!scan.error.empty()) {
      result.error = path.string() + ": " + scan.error + "; not resuming (move it away to run the shard afresh)";
      return result;
    }
    result.already_done = scan.rows;
    keep = scan.valid_bytes;
    if (scan.complete) return result;
    fs::resize_file(path, keep, ec);  // a torn last line goes; whole rows stay
    if (ec) {
      result.error = path.string() + ": " + ec.message();
      return result;
    }
  }
  std::FILE* out = std::fopen(path.c_str(), keep == 0 ? "wb" : "ab");
  if (out == nullptr) {
    result.error = path.string() + ": cannot open for writing";
    return result;
  }
  bool ok = true;
  if (keep == 0) ok = std::fwrite(header.data(), 1, header.size(), out) == header.size() && std::fflush(out) == 0;
  for (std::uint64_t id = range.first_run + result.already_done; ok && id <= range.last_run; ++id) {
    const ojson row = run_row(manifest, manifest.runs[id - 1]);
    if (row["status"] != "ok") ++result.not_ok;
    const std::string line = row.dump() + "\n";
    ok = std::fwrite(line.data(), 1, line.size(), out) == line.size() && std::fflush(out) == 0;
    ++result.ran;
    if (progress) progress(result.already_done + result.ran, result.total);
  }
  if (std::fclose(out) != 0) ok = false;
  if (!ok) result.error = path.string() + ": write failed (disk full?); run the shard again to continue";
  return result;
}

}  // namespace tnv::campaign
