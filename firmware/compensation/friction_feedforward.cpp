#include "firmware/compensation/friction_feedforward.hpp"

#include <cmath>

namespace tnv::fw {

ParamCheck validate(const FrictionFeedForward& ff) noexcept {
  struct Field {
    const char* name;
    const double* value;
  };
  const Field fields[] = {{"coulomb_mm_s", &ff.coulomb_mm_s},
                          {"stiction_mm_s", &ff.stiction_mm_s},
                          {"stribeck_mm_s", &ff.stribeck_mm_s},
                          {"gain", &ff.gain},
                          {"fraction", &ff.fraction}};
  for (const Field& f : fields)
    if (!std::isfinite(*f.value)) return param_error(f.value, f.name, "must be finite (NaN or inf given)");
  if (!(ff.coulomb_mm_s >= 0.0)) return param_error(&ff.coulomb_mm_s, "coulomb_mm_s", "must be >= 0");
  if (!(ff.stiction_mm_s >= ff.coulomb_mm_s))
    return param_error(&ff.stiction_mm_s, "stiction_mm_s", "must be >= coulomb_mm_s");
  if (!(ff.stribeck_mm_s > 0.0)) return param_error(&ff.stribeck_mm_s, "stribeck_mm_s", "must be > 0");
  if (!(ff.gain > 0.0)) return param_error(&ff.gain, "gain", "must be > 0");
  if (!(ff.fraction >= 0.0 && ff.fraction <= 1.5)) return param_error(&ff.fraction, "fraction", "must be 0 .. 1.5");
  return param_ok();
}

double stribeck_level_mm_s(const FrictionFeedForward& ff, double speed_mm_s) noexcept {
  const double r = speed_mm_s / ff.stribeck_mm_s;
  return ff.coulomb_mm_s + (ff.stiction_mm_s - ff.coulomb_mm_s) * std::exp(-r * r);
}

double friction_feedforward_mm_s(const FrictionFeedForward& ff, double ref_speed_now_mm_s,
                                 double ref_speed_next_mm_s) noexcept {
  if (!ff.enabled) return 0.0;
  const double v = 0.5 * (ref_speed_now_mm_s + ref_speed_next_mm_s);
  double dir = 0.0;
  if (std::fabs(v) > kReversalSpeed_mm_s) {
    dir = v > 0.0 ? 1.0 : -1.0;
  } else {
    // Turning round (or at rest): the way the reference is about to move.
    const double change = ref_speed_next_mm_s - ref_speed_now_mm_s;
    if (change > 0.0) dir = 1.0;
    if (change < 0.0) dir = -1.0;
  }
  return dir * ff.fraction * stribeck_level_mm_s(ff, v) / ff.gain;
}

}  // namespace tnv::fw
