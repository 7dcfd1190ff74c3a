#include "tools/tune/shaper_choice.hpp"

namespace tnv::tune {

ShaperChoice shaper_for_mode(bool mode_found, double mode_hz, double mode_zeta) {
  ShaperChoice c;
  if (!mode_found) {
    c.note = "no structural mode identified";
    return c;
  }
  c.spec.type = fw::ShaperType::zvd;
  c.spec.mode = {mode_hz, mode_zeta};
  c.spec.second_mode = {0.0, 0.0};
  if (const fw::ParamCheck check = fw::validate(c.spec); !check.ok) {
    c.note = std::string("identified mode outside the shaper's range: ") + check.field + ": " + check.reason;
    return c;
  }
  c.enabled = true;
  return c;
}

}  // namespace tnv::tune
