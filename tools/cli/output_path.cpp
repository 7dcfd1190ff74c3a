#include "tools/cli/output_path.hpp"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>

namespace tnv::cli {

namespace fs = std::filesystem;

namespace {

std::string writable_dir_problem(const fs::path& dir, const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (ec || !fs::exists(st)) return path + ": directory " + dir.string() + " does not exist";
  if (!fs::is_directory(st)) return path + ": " + dir.string() + " is not a directory";
  if (::access(dir.c_str(), W_OK | X_OK) != 0) return path + ": directory " + dir.string() + " is not writable";
  return {};
}

}  // namespace

std::string output_file_problem(const std::string& path) {
  if (path.empty()) return "an empty output path";
  if (path == "-") return {};  // stdout, where a tool allows it
  const fs::path p(path);
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(p, ec);
  if (!ec && fs::exists(st)) {
    const fs::file_status target = fs::status(p, ec);
    if (ec || !fs::is_regular_file(target)) return path + ": exists and is not a regular file";
    if (::access(p.c_str(), W_OK) != 0) return path + ": not writable";
  }
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  return writable_dir_problem(dir, path);
}

std::string plot_file_problem(const std::string& path) {
  std::string problem = output_file_problem(path);
  if (!problem.empty() || path == "-") return path == "-" ? path + ": a figure needs a file" : problem;
  const std::string suffix = fs::path(path).extension().string();
  if (suffix != ".svg" && suffix != ".png" && suffix != ".pdf")
    return path + ": a figure is .svg, .png or .pdf (the suffix chooses)";
  return {};
}

std::string output_dir_problem(const std::string& path) {
  if (path.empty()) return "an empty output directory";
  fs::path p(path);
  std::error_code ec;
  // The nearest part of the path that exists must be a writable directory (the rest is created).
  while (!p.empty() && !fs::exists(fs::symlink_status(p, ec))) {
    if (!p.has_parent_path() || p.parent_path() == p) {
      p = ".";
      break;
    }
    p = p.parent_path();
  }
  if (p.empty()) p = ".";
  return writable_dir_problem(p, path);
}

CLI::Validator OutputFile() {
  return CLI::Validator(output_file_problem, "FILE", "writable output file");
}

CLI::Validator PlotFile() {
  return CLI::Validator(plot_file_problem, "FILE", "writable .svg, .png or .pdf");
}

CLI::Validator OutputDir() {
  return CLI::Validator(output_dir_problem, "DIR", "writable output directory");
}

bool write_file_replacing(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::trunc | std::ios::binary);
    out << text;
    out.flush();
    if (!out) {
      ::unlink(temporary.c_str());
      return false;
    }
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    ::unlink(temporary.c_str());
    return false;
  }
  return true;
}

}  // namespace tnv::cli
