#pragma once
// The boring planner's learned state as the parameter image stores it
// (param_image.hpp, format version 3): a fixed block after the parameter
// entries, little-endian:
//   started u32 (0 or 1), parts i32, resets i32, streak i32,
//   position_streak 8 x i32,
//   theta 3 x f64, covariance 9 x f64 (row-major), innovation f64,
//   infeed_mm_rev 2 x f64 (top, bottom)
// Doubles are stored bit for bit, so a restored planner continues exactly.
// Decoding is all or nothing: a block that does not make a plausible state
// (validate(BoringStationState)) is refused, `out` untouched.
#include <cstddef>
#include <cstdint>
#include <span>

#include "firmware/adaptive/boring/boring_station.hpp"

namespace tnv::fw::can {

inline constexpr std::size_t kBoreStateImageBytes = 4 * (4 + kMaxBorePositions) + 8 * (3 + 9 + 1 + 2);

void encode_bore_state(const BoringStationState& state, std::span<std::uint8_t, kBoreStateImageBytes> out) noexcept;

bool decode_bore_state(std::span<const std::uint8_t, kBoreStateImageBytes> in, BoringStationState& out) noexcept;

}  // namespace tnv::fw::can
