#pragma once
// Runs a command line (or the real tnv-hil binary, TNV_HIL_EXE) as a script
// would, capturing stdout, stderr and the exit code.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tnv::test {

struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

// Any command line through the shell; stderr goes through a temporary file.
inline CliRun run_command(const std::string& command_line) {
  static int counter = 0;
  std::string name = "tnv_cli_";
  name.append(std::to_string(::getpid())).append("_").append(std::to_string(++counter)).append(".err");
  const std::string err_path = (std::filesystem::temp_directory_path() / name).string();
  std::string cmd = command_line;
  cmd += " 2>";
  cmd += err_path;
  CliRun r;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return r;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) r.out.append(buf, n);
  const int status = ::pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream e(err_path);
  std::stringstream ss;
  ss << e.rdbuf();
  r.err = ss.str();
  std::filesystem::remove(err_path);
  return r;
}

inline CliRun run_tnv_hil(const std::string& args) {
  std::string cmd = TNV_HIL_EXE;
  cmd += ' ';
  cmd += args;
  return run_command(cmd);
}

}  // namespace tnv::test
