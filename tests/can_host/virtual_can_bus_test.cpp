// The virtual bus: frame timing at the bit rate, arbitration by
// identifier, bounded node queues.
#include <gtest/gtest.h>

#include "tools/can/virtual_can_bus.hpp"

namespace tnv {
namespace {

using can_host::BusSide;
using can_host::Micros;
using can_host::VirtualCanBus;

hal::CanFrame frame(std::uint32_t id, std::uint8_t dlc = 8) {
  hal::CanFrame f;
  f.id = id;
  f.dlc = dlc;
  return f;
}

TEST(VirtualCanBus, AnEightByteFrameIs111BitsAnEmptyOne47) {
  EXPECT_EQ(VirtualCanBus::frame_bits(frame(0x100, 8)), 111u);
  EXPECT_EQ(VirtualCanBus::frame_bits(frame(0x100, 0)), 47u);
  hal::CanFrame ext = frame(0x100, 8);
  ext.extended = true;
  EXPECT_EQ(VirtualCanBus::frame_bits(ext), 131u);
}

TEST(VirtualCanBus, DeliversNoMoreFramesPerMillisecondThanFitAt1Mbit) {
  VirtualCanBus bus;
  for (int i = 0; i < 64; ++i) ASSERT_TRUE(bus.enqueue(BusSide::node, frame(0x600 + 1), Micros{0}));
  bus.advance_to(Micros{1000});
  int delivered = 0;
  while (bus.take(BusSide::host)) ++delivered;
  EXPECT_EQ(delivered, 9) << "1000 us / 111 us per frame";
  bus.advance_to(Micros{64 * 111});
  while (bus.take(BusSide::host)) ++delivered;
  EXPECT_EQ(delivered, 64) << "the last frame ends at 64 x 111 us";
  EXPECT_EQ(bus.counters().busy_bits, 64u * 111u);
}

TEST(VirtualCanBus, HalfTheBitRateHalvesTheFrames) {
  can_host::VirtualCanBusOptions o;
  o.bitrate_bit_s = 500'000;
  VirtualCanBus bus(o);
  for (int i = 0; i < 20; ++i) bus.enqueue(BusSide::node, frame(0x601), Micros{0});
  bus.advance_to(Micros{1000});
  int delivered = 0;
  while (bus.take(BusSide::host)) ++delivered;
  EXPECT_EQ(delivered, 4) << "1000 us / 222 us per frame";
}

TEST(VirtualCanBus, TheLowerIdentifierWinsArbitrationAmongFramesWaitingWhenTheBusFrees) {
  VirtualCanBus bus;
  bus.enqueue(BusSide::node, frame(0x601), Micros{0});  // on the wire first (alone at t = 0)
  bus.enqueue(BusSide::node, frame(0x602), Micros{10});
  bus.enqueue(BusSide::host, frame(0x081), Micros{20});  // waits for the bus, then beats 0x602
  bus.advance_to(Micros{1000});
  const auto first = bus.take(BusSide::host);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->id, 0x601u);
  const auto to_node = bus.take(BusSide::node);
  ASSERT_TRUE(to_node);
  EXPECT_EQ(to_node->id, 0x081u);
  const auto second = bus.take(BusSide::host);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->id, 0x602u);
}

TEST(VirtualCanBus, AFrameArrivesOnlyWhenItHasEnded) {
  VirtualCanBus bus;
  bus.enqueue(BusSide::host, frame(0x081), Micros{500});
  bus.advance_to(Micros{610});
  EXPECT_FALSE(bus.take(BusSide::node).has_value());
  bus.advance_to(Micros{611});
  EXPECT_TRUE(bus.take(BusSide::node).has_value());
}

TEST(VirtualCanBus, TheNodeTransmitQueueIsBoundedAndItsReceiveFifoDropsOverflow) {
  can_host::VirtualCanBusOptions o;
  o.node_tx_capacity = 4;
  o.node_rx_capacity = 2;
  VirtualCanBus bus(o);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(bus.enqueue(BusSide::node, frame(0x601), Micros{0}));
  EXPECT_FALSE(bus.enqueue(BusSide::node, frame(0x601), Micros{0})) << "full: CanPort::try_send must fail";
  for (int i = 0; i < 3; ++i) bus.enqueue(BusSide::host, frame(0x081), Micros{0});
  bus.advance_to(Micros{10'000});
  EXPECT_EQ(bus.counters().delivered_to_node, 2u);
  EXPECT_EQ(bus.counters().dropped_at_node, 1u);
}

}  // namespace
}  // namespace tnv
