#pragma once
// 11-bit identifier layout: [10:6] message id, [5:0] node id. The message
// id sits in the high bits so that arbitration orders by message (an
// e-stop to any node beats every telemetry frame of every node); node 0 is
// broadcast and only e-stop and stop commands are accepted on it.
#include <cstdint>

namespace tnv::fw::can {

inline constexpr std::uint8_t kBroadcastNode = 0;
inline constexpr std::uint8_t kMaxNodeId = 63;
inline constexpr std::uint8_t kMaxMessageId = 31;

constexpr std::uint32_t make_can_id(std::uint8_t message_id, std::uint8_t node) noexcept {
  return (static_cast<std::uint32_t>(message_id & 0x1Fu) << 6) | (node & 0x3Fu);
}
constexpr std::uint8_t message_of(std::uint32_t can_id) noexcept {
  return static_cast<std::uint8_t>((can_id >> 6) & 0x1Fu);
}
constexpr std::uint8_t node_of(std::uint32_t can_id) noexcept { return static_cast<std::uint8_t>(can_id & 0x3Fu); }

}  // namespace tnv::fw::can
