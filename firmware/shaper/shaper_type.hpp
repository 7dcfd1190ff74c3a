#pragma once
// The input-shaper families (seed digest S2 and the usual robust
// extensions): which impulse sequence cancels a mode, and how robustly.
#include <cstdint>
#include <optional>
#include <string_view>

namespace tnv::fw {

enum class ShaperType : std::uint8_t {
  zv = 0,  // zero vibration: 2 impulses, half a damped period
  zvd,     // zero vibration and derivative: 3 impulses, one period
  zvdd,    // second derivative too: 4 impulses, 1.5 periods
  ei,      // extra-insensitive, 5 % vibration tolerance: 3 impulses, one period
  mzv,     // modified ZV: 3 impulses spaced 3/8 of a period (0.75 periods)
};

inline constexpr ShaperType kShaperTypes[] = {ShaperType::zv, ShaperType::zvd, ShaperType::zvdd, ShaperType::ei,
                                              ShaperType::mzv};

constexpr const char* to_string(ShaperType t) noexcept {
  switch (t) {
    case ShaperType::zv: return "zv";
    case ShaperType::zvd: return "zvd";
    case ShaperType::zvdd: return "zvdd";
    case ShaperType::ei: return "ei";
    case ShaperType::mzv: return "mzv";
  }
  return "?";
}

constexpr std::optional<ShaperType> parse_shaper_type(std::string_view name) noexcept {
  for (ShaperType t : kShaperTypes)
    if (name == to_string(t)) return t;
  return std::nullopt;
}

// True for the shapers whose continuous impulses put an exact zero of
// vibration on the design mode (all but EI, which leaves its tolerance there).
constexpr bool zero_at_design_point(ShaperType t) noexcept { return t != ShaperType::ei; }

}  // namespace tnv::fw
