#pragma once
// Runs the real tnvctl (TNVCTL_EXE) or tnv-hil (TNV_HIL_EXE) as a script
// would: stdout, stderr, exit code; tnvctl's emulated-node storage goes to
// a per-test temporary directory (XDG_STATE_HOME), never the user's.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "tests/tools/cli_runner.hpp"

namespace tnv::test {

using ToolRun = CliRun;

inline ToolRun run_tool(const std::string& command_line) { return run_command(command_line); }

// A fresh state directory for the emulated node of one test.
inline std::filesystem::path state_dir(const std::string& test) {
  std::string name = "tnvctl_state_";
  name.append(std::to_string(::getpid())).append("_").append(test);
  const auto dir = std::filesystem::temp_directory_path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline ToolRun tnvctl(const std::filesystem::path& state, const std::string& args) {
  std::string cmd = "XDG_STATE_HOME=";
  cmd.append(state.string()).append(" ").append(TNVCTL_EXE).append(" ").append(args);
  return run_tool(cmd);
}

inline ToolRun tnv_hil(const std::string& args) {
  std::string cmd = TNV_HIL_EXE;
  return run_tool(cmd.append(" ").append(args));
}

inline std::filesystem::path write_file(const std::filesystem::path& path, const std::string& content) {
  std::ofstream(path) << content;
  return path;
}

inline bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

inline std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace tnv::test
