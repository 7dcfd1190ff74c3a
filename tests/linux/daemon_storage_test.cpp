// tnv-fw's storage worker: save and load over CAN while the servo holds go
// through drivers::ThreadStorageWorker, not the real-time loop; the node
// answers when the file I/O is done. Loop overruns depend on the machine's
// load here (no SCHED_FIFO in tests), so they are printed, not asserted.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <thread>

#include "drivers/linux/register_server.hpp"
#include "drivers/linux/unix_seqpacket.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "tests/linux/rig_support.hpp"
#include "tools/tnv-board-emu/ticking_bus.hpp"
#include "tools/tnv-fw/daemon.hpp"

namespace tnv {
namespace {

TEST(DaemonStorage, SaveAndLoadWhileHoldingAreAnsweredByTheWorker) {
  test::ScratchDir dir;
  const fwd::DaemonConfig config = test::rig_config(dir);
  emu::Machine machine(*emu::resolve_scenario("no-cut").scenario);
  board_emu::TickingBus ticking(machine);
  std::string error;
  const int listen_fd = drivers::listen_seqpacket(config.board.path, error);
  ASSERT_GE(listen_fd, 0) << error;
  std::thread server([&] {
    const int fd = drivers::accept_seqpacket(listen_fd);
    drivers::ServeStats stats;
    drivers::serve_register_connection(fd, ticking, -1, stats);
    ::close(fd);
  });
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
  daemon.reset();
  server.join();
  ::close(listen_fd);
}

}  // namespace
}  // namespace tnv
