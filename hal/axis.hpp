#pragma once
// The machine's axes: THE list. It indexes every per-axis array in hal/,
// firmware/, drivers/ and emulator/, and the per-axis parameter rows,
// protocol fields, capture channels and register rows are generated from it
// (docs/architecture.md, "an axis"). What is a fact of the XY plane (the
// circle, arcs, the contour error) names kPlaneAxes instead.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

// X(name, homing_rank): one line per axis, in index order. The name is one
// lower-case letter; it is the axis' prefix in parameter names ("x.") and its
// suffix in protocol fields and capture channels ("pos_x"). A homing command
// for several axes homes them one after the other in homing_rank order
// (lowest first; kHomingOrder).
#define TNV_AXES(X) \
  X(x, 1)           \
  X(y, 2)           \
  X(z, 0)

namespace tnv::hal {

enum class Axis : std::uint8_t {
#define TNV_AXIS_ENUMERATOR(name, ...) name,
  TNV_AXES(TNV_AXIS_ENUMERATOR)
#undef TNV_AXIS_ENUMERATOR
};

// Every axis, in index order (for range-for over the axes).
inline constexpr std::array kAxes{
#define TNV_AXIS_VALUE(name, ...) Axis::name,
    TNV_AXES(TNV_AXIS_VALUE)
#undef TNV_AXIS_VALUE
};

inline constexpr std::size_t kAxisCount = kAxes.size();

// The names, in index order ("x", "y"): also the value list of the protocol's axis fields.
inline constexpr std::array<const char*, kAxisCount> kAxisNames{
#define TNV_AXIS_NAME(name, ...) #name,
    TNV_AXES(TNV_AXIS_NAME)
#undef TNV_AXIS_NAME
};

constexpr std::size_t index(Axis axis) noexcept { return static_cast<std::size_t>(axis); }

// i < kAxisCount (a caller's loop bound or a checked wire field).
constexpr Axis axis_from_index(std::size_t i) noexcept { return kAxes[i]; }

constexpr const char* axis_label(Axis axis) noexcept { return kAxisNames[index(axis)]; }

constexpr char axis_name(Axis axis) noexcept { return kAxisNames[index(axis)][0]; }

// 'X' for x: the name in upper case (tables and reports).
constexpr char axis_upper_name(Axis axis) noexcept { return static_cast<char>(axis_name(axis) - 'a' + 'A'); }

// A per-axis array with `value` on every axis (an initialiser that does not
// list the axes, so it follows the list).
template <class T>
constexpr std::array<T, kAxisCount> per_axis(const T& value) noexcept {
  std::array<T, kAxisCount> out{};
  out.fill(value);
  return out;
}

// The axis named `name` ("x"), none for anything else.
constexpr std::optional<Axis> axis_from_name(std::string_view name) noexcept {
  for (const Axis a : kAxes)
    if (name == axis_label(a)) return a;
  return std::nullopt;
}

// The axes in the order a homing command for several of them homes them.
inline constexpr std::array<Axis, kAxisCount> kHomingOrder = [] {
  constexpr std::array<int, kAxisCount> rank{
#define TNV_AXIS_HOMING_RANK(name, homing_rank, ...) homing_rank,
      TNV_AXES(TNV_AXIS_HOMING_RANK)
#undef TNV_AXIS_HOMING_RANK
  };
  std::array<Axis, kAxisCount> order = kAxes;
  for (std::size_t i = 1; i < kAxisCount; ++i)  // insertion sort: stable, constexpr
    for (std::size_t j = i; j > 0 && rank[index(order[j])] < rank[index(order[j - 1])]; --j) {
      const Axis t = order[j];
      order[j] = order[j - 1];
      order[j - 1] = t;
    }
  return order;
}();

// A set of axes, one bit per axis (bit index(axis)).
using AxisSet = std::uint32_t;
static_assert(kAxisCount < 32, "an AxisSet holds one bit per axis");
constexpr AxisSet axis_bit(Axis axis) noexcept { return AxisSet{1} << index(axis); }
inline constexpr AxisSet kEveryAxis = (AxisSet{1} << kAxisCount) - 1;
constexpr bool contains(AxisSet set, Axis axis) noexcept { return (set & axis_bit(axis)) != 0; }

// The XY plane: where circles, arcs, the contour error and the milling force
// live. Code that is plane geometry uses these two, not "every axis".
inline constexpr Axis kPlaneFirst = Axis::x;
inline constexpr Axis kPlaneSecond = Axis::y;

namespace detail {
constexpr bool axes_well_formed() {
  for (std::size_t i = 0; i < kAxisCount; ++i) {
    if (index(kAxes[i]) != i) return false;
    const char* n = kAxisNames[i];
    if (n[0] < 'a' || n[0] > 'z' || n[1] != '\0') return false;
    for (std::size_t j = 0; j < i; ++j)
      if (kAxisNames[j][0] == n[0]) return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::axes_well_formed(), "TNV_AXES: one distinct lower-case letter per axis, in index order");
static_assert(kAxisCount >= 2, "the XY plane needs its two axes");

}  // namespace tnv::hal
