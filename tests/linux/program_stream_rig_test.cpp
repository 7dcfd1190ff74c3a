// tnvctl run's library over the SocketCAN host bus (the same class as
// `--iface can0`, here on the Unix-socket CAN link) against tnv-fw in wall
// time on the two-process rig: the program streams with flow control, runs
// to its end on the path without an underrun, and is scored.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/linux/two_process_support.hpp"
#include "tools/can/program_run.hpp"

namespace tnv {
namespace {

TEST(TwoProcessRigProgram, AProgramStreamsOverTheSocketCanHostBusToTheDaemonAndRunsToItsEnd) {
  test::ScratchDir dir;
  const fwd::DaemonConfig config = test::rig_config(dir);
  const std::string config_file = dir.file("tnv-fw.toml");
  test::write_config(config_file, config);
  const pid_t emu = test::spawn({TNV_BOARD_EMU_EXE, "--socket", config.board.path, "--scenario", "no-cut", "--once"},
                                dir.file("emu.log"));
  const pid_t fw = test::spawn({TNV_FW_EXE, "--config", config_file}, dir.file("fw.log"));
  const std::string can_socket = config.can.interface_name.substr(5);
  for (int i = 0; i < 500 && !std::filesystem::exists(can_socket); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(std::filesystem::exists(can_socket)) << test::read_file(dir.file("fw.log"));
  {
    test::HostLink host(can_socket);
    // 40 lines of 0.5 mm at 5 mm/s, 4 s: each element 100 ms, so a loaded machine's hiccups cannot drain the queue.
    std::string program = "G17 G21 G91 F300\n";
    for (int i = 0; i < 20; ++i) program += "G1 X0.5 Y0.25\nG1 X0.5 Y-0.25\n";
    const can_host::ProgramRunResult r = can_host::run_gcode(host.client, program, {});
    EXPECT_EQ(r.stream.end, can_host::StreamResult::End::done) << r.stream.message << "\n"
                                                               << test::read_file(dir.file("fw.log"));
    EXPECT_EQ(r.stream.acknowledged, 40u);
    EXPECT_EQ(r.stream.underruns, 0u);
    ASSERT_TRUE(r.score);
    std::printf("[rig] tnv-fw over the Unix-socket CAN link: %zu samples, telemetry complete %d, contour error max "
                "%.3f um, path deviation max %.3f um, cycle %.3f s\n",
                r.samples.size(), r.telemetry_complete, r.score->contour_error_max_um, r.score->path_deviation_max_um,
                r.score->cycle_time_s);
    EXPECT_TRUE(r.telemetry_complete);
    EXPECT_LE(r.score->path_deviation_max_um, 5.0 + 2e-3);
    EXPECT_GT(r.score->cycle_time_s, 3.5);
  }
  ASSERT_EQ(::kill(fw, SIGTERM), 0);
  EXPECT_EQ(test::wait_exit(fw), 0);
  EXPECT_EQ(test::wait_exit(emu), 0);
}

}  // namespace
}  // namespace tnv
