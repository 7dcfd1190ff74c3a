// The firmware's SocketCAN port against the injectable fake socket API:
// filters, error-frame counting, non-blocking transmit with drop
// counting, bus-off and recovery.
#include <gtest/gtest.h>
#include <linux/can/error.h>

#include "drivers/linux/socketcan_port.hpp"
#include "tests/can_host/fake_socket_api.hpp"

namespace tnv {
namespace {

using drivers::SocketCanPort;
using test::FakeSocketApi;

std::unique_ptr<SocketCanPort> open_port(FakeSocketApi& api, std::uint8_t node = 5) {
  drivers::SocketCanPortOptions o;
  o.interface_name = "can1";
  o.node_id = node;
  o.bus_off_holdoff = drivers::Micros{100'000};
  std::string error;
  auto port = SocketCanPort::open(api, o, error);
  EXPECT_TRUE(port) << error;
  return port;
}

hal::CanFrame frame(std::uint32_t id) {
  hal::CanFrame f;
  f.id = id;
  f.dlc = 2;
  f.data[0] = 0xAB;
  return f;
}

TEST(SocketCanPort, FiltersThisNodeAndBroadcastStandardFramesAndEnablesErrorFrames) {
  FakeSocketApi api;
  auto port = open_port(api, 5);
  EXPECT_EQ(api.asked_interface, "can1");
  EXPECT_EQ(api.bound_ifindex, FakeSocketApi::kIfIndex);
  EXPECT_TRUE(api.nonblocking);
  EXPECT_EQ(api.error_mask, CAN_ERR_MASK);
  ASSERT_EQ(api.filters.size(), 2u);
  EXPECT_EQ(api.filters[0].can_id, 5u);
  EXPECT_EQ(api.filters[1].can_id, 0u);
  for (const can_filter& f : api.filters) EXPECT_EQ(f.can_mask, 0x1Fu | CAN_EFF_FLAG | CAN_RTR_FLAG);
}

TEST(SocketCanPort, SetupFailuresNameTheInterfaceAndTheStepAndCloseTheSocket) {
  FakeSocketApi api;
  api.fail_bind = ENETDOWN;
  drivers::SocketCanPortOptions o;
  o.interface_name = "can1";
  std::string error;
  EXPECT_FALSE(SocketCanPort::open(api, o, error));
  EXPECT_EQ(error, "can1: cannot bind (is the interface up?): Network is down");
  EXPECT_EQ(api.closed, 1);
}

TEST(SocketCanPort, ErrorFramesAreCountedNeverReturnedAndShortReadsDiscarded) {
  FakeSocketApi api;
  auto port = open_port(api);
  api.queue_frame(FakeSocketApi::frame(CAN_ERR_FLAG | CAN_ERR_CRTL, {0, CAN_ERR_CRTL_RX_PASSIVE}));
  api.reads.push_back({{8, 0}, FakeSocketApi::frame(0x305, {1})});  // half a frame
  api.queue_frame(FakeSocketApi::frame(CAN_ERR_FLAG | CAN_ERR_PROT, {}));
  api.queue_frame(FakeSocketApi::frame(0x305, {9, 8}));
  hal::CanFrame got;
  ASSERT_TRUE(port->try_receive(got));
  EXPECT_EQ(got.id, 0x305u);
  EXPECT_EQ(got.data[0], 9);
  EXPECT_FALSE(port->try_receive(got)) << "nothing pending: returns at once";
  const drivers::CanPortCounters c = port->counters();
  EXPECT_EQ(c.rx_frames, 1u);
  EXPECT_EQ(c.rx_error_frames, 2u);
  EXPECT_EQ(port->error_frames(), 2u) << "what the node's heartbeat reports";
  EXPECT_EQ(c.error_passive_events, 1u);
  EXPECT_EQ(c.rx_short_reads, 1u);
}

TEST(SocketCanPort, AFullTransmitQueueDropsAndCountsWithoutBlocking) {
  FakeSocketApi api;
  auto port = open_port(api);
  EXPECT_EQ(port->try_send(frame(0x305)), hal::HalStatus::ok);
  api.tx_full = true;
  for (int i = 0; i < 5; ++i) EXPECT_EQ(port->try_send(frame(0x305)), hal::HalStatus::timeout);
  EXPECT_TRUE(api.poll_timeouts_ms.empty()) << "never waits for room";
  api.tx_full = false;
  api.writes.push_back({-1, ENETDOWN});
  EXPECT_EQ(port->try_send(frame(0x305)), hal::HalStatus::bus_error);
  const drivers::CanPortCounters c = port->counters();
  EXPECT_EQ(c.tx_frames, 1u);
  EXPECT_EQ(c.tx_dropped, 6u);
  ASSERT_EQ(api.written.size(), 1u);
  EXPECT_EQ(api.written[0].can_id, 0x305u);
  EXPECT_EQ(api.written[0].can_dlc, 2);
}

TEST(SocketCanPort, BusOffSilencesTransmitForTheHoldoffThenAProbeRecovers) {
  FakeSocketApi api;
  auto port = open_port(api);
  api.queue_frame(FakeSocketApi::frame(CAN_ERR_FLAG | CAN_ERR_BUSOFF, {}));
  hal::CanFrame got;
  EXPECT_FALSE(port->try_receive(got));
  EXPECT_TRUE(port->bus_off());
  EXPECT_EQ(port->try_send(frame(0x305)), hal::HalStatus::timeout);
  EXPECT_TRUE(api.written.empty()) << "nothing written while bus-off";
  api.now_us += 50'000;
  EXPECT_EQ(port->try_send(frame(0x305)), hal::HalStatus::timeout) << "still inside the 100 ms hold-off";
  api.now_us += 60'000;
  api.tx_full = true;  // the probe fails: another hold-off
  EXPECT_EQ(port->try_send(frame(0x305)), hal::HalStatus::timeout);
  EXPECT_TRUE(port->bus_off());
  api.tx_full = false;
  EXPECT_EQ(port->try_send(frame(0x305)), hal::HalStatus::timeout) << "hold-off restarted by the failed probe";
  api.now_us += 100'000;
  EXPECT_EQ(port->try_send(frame(0x305)), hal::HalStatus::ok);
  EXPECT_FALSE(port->bus_off());
  const drivers::CanPortCounters c = port->counters();
  EXPECT_EQ(c.bus_off_events, 1u);
  EXPECT_EQ(c.bus_off_recoveries, 1u);
  EXPECT_EQ(c.tx_dropped, 4u);
  EXPECT_EQ(c.tx_frames, 1u);
}

TEST(SocketCanPort, TheControllersRestartMessageEndsBusOff) {
  FakeSocketApi api;
  auto port = open_port(api);
  api.queue_frame(FakeSocketApi::frame(CAN_ERR_FLAG | CAN_ERR_BUSOFF, {}));
  api.queue_frame(FakeSocketApi::frame(CAN_ERR_FLAG | CAN_ERR_RESTARTED, {}));
  hal::CanFrame got;
  EXPECT_FALSE(port->try_receive(got));
  EXPECT_FALSE(port->bus_off());
  EXPECT_EQ(port->try_send(frame(0x305)), hal::HalStatus::ok) << "no hold-off after the kernel restarted the controller";
  EXPECT_EQ(port->counters().bus_off_recoveries, 1u);
}

}  // namespace
}  // namespace tnv
