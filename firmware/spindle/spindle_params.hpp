#pragma once
// The spindle's settings (reference plant "Spindle"; design notes
// "Spindle"). The drive's own limits are facts of the drive, not settings:
// 10 V of the 12-bit DAC is 12,000 rpm and its current limit ramps at most
// 6,000 rpm/s, so the settings may only stay inside them.
#include <cstdint>

#include "firmware/control/param_check.hpp"

namespace tnv::fw {

inline constexpr double kSpindleDriveFullScaleRpm = 12'000.0;  // 10 V on the spindle DAC
inline constexpr double kSpindleDriveAccelRpmS = 6'000.0;      // the drive's current limit
inline constexpr double kSpindleEncoderCountsPerRev = 4'096.0; // after x4 decoding

struct SpindleParams {
  double max_rpm = 12'000.0;         // a start or speed above this is refused
  double accel_rpm_s = 5'000.0;      // the command's ramp, inside the drive's limit
  double at_speed_fraction = 0.05;   // at speed: |n - n_cmd| <= fraction * |n_cmd| ...
  double at_speed_floor_rpm = 20.0;  // ... or this, whichever is larger
  std::uint32_t at_speed_ticks = 50; // ... held this many ticks in a row
  double standstill_rpm = 30.0;      // at or below it a stopping spindle counts as stopped
  bool operator==(const SpindleParams&) const = default;
};

// ok, or the first member out of its range (nothing is applied then).
ParamCheck validate(const SpindleParams& p) noexcept;

}  // namespace tnv::fw
