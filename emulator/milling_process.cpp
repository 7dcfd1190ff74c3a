#include "emulator/milling_process.hpp"

#include <cmath>

namespace tnv::emu {

MillingCoefficients milling_coefficients(const MillingProcessParams& p) noexcept {
  MillingCoefficients c;
  c.a11 = -std::exp(-p.sample_s / p.feed_time_constant_s);  // below S3 eq. (28)
  c.b11 = p.feed_gain * (1.0 + c.a11);
  c.a21 = -std::exp(-p.sample_s / p.force_time_constant_s);
  c.b21 = p.cutting_coefficient * (1.0 + c.a21);
  return c;
}

std::string validate_milling_process(const MillingProcessParams& p) {
  struct Field {
    const char* name;
    double value;
  };
  const Field fields[] = {{"sample_s", p.sample_s},
                          {"feed_time_constant_s", p.feed_time_constant_s},
                          {"feed_gain", p.feed_gain},
                          {"force_time_constant_s", p.force_time_constant_s},
                          {"cutting_coefficient", p.cutting_coefficient}};
  for (const Field& f : fields)
    if (!(std::isfinite(f.value) && f.value > 0.0)) return std::string(f.name) + ": must be > 0 and finite";
  return {};
}

double depth_profile_mm(const DepthProfile& d, double t_s) noexcept {
  if (t_s <= 0.0) return d.start_mm;
  if (t_s < d.rise_s) return d.start_mm + (d.peak_mm - d.start_mm) * t_s / d.rise_s;
  const double down_s = t_s - d.rise_s;
  if (down_s < d.fall_s) return d.peak_mm + (d.start_mm - d.peak_mm) * down_s / d.fall_s;
  return d.start_mm;
}

MillingProcess::MillingProcess(const MillingProcessParams& params) noexcept : c_(milling_coefficients(params)) {}

void MillingProcess::step(double u_applied, double depth_mm) noexcept {
  const double feed = -c_.a11 * feed_ + c_.b11 * (u_applied - force_);  // S3 eq. (27)
  const double force = -c_.a21 * force_ + c_.b21 * depth_mm * feed_;    // S3 eq. (28)
  feed_ = feed;
  force_ = force;
}

}  // namespace tnv::emu
