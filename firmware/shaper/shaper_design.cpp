#include "firmware/shaper/shaper_design.hpp"

#include <cmath>

#include "firmware/shaper/grid_taps.hpp"

namespace tnv::fw {

ParamCheck validate(const ShaperSpec& spec) noexcept {
  if (!parse_shaper_type(to_string(spec.type))) return param_error("type", "must be zv, zvd, zvdd, ei or mzv");
  if (const ParamCheck c = validate(spec.mode); !c.ok)
    return param_error(c.field[0] == 'f' ? "mode.freq_hz" : "mode.zeta", c.reason);
  if (!std::isfinite(spec.second_mode.freq_hz))
    return param_error("second_mode.freq_hz", "must be finite: 0 (none) or 5..200 Hz");
  if (spec.has_second_mode()) {
    if (const ParamCheck c = validate(spec.second_mode); !c.ok)
      return param_error(c.field[0] == 'f' ? "second_mode.freq_hz" : "second_mode.zeta", c.reason);
  }
  return param_ok();
}

bool same_spec(const ShaperSpec& a, const ShaperSpec& b) noexcept {
  return a.type == b.type && a.mode.freq_hz == b.mode.freq_hz && a.mode.zeta == b.mode.zeta &&
         a.second_mode.freq_hz == b.second_mode.freq_hz && a.second_mode.zeta == b.second_mode.zeta;
}

ShaperDesign design_shaper(const ShaperSpec& spec, double period_s) noexcept {
  ShaperDesign d;
  d.period_s = period_s;
  d.impulses = design_impulses(spec.type, spec.mode);
  d.taps = exact_grid_taps(spec.type, spec.mode, period_s);
  if (spec.has_second_mode()) {
    d.impulses = convolve(d.impulses, design_impulses(spec.type, spec.second_mode));
    d.taps = convolve(d.taps, exact_grid_taps(spec.type, spec.second_mode, period_s));
  }
  return d;
}

}  // namespace tnv::fw
