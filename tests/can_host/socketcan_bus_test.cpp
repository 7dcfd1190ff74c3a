// The SocketCAN transport against a fake socket: setup, filters, errors,
// short reads, EAGAIN, error frames, send back-pressure.
#include <gtest/gtest.h>
#include <linux/can/error.h>

#include "tests/can_host/fake_socket_api.hpp"
#include "tools/can/socketcan_bus.hpp"

namespace tnv {
namespace {

using can_host::BusError;
using can_host::Micros;
using can_host::SocketCanBus;
using can_host::SocketCanOptions;
using test::FakeSocketApi;

SocketCanOptions options(std::uint8_t node = 5) {
  SocketCanOptions o;
  o.interface_name = "can7";
  o.node = node;
  return o;
}

std::string error_of(FakeSocketApi& api) {
  try {
    SocketCanBus bus(api, options());
  } catch (const BusError& e) {
    return e.what();
  }
  return "";
}

TEST(SocketCanBus, OpensFiltersForTheNodeAndBindsToTheNamedInterface) {
  FakeSocketApi api;
  SocketCanBus bus(api, options(5));
  EXPECT_EQ(api.asked_interface, "can7");
  EXPECT_EQ(api.bound_ifindex, FakeSocketApi::kIfIndex);
  EXPECT_TRUE(api.nonblocking);
  EXPECT_EQ(api.error_mask, CAN_ERR_MASK) << "error frames must be delivered to be counted";
  ASSERT_EQ(api.filters.size(), 1u);
  const can_filter f = api.filters[0];
  // The kernel's test: (received id & mask) == (filter id & mask).
  auto passes = [&](canid_t id) { return (id & f.can_mask) == (f.can_id & f.can_mask); };
  EXPECT_TRUE(passes((0x09u << 5) | 5u)) << "PARAM_REPLY of node 5";
  EXPECT_TRUE(passes((0x0Cu << 5) | 5u)) << "HEARTBEAT of node 5";
  EXPECT_FALSE(passes((0x09u << 5) | 6u)) << "another node";
  EXPECT_FALSE(passes(((0x09u << 5) | 5u) | CAN_EFF_FLAG)) << "extended frame";
  EXPECT_FALSE(passes(((0x09u << 5) | 5u) | CAN_RTR_FLAG)) << "remote frame";
  EXPECT_EQ(bus.describe(), "can7");
}

TEST(SocketCanBus, SetupFailuresNameTheInterfaceAndTheStepAndCloseTheSocket) {
  FakeSocketApi missing;
  missing.fail_index = ENODEV;
  std::string e = error_of(missing);
  EXPECT_NE(e.find("can7"), std::string::npos) << e;
  EXPECT_NE(e.find("no such network interface"), std::string::npos) << e;

  FakeSocketApi bind_fails;
  bind_fails.fail_bind = ENETDOWN;
  e = error_of(bind_fails);
  EXPECT_NE(e.find("can7: cannot bind"), std::string::npos) << e;
  EXPECT_NE(e.find(std::strerror(ENETDOWN)), std::string::npos) << e;
  EXPECT_EQ(bind_fails.closed, 1) << "the socket must not leak";

  FakeSocketApi filter_fails;
  filter_fails.fail_filters = EINVAL;
  e = error_of(filter_fails);
  EXPECT_NE(e.find("receive filter"), std::string::npos) << e;
  EXPECT_EQ(filter_fails.closed, 1);

  FakeSocketApi no_can;
  no_can.fail_open = EAFNOSUPPORT;
  e = error_of(no_can);
  EXPECT_NE(e.find("CAN_RAW"), std::string::npos) << e;
  EXPECT_EQ(no_can.closed, 0) << "nothing was opened";
}

// tnv-fw's owner-only `unix:` socket: another user's host is told why it
// was refused (tnvctl prints it, the Python module raises it).
TEST(SocketCanBus, ARefusedUnixSocketSaysItIsOwnerOnly) {
  SocketCanOptions unix_options = options();
  unix_options.interface_name = "unix:/run/tnv/can.sock";
  const auto error_for = [&](int bind_error) {
    FakeSocketApi api;
    api.fail_bind = bind_error;
    try {
      SocketCanBus bus(api, unix_options);
    } catch (const BusError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  std::string e = error_for(EACCES);
  EXPECT_NE(e.find("unix:/run/tnv/can.sock: refused"), std::string::npos) << e;
  EXPECT_NE(e.find("owner-only"), std::string::npos) << e;
  EXPECT_EQ(e.find("ip link set"), std::string::npos) << "a CAN interface's advice for a socket: " << e;
  e = error_for(ENOENT);
  EXPECT_NE(e.find("no node listening"), std::string::npos) << e;
}

TEST(SocketCanBus, ReceiveSkipsShortReadsErrorFramesAndRemoteFrames) {
  FakeSocketApi api;
  SocketCanBus bus(api, options());
  api.reads.push_back({{8, 0}, FakeSocketApi::frame(0x245, {1, 2, 3})});  // half a can_frame
  api.queue_frame(FakeSocketApi::frame(CAN_ERR_FLAG | CAN_ERR_BUSOFF, {}));
  api.queue_frame(FakeSocketApi::frame(CAN_ERR_FLAG | CAN_ERR_CRTL, {}));
  api.queue_frame(FakeSocketApi::frame(0x245 | CAN_RTR_FLAG, {}));
  api.queue_frame(FakeSocketApi::frame(0x245, {9, 8, 7, 6, 5, 4, 3, 2}));
  const auto f = bus.receive(Micros{10'000});
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->id, 0x245u);
  EXPECT_FALSE(f->extended);
  EXPECT_EQ(f->dlc, 8);
  EXPECT_EQ(f->data[0], 9);
  EXPECT_EQ(f->data[7], 2);
  const auto c = bus.counters();
  EXPECT_EQ(c.rx_short_reads, 1u);
  EXPECT_EQ(c.rx_error_frames, 2u);
  EXPECT_EQ(c.rx_frames, 1u);
  EXPECT_EQ(bus.last_error_class(), static_cast<canid_t>(CAN_ERR_CRTL));
}

TEST(SocketCanBus, EagainWaitsInPollAndATimeoutReturnsNothing) {
  FakeSocketApi api;
  SocketCanBus bus(api, options());
  // Nothing pending: poll for the whole timeout (rounded up to ms), then nullopt.
  const long long before = api.now_us;
  EXPECT_FALSE(bus.receive(Micros{2'500}).has_value());
  ASSERT_FALSE(api.poll_timeouts_ms.empty());
  EXPECT_EQ(api.poll_timeouts_ms.front(), 3);
  EXPECT_GE(api.now_us - before, 2'500);
  // EAGAIN first, then a frame becomes readable.
  api.reads.push_back({{-1, EAGAIN}, {}});
  api.queue_frame(FakeSocketApi::frame(0x305, {1}));
  const auto f = bus.receive(Micros{50'000});
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->id, 0x305u);
  EXPECT_EQ(f->dlc, 1);
}

TEST(SocketCanBus, ExtendedFramesKeepTheirIdentifier) {
  FakeSocketApi api;
  SocketCanBus bus(api, options());
  api.queue_frame(FakeSocketApi::frame(0x1ABCDEu | CAN_EFF_FLAG, {1, 2}));
  const auto f = bus.receive(Micros{1'000});
  ASSERT_TRUE(f.has_value());
  EXPECT_TRUE(f->extended);
  EXPECT_EQ(f->id, 0x1ABCDEu);
}

TEST(SocketCanBus, AReadErrorIsABusErrorNamingTheInterface) {
  FakeSocketApi api;
  SocketCanBus bus(api, options());
  api.reads.push_back({{-1, ENETDOWN}, {}});
  try {
    bus.receive(Micros{1'000});
    FAIL() << "expected BusError";
  } catch (const BusError& e) {
    EXPECT_NE(std::string(e.what()).find("can7: receive failed"), std::string::npos) << e.what();
  }
}

TEST(SocketCanBus, SendWritesTheFrameAndWaitsForRoomOnEagain) {
  FakeSocketApi api;
  SocketCanBus bus(api, options());
  hal::CanFrame frame;
  frame.id = 0x205;
  frame.dlc = 8;
  frame.data = {1, 2, 3, 4, 5, 6, 7, 8};
  api.writes.push_back({-1, EAGAIN});
  bus.send(frame);
  ASSERT_EQ(api.written.size(), 1u);
  EXPECT_EQ(api.written[0].can_id, 0x205u);
  EXPECT_EQ(api.written[0].can_dlc, 8);
  EXPECT_EQ(api.written[0].data[7], 8);
  EXPECT_EQ(bus.counters().tx_frames, 1u);
  EXPECT_FALSE(api.poll_timeouts_ms.empty()) << "EAGAIN must wait in poll(POLLOUT), not spin";
}

TEST(SocketCanBus, ATransmitQueueThatStaysFullIsABusErrorAfterTheSendTimeout) {
  FakeSocketApi api;
  SocketCanBus bus(api, options());
  api.tx_full = true;
  api.writable_after_poll = false;
  const long long before = api.now_us;
  try {
    bus.send(hal::CanFrame{});
    FAIL() << "expected BusError";
  } catch (const BusError& e) {
    EXPECT_NE(std::string(e.what()).find("can7: transmit queue full"), std::string::npos) << e.what();
  }
  EXPECT_GE(api.now_us - before, 100'000) << "gave up before the send timeout";
  EXPECT_EQ(bus.counters().tx_frames, 0u);
}

TEST(SocketCanBus, AShortWriteIsABusError) {
  FakeSocketApi api;
  SocketCanBus bus(api, options());
  api.writes.push_back({4, 0});
  EXPECT_THROW(bus.send(hal::CanFrame{}), BusError);
}

}  // namespace
}  // namespace tnv
