#include "firmware/spindle/spindle_params.hpp"

#include <cmath>

namespace tnv::fw {

namespace {
// lo < v <= hi, and finite.
bool in_left_open(double v, double lo, double hi) noexcept { return std::isfinite(v) && v > lo && v <= hi; }
}  // namespace

ParamCheck validate(const SpindleParams& p) noexcept {
  if (!in_left_open(p.max_rpm, 0.0, kSpindleDriveFullScaleRpm))
    return param_error(&p.max_rpm, "max_rpm", "must satisfy 0 < max_rpm <= 12000 (the drive's full scale)");
  if (!in_left_open(p.accel_rpm_s, 0.0, kSpindleDriveAccelRpmS))
    return param_error(&p.accel_rpm_s, "accel_rpm_s", "must satisfy 0 < accel_rpm_s <= 6000 (the drive's limit)");
  if (!in_left_open(p.at_speed_fraction, 0.0, 0.5))
    return param_error(&p.at_speed_fraction, "at_speed_fraction", "must satisfy 0 < at_speed_fraction <= 0.5");
  if (!std::isfinite(p.at_speed_floor_rpm) || p.at_speed_floor_rpm < 0.0 || p.at_speed_floor_rpm > 1'000.0)
    return param_error(&p.at_speed_floor_rpm, "at_speed_floor_rpm", "must satisfy 0 <= at_speed_floor_rpm <= 1000");
  if (p.at_speed_ticks < 1 || p.at_speed_ticks > 10'000)
    return param_error(&p.at_speed_ticks, "at_speed_ticks", "must satisfy 1 <= at_speed_ticks <= 10000");
  if (!in_left_open(p.standstill_rpm, 0.0, 500.0))
    return param_error(&p.standstill_rpm, "standstill_rpm", "must satisfy 0 < standstill_rpm <= 500");
  return param_ok();
}

}  // namespace tnv::fw
