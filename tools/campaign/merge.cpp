#include "tools/campaign/merge.hpp"

#include <map>
#include <memory>
#include <system_error>
#include <vector>

#include <sqlite3.h>

#include "tools/campaign/sqlite_handle.hpp"

#include "emulator/text_file.hpp"
#include "tools/campaign/experiment_row.hpp"
#include "tools/campaign/manifest.hpp"
#include "tools/campaign/shard.hpp"

namespace tnv::campaign {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

namespace {

void bind_json(sqlite3_stmt* stmt, int index, const ojson& v) {
  if (v.is_null()) {
    sqlite3_bind_null(stmt, index);
  } else if (v.is_boolean()) {
    sqlite3_bind_int(stmt, index, v.get<bool>() ? 1 : 0);
  } else if (v.is_number_integer()) {
    sqlite3_bind_int64(stmt, index, v.get<std::int64_t>());
  } else if (v.is_number()) {
    sqlite3_bind_double(stmt, index, v.get<double>());
  } else {
    const std::string s = v.is_string() ? v.get<std::string>() : v.dump();
    sqlite3_bind_text(stmt, index, s.c_str(), static_cast<int>(s.size()), SQLITE_TRANSIENT);
  }
}

struct ShardFile {
  int shard = 0;
  fs::path path;
};

}  // namespace

MergeResult merge_campaign(const fs::path& dir) {
  MergeResult result;
  const ManifestResult loaded = load_manifest(dir);
  if (!loaded.manifest) {
    result.error = loaded.error;
    return result;
  }
  const Manifest& m = *loaded.manifest;

  // Which shard files there are: one sharding, each shard once.
  const fs::path shard_dir = dir / "shards";
  std::map<int, std::vector<fs::path>> by_count;  // shards -> files
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(shard_dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() > 8 && name.compare(name.size() - 8, 8, ".partial") == 0) continue;
    if (!parse_shard_file_name(name)) {
      result.error = entry.path().string() + ": not a shard file (shard-IIII-of-NNNN.jsonl); nothing merged";
      return result;
    }
    by_count[parse_shard_file_name(name)->second].push_back(entry.path());
  }
  if (ec) {
    result.error = shard_dir.string() + ": " + ec.message();
    return result;
  }
  if (by_count.empty()) {
    result.error = shard_dir.string() + ": no shards (tnv-hil campaign run DIR --shard I/N); nothing merged";
    return result;
  }
  if (by_count.size() > 1) {
    const fs::path& a = by_count.begin()->second.front();
    const fs::path& b = by_count.rbegin()->second.front();
    result.error = a.string() + " and " + b.string() + ": two shardings of the same runs (duplicate shards); nothing merged";
    return result;
  }
  const int shards = by_count.begin()->first;
  std::vector<ShardFile> files;
  for (int i = 1; i <= shards; ++i) {
    const fs::path p = shard_dir / shard_file_name(i, shards);
    if (!fs::exists(p, ec)) {
      result.error = p.string() + ": missing (shard " + std::to_string(i) + " of " + std::to_string(shards) +
                     " not run); nothing merged";
      return result;
    }
    files.push_back({i, p});
  }

  // Every shard whole and this campaign's, before anything is written.
  for (const ShardFile& f : files) {
    std::string text, error;
    if (!emu::read_text_file(f.path.string(), std::size_t{1} << 34, text, error)) {
      result.error = emu::one_line(error) + "; nothing merged";
      return result;
    }
    const ShardRange range = shard_range(m.runs.size(), f.shard, shards);
    const ShardScan scan = scan_shard_text(text, shard_header_line(m, f.shard, shards), range);
    if (!scan.error.empty() || !scan.complete) {
      result.error = f.path.string() + ": " +
                     (scan.error.empty() ? "incomplete, " + std::to_string(scan.rows) + " of " +
                                               std::to_string(range.size()) + " runs (run the shard again to finish it)"
                                         : scan.error) +
                     "; nothing merged";
      return result;
    }
  }

  const fs::path final_path = dir / kDatabaseName;
  const fs::path tmp_path = dir / (std::string(kDatabaseName) + ".partial");
  fs::remove(tmp_path, ec);
  auto fail = [&](const std::string& error) {
    result.error = error + "; nothing merged";
    fs::remove(tmp_path, ec);
    return result;
  };
  std::string error;
  {
    SqliteDb db;
    if (sqlite3_open(tmp_path.c_str(), &db.db) != SQLITE_OK) return fail(tmp_path.string() + ": cannot create");
    const std::vector<ResultKey>& results = result_keys(m.experiment);
    std::string columns = "run_id INTEGER PRIMARY KEY, sample INTEGER NOT NULL, controller TEXT NOT NULL, seed INTEGER NOT NULL, "
                          "status TEXT NOT NULL, reason TEXT NOT NULL";
    for (const InputName& in : m.inputs) columns += ", " + quoted_identifier(in.name);
    for (const ResultKey& k : results) columns += ", " + quoted_identifier(k.name) + " " + k.sql_type;
    columns += ", io_work_unmetered INTEGER NOT NULL, tool_version TEXT NOT NULL, build_id TEXT NOT NULL";
    if (!db.exec("PRAGMA journal_mode=OFF; PRAGMA synchronous=OFF; BEGIN;", error) ||
        !db.exec("CREATE TABLE runs (" + columns + ");", error) ||
        !db.exec("CREATE TABLE campaign (key TEXT PRIMARY KEY, value);", error))
      return fail(error);
    const std::size_t n_columns = 6 + m.inputs.size() + results.size() + 3;
    std::string placeholders;
    for (std::size_t i = 0; i < n_columns; ++i) placeholders += i == 0 ? "?" : ",?";
    SqliteStatement insert;
    if (sqlite3_prepare_v2(db.db, ("INSERT INTO runs VALUES (" + placeholders + ");").c_str(), -1, &insert.stmt,
                           nullptr) != SQLITE_OK)
      return fail(std::string("sqlite: ") + sqlite3_errmsg(db.db));
    const std::string version = tool_version_text(), build = tool_build_id_text();
    std::string insert_error;
    for (const ShardFile& f : files) {
      std::string text;
      if (!emu::read_text_file(f.path.string(), std::size_t{1} << 34, text, error)) return fail(emu::one_line(error));
      const ShardRange range = shard_range(m.runs.size(), f.shard, shards);
      scan_shard_text(text, shard_header_line(m, f.shard, shards), range, [&](const ojson& row) {
        if (!insert_error.empty()) return;
        const ManifestRun& run = m.runs[row["run_id"].get<std::uint64_t>() - 1];
        int c = 1;
        sqlite3_reset(insert.stmt);
        sqlite3_bind_int64(insert.stmt, c++, static_cast<std::int64_t>(run.run_id));
        sqlite3_bind_int64(insert.stmt, c++, static_cast<std::int64_t>(run.sample));
        bind_json(insert.stmt, c++, controller_text(run.controller));
        sqlite3_bind_int64(insert.stmt, c++, run.seed);
        bind_json(insert.stmt, c++, row.value("status", ""));
        bind_json(insert.stmt, c++, row.value("reason", ""));
        for (const InputName& in : m.inputs) bind_json(insert.stmt, c++, run.inputs.at(in.name));
        for (const ResultKey& k : results) bind_json(insert.stmt, c++, row.contains(k.name) ? row[k.name] : ojson());
        sqlite3_bind_int(insert.stmt, c++, row.value("io_work_unmetered", false) ? 1 : 0);
        bind_json(insert.stmt, c++, version);
        bind_json(insert.stmt, c++, build);
        if (sqlite3_step(insert.stmt) != SQLITE_DONE) insert_error = std::string("sqlite: ") + sqlite3_errmsg(db.db);
        ++result.rows;
      });
      if (!insert_error.empty()) return fail(insert_error);
    }
    SqliteStatement meta;
    if (sqlite3_prepare_v2(db.db, "INSERT INTO campaign VALUES (?, ?);", -1, &meta.stmt, nullptr) != SQLITE_OK)
      return fail(std::string("sqlite: ") + sqlite3_errmsg(db.db));
    std::string manifest_text;
    emu::read_text_file((dir / kManifestName).string(), std::size_t{1} << 30, manifest_text, error);
    const ojson head = ojson::parse(manifest_text);
    for (const char* key :
         {"source", "experiment", "scenario", "controllers", "samples", "seed", "sampling", "limit_um", "vary", "settings"}) {
      if (!head.contains(key)) continue;  // "settings": only an experiment that has some
      sqlite3_reset(meta.stmt);
      bind_json(meta.stmt, 1, key);
      const ojson& v = head.at(key);
      bind_json(meta.stmt, 2, v.is_structured() ? ojson(v.dump()) : v);
      if (sqlite3_step(meta.stmt) != SQLITE_DONE) return fail(std::string("sqlite: ") + sqlite3_errmsg(db.db));
    }
    if (!db.exec("COMMIT;", error)) return fail(error);
  }
  fs::rename(tmp_path, final_path, ec);
  if (ec) return fail(final_path.string() + ": " + ec.message());
  result.shards = static_cast<std::size_t>(shards);
  return result;
}

}  // namespace tnv::campaign
