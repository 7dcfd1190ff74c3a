#pragma once
// The figures of the tools come from the tnvplot package (tools/plot/)
// run by Debian's /usr/bin/python3 with python3-matplotlib: the tool writes
// the figure's data (JSON or CSV) beside the figure, then runs the plotter.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tnv::cli {

// The directory holding the tnvplot package: the installed copy
// (<prefix>/share/tnv/python beside <prefix>/bin) or the source tree's.
std::string plot_package_dir();

// Runs /usr/bin/python3 -m tnvplot KIND INPUTS... OUTPUT EXTRA... (no
// shell; its output goes to stderr). "" when the figure was written, else
// what went wrong, naming `output`.
std::string run_plotter(const std::string& kind, const std::vector<std::string>& inputs, const std::string& output,
                        const std::vector<std::string>& extra = {});

// The file the data of `figure` is kept in: "out/c.svg" -> "out/c.plot.json"
// (suffix ".plot.csv" for CSV data), so the figure can be drawn again
// (python3 -m tnvplot KIND DATA OTHER.pdf).
std::string plot_data_path(const std::string& figure, const char* suffix = ".plot.json");

// Draws `figure` from data files already written; prints "[plot] wrote
// FIGURE" or the error on stderr (prefixed with `tool`). false on failure.
bool plot_files(const std::string& figure, const std::string& kind, const std::vector<std::string>& inputs,
                const std::vector<std::string>& extra, const char* tool);

// Writes `data` (kind "circle" or "panels") beside `figure` and draws it;
// prints "[plot] wrote FIGURE" or the error on stderr. false on failure.
bool plot_json(const std::string& figure, const nlohmann::json& data, const char* tool);

}  // namespace tnv::cli
