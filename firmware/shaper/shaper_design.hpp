#pragma once
// What the operator configures (type, mode, optional second mode) and what
// the firmware makes of it: the continuous impulses and the taps on the
// control grid. Two modes: the two single-mode shapers in series
// (convolution), as for the 30 Hz and 100 Hz modes of the S2 XY stage.
#include "firmware/control/param_check.hpp"
#include "firmware/shaper/impulse_design.hpp"
#include "firmware/shaper/impulse_train.hpp"
#include "firmware/shaper/shaper_type.hpp"
#include "firmware/shaper/tap_set.hpp"

namespace tnv::fw {

struct ShaperSpec {
  ShaperType type = ShaperType::zvd;
  ModeSpec mode{};
  ModeSpec second_mode{0.0, 0.0};  // freq_hz == 0: single-mode shaper (same type for both)
  bool has_second_mode() const noexcept { return second_mode.freq_hz != 0.0; }
};

// fields "type", "mode.freq_hz", "mode.zeta", "second_mode.freq_hz", "second_mode.zeta".
ParamCheck validate(const ShaperSpec& spec) noexcept;

// Same type and modes: the same design (design_shaper is a pure function of the spec).
bool same_spec(const ShaperSpec& a, const ShaperSpec& b) noexcept;

struct ShaperDesign {
  ImpulseTrain impulses{};  // continuous (convolved for two modes)
  TapSet taps{};            // as implemented: exact_grid_taps (convolved for two modes)
  double period_s = 1e-3;
  double duration_s() const noexcept { return static_cast<double>(taps.span()) * period_s; }
  // Centroid of the taps: a ramp comes out delayed by exactly this.
  double delay_s() const noexcept { return taps.centroid_samples() * period_s; }
};

// Requires validate(spec).ok and period_s > 0.
ShaperDesign design_shaper(const ShaperSpec& spec, double period_s) noexcept;

}  // namespace tnv::fw
