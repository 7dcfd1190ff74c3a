#pragma once
// The input-shaper families (seed digest S2 and the usual robust
// extensions): which impulse sequence cancels a mode, and how robustly.
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string_view>
#include "hal/listed_enum.hpp"

namespace tnv::fw {

// The families in wire order (SHAPER_CONFIG.type): the enum, its names and
// the protocol's value list come from this one list.
#define TNV_SHAPER_TYPES(X) \
  X(zv)    /* zero vibration: 2 impulses, half a damped period */ \
  X(zvd)   /* zero vibration and derivative: 3 impulses, one period */ \
  X(zvdd)  /* second derivative too: 4 impulses, 1.5 periods */ \
  X(ei)    /* extra-insensitive, 5 % vibration tolerance: 3 impulses, one period */ \
  X(mzv)   /* modified ZV: 3 impulses spaced 3/8 of a period (0.75 periods) */

TNV_LISTED_ENUM(ShaperType, TNV_SHAPER_TYPES)

constexpr std::optional<ShaperType> parse_shaper_type(std::string_view name) noexcept {
  for (ShaperType t : kShaperTypes)
    if (name == to_string(t)) return t;
  return std::nullopt;
}

// True for the shapers whose continuous impulses put an exact zero of
// vibration on the design mode (all but EI, which leaves its tolerance there).
constexpr bool zero_at_design_point(ShaperType t) noexcept { return t != ShaperType::ei; }

}  // namespace tnv::fw
