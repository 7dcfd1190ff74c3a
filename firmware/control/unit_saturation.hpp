#pragma once
// S1 eqs. (4)-(7): sat(.) is the unit saturation, linear inside [-1, 1].

namespace tnv::fw {

constexpr double sat_unit(double v) noexcept { return v > 1.0 ? 1.0 : (v < -1.0 ? -1.0 : v); }

}  // namespace tnv::fw
