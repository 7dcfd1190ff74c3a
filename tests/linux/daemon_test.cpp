// The daemon in-process against a board-server thread (the emulated board
// advancing one tick per snapshot read) and a host on the Unix-socket CAN
// link: parameter round trip, heartbeat, a circle, stop from the controlling thread
// with the outputs left safe. Exercises the loop thread, its start/stop
// and the histogram hand-off under TSan.
#include <gtest/gtest.h>
#include <unistd.h>


#include "tests/linux/board_server.hpp"
#include "tests/linux/rig_support.hpp"
#include "tools/tnv-fw/daemon.hpp"

namespace tnv {
namespace {

TEST(Daemon, ServesParametersAndHeartbeatsThenStopsWithOutputsSafe) {
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
    const can_host::Heartbeat hb = host.client.wait_heartbeat(can_host::Micros{3'000'000});
    EXPECT_EQ(hb.state, fw::MotionState::disabled);
    EXPECT_EQ(hb.fault, fw::FaultReason::none);
    const double before = host.client.get(test::gamma_x());
    const double target = before == 0.25 ? 0.3 : 0.25;
    EXPECT_DOUBLE_EQ(host.client.set(test::gamma_x(), target), target);
    EXPECT_DOUBLE_EQ(host.client.get(test::gamma_x()), target) << "read back over CAN";
    EXPECT_GE(host.bus.counters().rx_frames, 4u);
    // A whole circle on wall-clock ticks: the table starts at (R, 0) of the
    // scenario's 6 mm circle; 20 mm/s keeps it under 3 s.
    EXPECT_EQ(host.client.circle(6.0, 20.0).result, fw::can::ErrorCode::ok);
    const can_host::Heartbeat done = host.client.wait_at_rest(can_host::Micros{20'000'000});
    EXPECT_EQ(done.fault, fw::FaultReason::none);
  }
  const fwd::SafeStateReport safe = daemon->stop();
  EXPECT_TRUE(safe.safe) << safe.one_line();
  EXPECT_GT(daemon->loop_counters().cycles, 10u);
  EXPECT_EQ(daemon->latency().count, daemon->loop_counters().cycles);
  const std::string summary = daemon->summary();
  EXPECT_NE(summary.find("wake-up latency: min"), std::string::npos) << summary;
  daemon.reset();  // closes the register link: the server sees the peer leave
  EXPECT_EQ(board.join(), drivers::ServeEnd::peer_closed);
  emu::Machine& machine = board.machine();
  EXPECT_TRUE(machine.board_outputs().safe(machine.dac_mid_code()));
  EXPECT_GT(board.ticking().ticks_served(), 2000u) << "dwell + circle at 1 tick per ms";
  EXPECT_NEAR(machine.truth(hal::Axis::x).position_mm, 6.0, 0.05) << "back at the circle's start";
  EXPECT_NEAR(machine.truth(hal::Axis::y).position_mm, 0.0, 0.05);
}

// Commissioning mode on the board needs [safety] allow_commissioning: by
// default enter_commissioning is not_permitted and a safety parameter
// stays locked; with the key the same requests go through.
TEST(Daemon, CommissioningNeedsTheLocalPermission) {
  for (const bool allowed : {false, true}) {
    SCOPED_TRACE(allowed ? "allowed" : "default");
    test::ScratchDir dir;
    fwd::DaemonConfig config = test::rig_config(dir);
    config.safety.allow_commissioning = allowed;
    test::BoardServer board(config.board.path);
    ASSERT_TRUE(board.listening()) << board.error();
    std::string error;
    std::unique_ptr<fwd::Daemon> daemon = fwd::Daemon::open(config, {}, error);
    ASSERT_TRUE(daemon) << error;
    ASSERT_EQ(daemon->start(), "");
    {
      test::HostLink host(config.can.interface_name.substr(5));
      host.client.wait_heartbeat(can_host::Micros{3'000'000});
      const fw::can::ParamDef& floor = *fw::can::find_param("x.limits.following_floor_mm");
      fw::can::ErrorCode enter = fw::can::ErrorCode::ok;
      try {
        host.client.command(fw::can::CommandCode::enter_commissioning);
      } catch (const can_host::RequestError& e) {
        enter = e.code();
      }
      fw::can::ErrorCode set = fw::can::ErrorCode::ok;
      try {
        host.client.set(floor, 0.08);
      } catch (const can_host::RequestError& e) {
        set = e.code();
      }
      EXPECT_EQ(enter, allowed ? fw::can::ErrorCode::ok : fw::can::ErrorCode::not_permitted);
      EXPECT_EQ(set, allowed ? fw::can::ErrorCode::ok : fw::can::ErrorCode::commissioning_required);
      EXPECT_NEAR(host.client.get(floor), allowed ? 0.08 : 0.05, 1e-6);
    }
    EXPECT_TRUE(daemon->stop().safe);
  }
}

TEST(Daemon, AMissingBoardIsAOneLineErrorNamingTheSocket) {
  test::ScratchDir dir;
  fwd::DaemonConfig config = test::rig_config(dir);
  config.board.connect_timeout_ms = 0;
  std::string error;
  EXPECT_FALSE(fwd::Daemon::open(config, {}, error));
  EXPECT_EQ(error, config.board.path + ": cannot connect to the board: No such file or directory");
}

}  // namespace
}  // namespace tnv
