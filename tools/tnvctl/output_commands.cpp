// tnvctl dump-dbc | plot: outputs that need no node.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "drivers/storage/regular_file.hpp"
#include "tools/cli/output_path.hpp"
#include "tools/cli/run_plotter.hpp"
#include "tools/can/capture_csv.hpp"
#include "tools/can/capture_score.hpp"
#include "tools/protogen/dbc_writer.hpp"
#include "tools/score/score_json.hpp"
#include "tools/tnvctl/commands.hpp"

namespace tnv::tnvctl {

namespace {

constexpr std::size_t kMaxCaptureCsvBytes = 256u << 20;  // far beyond a full capture buffer as CSV

int run_dump_dbc(Session& session, Report& report) {
  const std::string dbc = protogen::write_dbc(static_cast<std::uint8_t>(session.options().node));
  if (report.json_mode()) report.data["dbc"] = dbc;
  else std::cout << dbc;
  return kExitOk;
}

struct PlotOptions {
  std::vector<std::string> csv;
  std::vector<std::string> labels;
  std::string out;
  std::string title = "captured circles";
};

void check_plot(const PlotOptions& o) {
  if (!o.labels.empty() && o.labels.size() != o.csv.size()) throw BadInput("give one --label per --csv, or none");
}

int run_plot(const PlotOptions& o, Session&, Report& report) {
  check_plot(o);
  std::vector<can_host::CaptureTable> tables;
  for (const std::string& path : o.csv) {
    std::string text;
    std::string error;
    if (!drivers::read_regular_file(path, kMaxCaptureCsvBytes, drivers::LinkPolicy::follow, text, error)) {
      throw BadInput(error);
    }
    std::optional<can_host::CaptureTable> t = can_host::read_capture_csv(text, error);
    if (!t) {
      std::string message = path;
      throw BadInput(message.append(": ").append(error));
    }
    tables.push_back(std::move(*t));
  }
  std::vector<std::string> plot_args = {"--title", o.title};
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const std::string label = o.labels.empty() ? std::filesystem::path(o.csv[i]).stem().string() : o.labels[i];
    plot_args.insert(plot_args.end(), {"--label", label});
    std::string error;
    nlohmann::json row = {{"csv", o.csv[i]}, {"label", label}};
    if (const auto stats = can_host::score_circle(tables[i], error)) {
      row["circle"] = hil::contour_stats_json(*stats);
      char buf[200];
      std::snprintf(buf, sizeof buf, "%-24s max %.4f um   mean %.4f um   std %.4f um", label.c_str(), stats->max_um,
                    stats->mean_um, stats->std_um);
      report.line(buf);
    }
    list.push_back(row);
  }
  // The plotter draws circle captures as rows of the S1 figure and refuses
  // to compare anything else; one other capture is drawn channel by channel.
  const std::string error = cli::run_plotter("capture", o.csv, o.out, plot_args);
  if (!error.empty()) throw RunFailed(error);
  std::string text = "[plot] wrote ";
  report.line(text.append(o.out));
  report.data["rows"] = list;
  report.data["plot"] = o.out;
  return kExitOk;
}

}  // namespace

void add_output_commands(CLI::App& app, ActionSlot& slot) {
  app.add_subcommand("dump-dbc", "print the DBC of the protocol (for --node N; no device needed)")->callback([&slot] {
    slot = Action{"dump-dbc", false, [](Session& s, Report& r) { return run_dump_dbc(s, r); }};
  });

  auto o = std::make_shared<PlotOptions>();
  CLI::App* cmd = app.add_subcommand("plot", "plot captures saved with `capture --csv`, one row each (no device needed)");
  cmd->add_option("--csv", o->csv, "a capture CSV (repeat to compare)")->required()->check(CLI::ExistingFile);
  cmd->add_option("--label", o->labels, "row label per --csv (default: the file name)");
  cmd->add_option("--out", o->out, "the figure to write (.svg, .png or .pdf)")->required()->check(tnv::cli::PlotFile());
  cmd->add_option("--title", o->title, "figure title")->capture_default_str();
  cmd->callback([&slot, o] {
    slot = Action{"plot", false, [o](Session& s, Report& r) { return run_plot(*o, s, r); }, [o] { check_plot(*o); }};
  });
}

}  // namespace tnv::tnvctl
