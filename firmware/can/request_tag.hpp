#pragma once
// The tag byte every answered request carries (byte 0 of COMMAND, JOG,
// MOVE, CIRCLE, SHAPER, EXCITE, PARAM_REQUEST, CAPTURE_CONTROL) and its
// reply echoes: the host id in the high nibble, the host's own sequence in
// the low nibble. A host tells its reply from a stale one or another
// host's by the whole byte; the node keys staged sets and command
// ownership on the host id. Host 0 is anonymous: only ESTOP and the
// broadcast stop are accepted from it.
#include <cstdint>

namespace tnv::fw::can {

inline constexpr std::uint8_t kAnonymousHost = 0;
inline constexpr std::uint8_t kMaxHostId = 15;

constexpr std::uint8_t host_of_tag(std::uint8_t tag) noexcept { return static_cast<std::uint8_t>(tag >> 4); }
constexpr std::uint8_t sequence_of_tag(std::uint8_t tag) noexcept { return static_cast<std::uint8_t>(tag & 0x0Fu); }
constexpr std::uint8_t make_tag(std::uint8_t host, std::uint8_t sequence) noexcept {
  return static_cast<std::uint8_t>(((host & 0x0Fu) << 4) | (sequence & 0x0Fu));
}

}  // namespace tnv::fw::can
