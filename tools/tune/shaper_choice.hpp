#pragma once
// The input shaper for an identified mode (x.shaper.* / y.shaper.*), the
// rule: ZVD at the identified (f, zeta), enabled; none without a mode or
// outside the shaper's design range (5..200 Hz, zeta <= 0.3). ZVD rather
// than ZV: at a 3 % frequency error (the mode fit's tolerance) ZV leaves
// about 5 % of the vibration, ZVD well under 1 % (docs/autotune.md, measured
// by `tnv-hil shaper design`), for one damped period of delay instead of half.
#include <string>

#include "firmware/shaper/shaper_design.hpp"

namespace tnv::tune {

struct ShaperChoice {
  bool enabled = false;
  fw::ShaperSpec spec{};  // meaningful when enabled
  std::string note;       // why none
};

ShaperChoice shaper_for_mode(bool mode_found, double mode_hz, double mode_zeta);

}  // namespace tnv::tune
