#pragma once
// The two table axes. Indexes every per-axis array in hal/, firmware/ and drivers/.
#include <cstddef>
#include <cstdint>

namespace tnv::hal {

enum class Axis : std::uint8_t { x = 0, y = 1 };

inline constexpr std::size_t kAxisCount = 2;

constexpr std::size_t index(Axis axis) noexcept { return static_cast<std::size_t>(axis); }

constexpr Axis axis_from_index(std::size_t i) noexcept { return i == 0 ? Axis::x : Axis::y; }

constexpr char axis_name(Axis axis) noexcept { return axis == Axis::x ? 'x' : 'y'; }

}  // namespace tnv::hal
