#pragma once
// Units the firmware tests share: the 1 ms control tick and one encoder
// count (10 mm lead / 24,000 counts per revolution).
#include <numbers>

namespace tnv::fw::test_units {

inline constexpr double kPeriodS = 1e-3;
inline constexpr double kCountMm = 10.0 / 24000.0;
inline constexpr double kPi = std::numbers::pi;

}  // namespace tnv::fw::test_units
