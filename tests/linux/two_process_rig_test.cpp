// The two-process rig on one machine: tnv-board-emu serving the emulated
// board on a Unix socket and tnv-fw (no tick line: clock_nanosleep
// deadlines) talking CAN over the Unix-socket link; the test is the host.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/linux/two_process_support.hpp"

namespace tnv {
namespace {

using test::read_file;
using test::spawn;
using test::wait_exit;

TEST(TwoProcessRig, ParameterRoundTripOverCanThenSigtermLeavesTheOutputsSafe) {
  test::ScratchDir dir;
  const test::RigProcesses rig = test::start_rig(dir, test::rig_config(dir));
  const pid_t emu = rig.emu;
  const pid_t fw = rig.fw;
  ASSERT_FALSE(rig.can_socket.empty());
  {
    test::HostLink host(rig.can_socket);
    EXPECT_EQ(host.client.wait_heartbeat(can_host::Micros{3'000'000}).fault, fw::FaultReason::none);
    EXPECT_DOUBLE_EQ(host.client.set(test::gamma_x(), 0.25), 0.25);
    EXPECT_DOUBLE_EQ(host.client.get(test::gamma_x()), 0.25);
  }
  ASSERT_EQ(::kill(fw, SIGTERM), 0);
  EXPECT_EQ(wait_exit(fw), 0);
  EXPECT_EQ(wait_exit(emu), 0) << "--once: the emulator ends when the firmware leaves";
  const std::string fw_log = read_file(dir.file("fw.log"));
  EXPECT_NE(fw_log.find("tnv-fw: stopped (SIGTERM); outputs safe: DAC x 2048, DAC y 2048, DAC z 2048, DAC spindle 2048 (mid-scale 2048), enables 0x0"),
            std::string::npos)
      << fw_log;
  const std::string emu_log = read_file(dir.file("emu.log"));
  EXPECT_NE(emu_log.find("tnv-board-emu: firmware disconnected after"), std::string::npos) << emu_log;
}

TEST(TwoProcessRig, ABadConfigExitsWithCode2AndOneLine) {
  test::ScratchDir dir;
  const std::string config_file = dir.file("bad.toml");
  std::ofstream(config_file) << "[board]\ntransport = \"socket\"\npath = \"/x\"\n[rt]\npriority = 100\n";
  const pid_t fw = spawn({TNV_FW_EXE, "--config", config_file}, dir.file("fw.log"));
  EXPECT_EQ(wait_exit(fw), 2);
  EXPECT_EQ(read_file(dir.file("fw.log")), "tnv-fw: " + config_file + ":5: rt.priority: must be 0..99 (got 100)\n");
}

TEST(TwoProcessRig, LatencyTestPrintsACyclictestLikeSummary) {
  test::ScratchDir dir;
  const pid_t fw = spawn({TNV_FW_EXE, "--latency-test", "0.05"}, dir.file("lat.log"));
  EXPECT_EQ(wait_exit(fw), 0);
  const std::string log = read_file(dir.file("lat.log"));
  EXPECT_NE(log.find("# tnv-fw latency test: period 1000 us, 50 cycles"), std::string::npos) << log;
  EXPECT_NE(log.find("p99 "), std::string::npos) << log;
}

}  // namespace
}  // namespace tnv
