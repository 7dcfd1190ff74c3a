#pragma once
// Output paths checked when the command line is parsed, before a run that
// may take minutes: a plot or CSV the tool cannot write is a bad command
// line (exit 2, nothing run), not a failure found at the end.
#include <CLI/CLI.hpp>
#include <string>

namespace tnv::cli {

// "" when `path` can be written as a file: its directory exists and is
// writable, and the path is absent or a regular file (not a directory, a
// FIFO, a device); else what is wrong, naming the path.
std::string output_file_problem(const std::string& path);
// output_file_problem(), and the suffix names a figure format the plotter
// writes: .svg, .png or .pdf.
std::string plot_file_problem(const std::string& path);
// "" when `path` is or can be made a writable directory (the nearest
// existing ancestor is a writable directory).
std::string output_dir_problem(const std::string& path);

// Writes `text` as the whole of `path`: into a file beside it, renamed over
// it, so a failed write leaves an existing file as it was. false when the
// file could not be written or renamed.
bool write_file_replacing(const std::string& path, const std::string& text);

// The same as CLI11 validators (->check(OutputFile())).
CLI::Validator OutputFile();
CLI::Validator OutputDir();
CLI::Validator PlotFile();

}  // namespace tnv::cli
