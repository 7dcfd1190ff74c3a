#pragma once
// 11-bit identifier layout: [10:5] message id, [4:0] node id. The message
// id sits in the high bits so that arbitration orders by message (an
// e-stop to any node beats every telemetry frame of every node); node 0 is
// broadcast and only e-stop and stop commands are accepted on it. Six bits
// of message id leave room for the per-axis messages (one id per axis of
// each per-axis block, protocol_messages.hpp).
#include <cstdint>

namespace tnv::fw::can {

inline constexpr std::uint8_t kBroadcastNode = 0;
inline constexpr unsigned kNodeIdBits = 5;
inline constexpr std::uint32_t kNodeIdMask = (1u << kNodeIdBits) - 1u;  // 0x1F
inline constexpr std::uint8_t kMaxNodeId = kNodeIdMask;                  // 31
inline constexpr std::uint32_t kMessageIdMask = (1u << (11 - kNodeIdBits)) - 1u;
inline constexpr std::uint8_t kMaxMessageId = kMessageIdMask;  // 63

constexpr std::uint32_t make_can_id(std::uint8_t message_id, std::uint8_t node) noexcept {
  return ((message_id & kMessageIdMask) << kNodeIdBits) | (node & kNodeIdMask);
}
constexpr std::uint8_t message_of(std::uint32_t can_id) noexcept {
  return static_cast<std::uint8_t>((can_id >> kNodeIdBits) & kMessageIdMask);
}
constexpr std::uint8_t node_of(std::uint32_t can_id) noexcept { return static_cast<std::uint8_t>(can_id & kNodeIdMask); }

}  // namespace tnv::fw::can
