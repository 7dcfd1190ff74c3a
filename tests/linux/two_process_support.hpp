#pragma once
// The two-process rig's processes (tnv-board-emu, tnv-fw) for the tests
// that talk to it: spawn with output to a file, wait for the exit code,
// read a log, write the daemon's config.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <string>
#include <vector>

#include "tests/linux/rig_support.hpp"

extern char** environ;

namespace tnv::test {

inline pid_t spawn(const std::vector<std::string>& args, const std::string& out_file) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = -1;
  EXPECT_EQ(posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ), 0) << args[0];
  posix_spawn_file_actions_destroy(&actions);
  return pid;
}

inline int wait_exit(pid_t pid) {
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline void write_config(const std::string& path, const fwd::DaemonConfig& c) {
  std::ofstream out(path);
  out << "[board]\ntransport = \"socket\"\npath = \"" << c.board.path << "\"\nreply_timeout_ms = 2000\n"
      << "[can]\ninterface = \"" << c.can.interface_name << "\"\nnode_id = 1\n"
      << "[rt]\npriority = 0\nrequire = false\n"
      << "[tick]\nperiod_us = 1000\n"
      << "[params]\nfile = \"" << c.params.file << "\"\n";
}

// tnv-board-emu (--once) and tnv-fw on the rig config of `dir`, waited for
// until the daemon has bound its CAN socket; its path, or "" (with the
// daemon's log in a failure) when it never came.
struct RigProcesses {
  pid_t emu = -1;
  pid_t fw = -1;
  std::string can_socket;
};
inline RigProcesses start_rig(const ScratchDir& dir, const fwd::DaemonConfig& config) {
  const std::string config_file = dir.file("tnv-fw.toml");
  write_config(config_file, config);
  RigProcesses rig;
  rig.emu = spawn({TNV_BOARD_EMU_EXE, "--socket", config.board.path, "--scenario", "no-cut", "--once"},
                  dir.file("emu.log"));
  rig.fw = spawn({TNV_FW_EXE, "--config", config_file}, dir.file("fw.log"));
  // The firmware binds its CAN socket once the board has answered.
  const std::string can_socket = config.can.interface_name.substr(5);
  for (int i = 0; i < 500 && !std::filesystem::exists(can_socket); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(std::filesystem::exists(can_socket)) << read_file(dir.file("fw.log"));
  if (std::filesystem::exists(can_socket)) rig.can_socket = can_socket;
  return rig;
}

}  // namespace tnv::test
