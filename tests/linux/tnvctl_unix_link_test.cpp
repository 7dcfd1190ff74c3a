// tnvctl --iface unix:PATH reaches tnv-fw over its Unix-socket CAN link
// (the two-process rig without vcan): a parameter set and read back by the
// real tnvctl, then refused input that changes nothing, and a path with
// no daemon behind it.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "tests/linux/two_process_support.hpp"

namespace tnv {
namespace {

using test::read_file;
using test::spawn;
using test::wait_exit;

struct TnvctlRun {
  int exit_code;
  std::string output;
};

TnvctlRun tnvctl(const test::ScratchDir& dir, const std::string& iface, std::vector<std::string> args) {
  std::vector<std::string> argv{TNVCTL_EXE, "--iface", iface, "--timeout-ms", "2000"};
  argv.insert(argv.end(), args.begin(), args.end());
  const std::string log = dir.file("tnvctl.log");
  const int code = wait_exit(spawn(argv, log));
  return {code, read_file(log)};
}

TEST(TnvctlUnixLink, SetsAndReadsAParameterOfTheDaemonThenARefusalChangesNothing) {
  test::ScratchDir dir;
  const fwd::DaemonConfig config = test::rig_config(dir);
  const std::string config_file = dir.file("tnv-fw.toml");
  test::write_config(config_file, config);
  const pid_t emu = spawn({TNV_BOARD_EMU_EXE, "--socket", config.board.path, "--scenario", "no-cut", "--once"},
                          dir.file("emu.log"));
  const pid_t fw = spawn({TNV_FW_EXE, "--config", config_file}, dir.file("fw.log"));
  const std::string can_socket = config.can.interface_name.substr(5);
  for (int i = 0; i < 500 && !std::filesystem::exists(can_socket); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(std::filesystem::exists(can_socket)) << read_file(dir.file("fw.log"));
  const std::string iface = config.can.interface_name;

  const TnvctlRun set = tnvctl(dir, iface, {"params", "set", "x.sliding.gamma=0.375"});
  EXPECT_EQ(set.exit_code, 0) << set.output;
  const TnvctlRun get = tnvctl(dir, iface, {"--json", "params", "get", "x.sliding.gamma"});
  ASSERT_EQ(get.exit_code, 0) << get.output;
  EXPECT_NE(get.output.find("0.375"), std::string::npos) << get.output;

  // Out of range: refused before anything is sent (exit 2), named, and the value stays.
  const TnvctlRun bad = tnvctl(dir, iface, {"params", "set", "x.sliding.gamma=1e9"});
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("x.sliding.gamma"), std::string::npos) << bad.output;
  const TnvctlRun after = tnvctl(dir, iface, {"--json", "params", "get", "x.sliding.gamma"});
  EXPECT_NE(after.output.find("0.375"), std::string::npos) << after.output;

  // No daemon at the path: a clear error, exit 1.
  const TnvctlRun none = tnvctl(dir, "unix:" + dir.file("nobody.sock"), {"params", "get", "x.sliding.gamma"});
  EXPECT_EQ(none.exit_code, 1) << none.output;
  EXPECT_NE(none.output.find("tnvctl:"), std::string::npos) << none.output;

  ASSERT_EQ(::kill(fw, SIGTERM), 0);
  EXPECT_EQ(wait_exit(fw), 0) << read_file(dir.file("fw.log"));
  EXPECT_EQ(wait_exit(emu), 0);
}

}  // namespace
}  // namespace tnv
