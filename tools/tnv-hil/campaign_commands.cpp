// tnv-hil campaign plan | run | merge | replay | report: many HIL runs
// described by a campaign file, run in shards by an existing engine
// (docs/campaigns.md). The logic is tools/campaign; this file parses and prints.
#ifdef TNV_HAVE_CAMPAIGN
#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>

#include "emulator/text_file.hpp"
#include "tools/campaign/campaign_file.hpp"
#include "tools/campaign/experiment_row.hpp"
#include "tools/campaign/manifest.hpp"
#include "tools/campaign/merge.hpp"
#include "tools/campaign/report.hpp"
#include "tools/campaign/shard.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/cli/run_plotter.hpp"
#include "tools/tnv-hil/cli_support.hpp"
#include "tools/tnv-hil/commands.hpp"

namespace tnv::cli {

namespace {

namespace fs = std::filesystem;
namespace cmp = tnv::campaign;

struct CampaignOptions {
  std::string file;
  std::string dir;
  std::string shard;
  std::optional<int> shards;
  std::uint64_t run_id = 0;
  bool json = false;
  std::string metric;  // "": the experiment's default
  std::optional<double> limit_um;
  std::string plot;
};

int plan_command(const CampaignOptions& o) {
  std::string text, error;
  if (!emu::read_text_file(o.file, std::size_t{1} << 20, text, error)) {
    std::fprintf(stderr, "tnv-hil: %s\n", emu::one_line(error).c_str());
    return kExitBadInput;
  }
  const cmp::CampaignResult parsed = cmp::parse_campaign_text(text, o.file, fs::path(o.file).parent_path());
  if (!parsed.spec) {
    std::fprintf(stderr, "tnv-hil: %s\n", parsed.error.c_str());
    return kExitBadInput;
  }
  const cmp::PlanResult plan = cmp::plan_campaign(*parsed.spec, text, o.dir);
  if (!plan.ok) {
    std::fprintf(stderr, "tnv-hil: %s\n", plan.error.c_str());
    return kExitBadInput;
  }
  std::printf("%s: %zu runs (%zu samples x %zu controllers) planned\n", o.dir.c_str(), plan.runs, parsed.spec->runs,
              parsed.spec->controllers.size());
  return kExitOk;
}

std::optional<cmp::Manifest> manifest_or_report(const std::string& dir) {
  cmp::ManifestResult m = cmp::load_manifest(dir);
  if (!m.manifest) std::fprintf(stderr, "tnv-hil: %s\n", m.error.c_str());
  return std::move(m.manifest);
}

int run_command(const CampaignOptions& o) {
  cmp::ShardChoice choice;
  if (!o.shard.empty()) {
    choice = cmp::parse_shard_text(o.shard);
  } else {
    choice = cmp::shard_from_environment(o.shards, [](const char* name) { return std::getenv(name); });
  }
  if (!choice.error.empty()) {
    std::fprintf(stderr, "tnv-hil: %s\n", choice.error.c_str());
    return kExitBadInput;
  }
  const auto manifest = manifest_or_report(o.dir);
  if (!manifest) return kExitBadInput;
  Progress progress("shard " + std::to_string(choice.shard) + "/" + std::to_string(choice.shards));
  const cmp::ShardRunResult r = cmp::run_shard(o.dir, *manifest, choice.shard, choice.shards, std::ref(progress));
  if (!r.error.empty()) {
    std::fprintf(stderr, "tnv-hil: %s\n", r.error.c_str());
    return kExitFailure;
  }
  std::fprintf(stderr, "[campaign] shard %d/%d: %zu runs, %zu already done, %zu run now (%zu not ok)\n", choice.shard,
               choice.shards, r.total, r.already_done, r.ran, r.not_ok);
  return kExitOk;
}

int merge_command(const CampaignOptions& o) {
  const cmp::MergeResult r = cmp::merge_campaign(o.dir);
  if (!r.error.empty()) {
    std::fprintf(stderr, "tnv-hil: %s\n", r.error.c_str());
    return kExitFailure;
  }
  std::printf("%s: %zu runs from %zu shards\n", (fs::path(o.dir) / cmp::kDatabaseName).c_str(), r.rows, r.shards);
  return kExitOk;
}

// The row the shards recorded for `run_id`, as its line's bytes; "" if none.
std::string recorded_line(const std::string& dir, const cmp::Manifest& m, std::uint64_t run_id, std::string& where) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(fs::path(dir) / "shards", ec)) {
    const auto parsed = cmp::parse_shard_file_name(entry.path().filename().string());
    if (!parsed) continue;
    const cmp::ShardRange range = cmp::shard_range(m.runs.size(), parsed->first, parsed->second);
    if (run_id < range.first_run || run_id > range.last_run) continue;
    std::string text, error;
    if (!emu::read_text_file(entry.path().string(), std::size_t{1} << 34, text, error)) continue;
    // The shard's own header: a row recorded by another build is still
    // compared (and the builds named), as long as it is this campaign's.
    const std::string expected = cmp::shard_header_line(m, parsed->first, parsed->second);
    const std::string header = text.substr(0, text.find('\n') + 1);
    nlohmann::ordered_json h, e = nlohmann::ordered_json::parse(expected);
    try {
      h = nlohmann::ordered_json::parse(header);
    } catch (const std::exception&) {
      continue;
    }
    if (h.value("campaign", "") != e["campaign"] || h.value("shard", 0) != parsed->first) continue;
    std::string line;
    cmp::scan_shard_text(text, header, range, [&](const nlohmann::ordered_json& row) {
      if (row["run_id"] == run_id) line = row.dump();
    });
    if (!line.empty()) {
      where = entry.path().string();
      if (header != expected)
        where += " (recorded by tool " + h.value("tool_version", "?") + " build " + h.value("build_id", "?") +
                 ", replayed by " + cmp::tool_version_text() + " build " + cmp::tool_build_id_text() + ")";
      return line;
    }
  }
  return {};
}

int replay_command(const CampaignOptions& o) {
  const auto manifest = manifest_or_report(o.dir);
  if (!manifest) return kExitBadInput;
  if (o.run_id < 1 || o.run_id > manifest->runs.size()) {
    std::fprintf(stderr, "tnv-hil: run %llu: the campaign has runs 1..%zu\n", static_cast<unsigned long long>(o.run_id),
                 manifest->runs.size());
    return kExitBadInput;
  }
  const cmp::ManifestRun& run = manifest->runs[o.run_id - 1];
  const nlohmann::ordered_json row = cmp::run_row(*manifest, run);
  const std::string line = row.dump();
  if (o.json) {
    std::cout << line << '\n';
  } else {
    std::cout << "run " << run.run_id << " (sample " << run.sample << ", " << cmp::controller_text(run.controller) << ", seed "
              << run.seed << ") " << run.inputs.dump() << '\n';
    for (const auto& [key, value] : row.items())
      if (key != "run_id") std::cout << "  " << key << " = " << value.dump() << '\n';
  }
  std::string where;
  const std::string recorded = recorded_line(o.dir, *manifest, o.run_id, where);
  if (recorded.empty()) {
    std::fprintf(stderr, "[replay] run %llu: no recorded row to compare with (its shard has not run it)\n",
                 static_cast<unsigned long long>(o.run_id));
  } else if (recorded == line) {
    std::fprintf(stderr, "[replay] run %llu: identical to its row in %s\n", static_cast<unsigned long long>(o.run_id),
                 where.c_str());
  } else {
    std::fprintf(stderr, "tnv-hil: run %llu differs from its row in %s:\n  recorded %s\n  replayed %s\n",
                 static_cast<unsigned long long>(o.run_id), where.c_str(), recorded.c_str(), line.c_str());
    return kExitFailure;
  }
  return kExitOk;
}

int report_command(const CampaignOptions& o) {
  const fs::path db = fs::path(o.dir) / cmp::kDatabaseName;
  const cmp::CampaignReport report = cmp::report_campaign(db, o.metric, o.limit_um);
  if (!report.error.empty()) {
    std::fprintf(stderr, "tnv-hil: %s\n", report.error.c_str());
    return kExitFailure;
  }
  if (o.json)
    std::cout << cmp::report_json(report).dump(2) << '\n';
  else
    std::cout << cmp::report_text(report);
  if (!o.plot.empty()) {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%.17g", report.limit);
    if (!plot_files(o.plot, "campaign", {db.string()}, {"--option", "metric=" + report.metric, "--option", std::string("limit=") + limit},
                    "tnv-hil"))
      return kExitFailure;
  }
  return kExitOk;
}

}  // namespace

void add_campaign_commands(CLI::App& app, Runner& run) {
  auto o = std::make_shared<CampaignOptions>();
  CLI::App* campaign = app.add_subcommand("campaign", "many runs from a campaign file, in shards, merged, replayable (docs/campaigns.md)");
  campaign->require_subcommand(1);

  CLI::App* plan = campaign->add_subcommand("plan", "resolve every run of a campaign file into DIR/manifest.json");
  plan->add_option("file", o->file, "the campaign file (TOML)")->required()->check(CLI::ExistingFile);
  plan->add_option("--out", o->dir, "the campaign directory (new or empty)")->required();
  plan->callback([&run, o] { run = [o] { return plan_command(*o); }; });

  CLI::App* shard = campaign->add_subcommand("run", "run one shard of a planned campaign (resumable)");
  shard->add_option("dir", o->dir, "the campaign directory")->required()->check(CLI::ExistingDirectory);
  shard->add_option("--shard", o->shard, "I/N: shard I (from 1) of N; else from SLURM_ARRAY_TASK_ID or JOB_COMPLETION_INDEX");
  shard->add_option("--shards", o->shards, "N, with an index from the environment")->check(CLI::Range(1, cmp::kMaxShards));
  shard->callback([&run, o] { run = [o] { return run_command(*o); }; });

  CLI::App* merge = campaign->add_subcommand("merge", "check every shard and write DIR/campaign.sqlite");
  merge->add_option("dir", o->dir, "the campaign directory")->required()->check(CLI::ExistingDirectory);
  merge->callback([&run, o] { run = [o] { return merge_command(*o); }; });

  CLI::App* replay = campaign->add_subcommand("replay", "run one run again and compare it with its recorded row");
  replay->add_option("dir", o->dir, "the campaign directory")->required()->check(CLI::ExistingDirectory);
  replay->add_option("run_id", o->run_id, "the run (from 1)")->required();
  replay->add_flag("--json", o->json, "print the row as the shard holds it");
  replay->callback([&run, o] { run = [o] { return replay_command(*o); }; });

  CLI::App* report = campaign->add_subcommand("report", "yield, quantiles and sensitivity from DIR/campaign.sqlite");
  report->add_option("dir", o->dir, "the campaign directory")->required()->check(CLI::ExistingDirectory);
  report->add_option("--metric", o->metric, "the result judged (default: the experiment's, e.g. max_um for circle; true_tool_max_um, ...)");
  report->add_option("--limit-um", o->limit_um, "the yield limit (default: the campaign file's limit_um)");
  report->add_flag("--json", o->json, "print JSON on stdout");
  report->add_option("--plot", o->plot, "write the figure (.svg, .png or .pdf)")->check(tnv::cli::PlotFile());
  report->callback([&run, o] { run = [o] { return report_command(*o); }; });
}

}  // namespace tnv::cli
#endif
