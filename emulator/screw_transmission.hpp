#pragma once
// The ball screw between the motor and the table ([plant.x] / [plant.y]
// backlash_um, lead_error_um_per_m, pitch_error_um, pitch_period_mm;
// docs/scenarios.md "Ball screw"). The encoder sits on the motor, so the
// plant state p is the motor side in mm of screw travel (motor angle times
// lead / 2 pi), and the table is what this transmission makes of it:
//
//   backlash (the play operator, lash b):  e = min(max(e, p - b/2), p + b/2)
//   lead error at the engaged position e:  table = e + c e + a sin(2 pi e / P)
//
// c = lead_error_um_per_m * 1e-6 (cumulative), a = pitch_error_um / 1000 mm,
// P = pitch_period_mm; both errors are zero at the machine origin e = 0.
// The lash starts centred (e = p at power-up): the first move in either
// direction loses b/2, every reversal after that loses b.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "emulator/scenario.hpp"

namespace tnv::emu {

class ScrewTransmission {
 public:
  ScrewTransmission(const AxisPlantParams& p, double motor_mm) noexcept
      : half_lash_mm_(p.backlash_um * 0.5e-3),
        lead_error_per_mm_(p.lead_error_um_per_m * 1e-6),
        pitch_error_mm_(p.pitch_error_um * 1e-3),
        pitch_wavenumber_per_mm_(p.pitch_period_mm > 0.0 ? 2.0 * std::numbers::pi / p.pitch_period_mm : 0.0),
        enabled_(p.backlash_um != 0.0 || p.lead_error_um_per_m != 0.0 || p.pitch_error_um != 0.0),
        engaged_mm_(motor_mm) {}

  // Off: the table is the motor side, exactly (no arithmetic on it).
  bool enabled() const noexcept { return enabled_; }
  bool has_backlash() const noexcept { return half_lash_mm_ > 0.0; }

  // The motor side is now at `motor_mm`. The play operator is rate
  // independent: exact when called at every extremum of p (the plant calls
  // it at every sub-step end; inside a sub-step p has at most one extremum,
  // where Karnopp sticks the axis at the sub-step's end anyway).
  void follow(double motor_mm) noexcept {
    engaged_mm_ = std::min(std::max(engaged_mm_, motor_mm - half_lash_mm_), motor_mm + half_lash_mm_);
  }
  // Where the thread engages: follows the motor side through the lash (itself without one).
  double engaged_mm(double motor_mm) const noexcept { return has_backlash() ? engaged_mm_ : motor_mm; }
  double table_mm(double motor_mm) const noexcept {
    const double e_mm = engaged_mm(motor_mm);
    return e_mm + lead_error_per_mm_ * e_mm + pitch_error_mm_ * std::sin(pitch_wavenumber_per_mm_ * e_mm);
  }

 private:
  double half_lash_mm_;
  double lead_error_per_mm_;
  double pitch_error_mm_;
  double pitch_wavenumber_per_mm_;
  bool enabled_;
  double engaged_mm_;
};

}  // namespace tnv::emu
