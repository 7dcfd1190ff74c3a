// The node's transmit queue: CAN-id order, oldest first among equals, and
// telemetry (droppable) is what makes room when it is full.
#include <gtest/gtest.h>

#include <vector>

#include "firmware/can/tx_priority_queue.hpp"

namespace tnv::fw::can {
namespace {

hal::CanFrame frame(std::uint32_t id, std::uint8_t mark = 0) {
  hal::CanFrame f{id, false, 8, {}};
  f.data[0] = mark;
  return f;
}

std::vector<std::uint32_t> drain_ids(TxPriorityQueue& q) {
  std::vector<std::uint32_t> out;
  while (!q.empty()) {
    out.push_back(q.top().id);
    q.pop();
  }
  return out;
}

TEST(TxPriorityQueue, FramesLeaveByIdentifierThenByAge) {
  TxPriorityQueue q;
  q.push(frame(0x401), true);
  q.push(frame(0x301), false);
  q.push(frame(0x241, 1), false);
  q.push(frame(0x041), false);
  q.push(frame(0x241, 2), false);
  EXPECT_EQ(q.top().id, 0x041u);
  q.pop();
  EXPECT_EQ(q.top().data[0], 1) << "the older of two equal identifiers first";
  q.pop();
  EXPECT_EQ(q.top().data[0], 2);
  EXPECT_EQ(drain_ids(q), (std::vector<std::uint32_t>{0x241, 0x301, 0x401}));
}

TEST(TxPriorityQueue, WhenFullTelemetryMakesRoomAndNeverAReply) {
  TxPriorityQueue q;
  for (std::size_t i = 0; i < TxPriorityQueue::kCapacity; ++i)
    ASSERT_EQ(q.push(frame(i % 2 == 0 ? 0x401 : 0x441), true), TxPriorityQueue::Push::queued);
  // A reply evicts the lowest-priority telemetry frame.
  EXPECT_EQ(q.push(frame(0x0C1), false), TxPriorityQueue::Push::evicted_other);
  // Telemetry of lower priority than everything held is the one dropped.
  EXPECT_EQ(q.push(frame(0x481), true), TxPriorityQueue::Push::dropped);
  // Telemetry of higher priority replaces a lower one.
  EXPECT_EQ(q.push(frame(0x3C1), true), TxPriorityQueue::Push::evicted_other);
  EXPECT_EQ(q.size(), TxPriorityQueue::kCapacity);
  const std::vector<std::uint32_t> ids = drain_ids(q);
  EXPECT_EQ(ids.front(), 0x0C1u);
  EXPECT_EQ(ids[1], 0x3C1u);
  std::size_t high = 0;
  for (std::uint32_t id : ids) high += id == 0x441 ? 1 : 0;
  EXPECT_EQ(high, TxPriorityQueue::kCapacity / 2 - 2) << "the two evicted were the 0x441 frames";
}

TEST(TxPriorityQueue, AQueueFullOfRepliesDropsTheNewcomer) {
  TxPriorityQueue q;
  for (std::size_t i = 0; i < TxPriorityQueue::kCapacity; ++i) q.push(frame(0x0C1), false);
  EXPECT_EQ(q.push(frame(0x041), false), TxPriorityQueue::Push::dropped);
  EXPECT_EQ(q.push(frame(0x401), true), TxPriorityQueue::Push::dropped);
}

}  // namespace
}  // namespace tnv::fw::can
