#pragma once
// Which cyclic messages are due: each one every tlm.*_ms ticks (1 ms
// each), 0 = off. A changed period restarts that message's count, so the
// first frame after a change comes one new period later.
#include <array>
#include <cstdint>

#include "firmware/can/node_settings.hpp"

namespace tnv::fw::can {

enum class Cyclic : std::uint8_t { heartbeat = 0, position, sliding, output, contour, arsc, spindle };
inline constexpr std::size_t kCyclicCount = 7;

constexpr std::uint32_t cyclic_bit(Cyclic c) noexcept { return 1u << static_cast<unsigned>(c); }

class TelemetryScheduler {
 public:
  // `ticks` new ticks have passed (normally 1); returns the cyclic_bit()s
  // of the messages due now (at most one frame of each, however many
  // periods passed).
  std::uint32_t advance(const TelemetryPeriods& periods, std::uint64_t ticks) noexcept;

 private:
  std::array<std::uint64_t, kCyclicCount> elapsed_{};
  std::array<std::uint32_t, kCyclicCount> period_{};
};

}  // namespace tnv::fw::can
