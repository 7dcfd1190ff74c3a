#pragma once
// Speed command <-> offset-binary DAC code. Reference plant: 12 bit, +-10 V,
// 1000 rpm at 10 V, 10 mm lead: +-166.67 mm/s, 1 LSB = 0.08138 mm/s.
#include <cmath>
#include <cstdint>

namespace tnv::fw {

struct DacScale {
  unsigned bits = 12;
  double full_scale_mm_s = 1000.0 * 10.0 / 60.0;  // speed at +full scale (10 V)
  bool operator==(const DacScale&) const = default;

  double lsb_mm_s() const noexcept { return full_scale_mm_s / static_cast<double>(mid_code()); }
  std::uint16_t mid_code() const noexcept { return static_cast<std::uint16_t>(1u << (bits - 1)); }
  std::uint16_t max_code() const noexcept { return static_cast<std::uint16_t>((1u << bits) - 1); }
};

// Rounded to the nearest code and saturated; a non-finite command gives
// mid-scale (0 V): the supervisor faults on it separately.
inline std::uint16_t speed_to_dac_code(double speed_mm_s, const DacScale& scale) noexcept {
  if (!std::isfinite(speed_mm_s)) return scale.mid_code();
  const double code = std::nearbyint(static_cast<double>(scale.mid_code()) + speed_mm_s / scale.lsb_mm_s());
  if (code <= 0.0) return 0;
  if (code >= static_cast<double>(scale.max_code())) return scale.max_code();
  return static_cast<std::uint16_t>(code);
}

inline double dac_code_to_speed_mm_s(std::uint16_t code, const DacScale& scale) noexcept {
  return (static_cast<double>(code) - static_cast<double>(scale.mid_code())) * scale.lsb_mm_s();
}

}  // namespace tnv::fw
