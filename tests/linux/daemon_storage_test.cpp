// tnv-fw's storage worker: save and load over CAN while the servo holds go
// through drivers::ThreadStorageWorker, not the real-time loop; the node
// answers when the file I/O is done. Loop overruns depend on the machine's
// load here (no SCHED_FIFO in tests), so they are printed, not asserted.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "tests/linux/board_server.hpp"
#include "tests/linux/rig_support.hpp"
#include "tools/tnv-fw/daemon.hpp"

namespace tnv {
namespace {

TEST(DaemonStorage, SaveAndLoadWhileHoldingAreAnsweredByTheWorker) {
  test::ScratchDir dir;
  const fwd::DaemonConfig config = test::rig_config(dir);
  test::BoardServer board(config.board.path);
  ASSERT_TRUE(board.listening()) << board.error();
  std::string error;
  std::unique_ptr<fwd::Daemon> daemon = fwd::Daemon::open(config, {}, error);
  ASSERT_TRUE(daemon) << error;
  ASSERT_EQ(daemon->start(), "");
  {
    test::HostLink host(config.can.interface_name.substr(5));
    host.client.wait_heartbeat(can_host::Micros{3'000'000});
    EXPECT_EQ(host.client.command(fw::can::CommandCode::enable).result, fw::can::ErrorCode::ok);
    const double before = host.client.get(test::gamma_x());
    const double saved = before == 0.25 ? 0.3 : 0.25;
    ASSERT_DOUBLE_EQ(host.client.set(test::gamma_x(), saved), saved);
    EXPECT_EQ(host.client.command(fw::can::CommandCode::save_params).result, fw::can::ErrorCode::ok);
    EXPECT_TRUE(std::filesystem::is_regular_file(config.params.file));
    ASSERT_DOUBLE_EQ(host.client.set(test::gamma_x(), before), before);
    EXPECT_EQ(host.client.command(fw::can::CommandCode::load_params).result, fw::can::ErrorCode::ok);
    EXPECT_DOUBLE_EQ(host.client.get(test::gamma_x()), saved) << "the saved set, loaded whole";
    for (int k = 0; k < 50; ++k)
      EXPECT_EQ(host.client.command(fw::can::CommandCode::restore_defaults).result, fw::can::ErrorCode::ok);
    for (int k = 0; k < 10; ++k)
      EXPECT_EQ(host.client.command(fw::can::CommandCode::save_params).result, fw::can::ErrorCode::ok);
    const can_host::Heartbeat hb = host.client.wait_heartbeat(can_host::Micros{3'000'000});
    EXPECT_EQ(hb.state, fw::MotionState::holding);
    EXPECT_EQ(hb.fault, fw::FaultReason::none);
  }
  daemon->stop();
  const drivers::RtLoopCounters c = daemon->loop_counters();
  std::printf("daemon: %llu cycles, %llu overruns, %llu skipped ticks (50 restore_defaults, 11 saves, 1 load)\n",
              static_cast<unsigned long long>(c.cycles), static_cast<unsigned long long>(c.overruns),
              static_cast<unsigned long long>(c.skipped_ticks));
}

}  // namespace
}  // namespace tnv
