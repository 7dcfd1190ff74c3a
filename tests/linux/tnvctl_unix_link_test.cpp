// tnvctl --iface unix:PATH reaches tnv-fw over its Unix-socket CAN link
// (the two-process rig without vcan): a parameter set and read back by the
// real tnvctl, then refused input that changes nothing, and a path with
// no daemon behind it.
#include <gtest/gtest.h>

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
  const test::RigProcesses rig = test::start_rig(dir, config);
  ASSERT_FALSE(rig.can_socket.empty());
  const pid_t emu = rig.emu;
  const pid_t fw = rig.fw;
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
