#pragma once
// Ball-screw compensation (issue 16): the encoder is on the motor, the
// program is for the table. Between them a worn screw loses motion at
// every reversal (backlash) and its lead is not exactly its nominal value
// (lead error, here its cumulative part). The compensation moves the
// motor-side reference the controllers follow so that the table follows
// the program:
//
//   x_motor = x_ref / (1 + c) + d * b / 2
//
// c = lead_um_per_m * 1e-6 (the table moves (1 + c) mm per motor mm,
// measured from the machine origin); b the backlash; d = +1 / -1 the
// direction the reference last moved (0 before its first move: the lash
// is assumed centred at power-up). A change of d moves the offset d * b / 2
// at backlash_rate_mm_s, not in one step, so a reversal asks the axis for
// a bounded extra speed. Fixed cost per tick, no allocation.
//
// What a motor-side encoder cannot tell: whether the lash really was
// centred at power-up (the first move's table position is off by up to
// b / 2 otherwise; homing takes the lash up in a known direction), and
// the lead error's periodic part within one turn (docs/robustness.md).
#include "firmware/control/param_check.hpp"

namespace tnv::fw {

struct ScrewCompensation {
  double backlash_mm = 0.0;          // b: lost motion at a reversal, 0 = off
  double backlash_rate_mm_s = 1.0;   // how fast the offset changes at a reversal (> 0)
  double lead_um_per_m = 0.0;        // c * 1e6: table travel error per metre of motor travel, 0 = off
};

// Finite; 0 <= b <= 0.2 mm; 0.01 <= rate <= 100 mm/s; |c| <= 1000 um/m.
ParamCheck validate(const ScrewCompensation& c) noexcept;
bool same(const ScrewCompensation& a, const ScrewCompensation& b) noexcept;

class ScrewCompensator {
 public:
  // The motor-side offsets for the tick's table-side references x_ref,k and
  // x_ref,k+1 (next), advancing the backlash state by one tick of tick_s.
  struct Offsets {
    double now_mm = 0.0;
    double next_mm = 0.0;
  };
  Offsets advance(const ScrewCompensation& c, double reference_mm, double next_reference_mm, double tick_s) noexcept;
  // The offset last applied at x_ref,k+1 (servo off: the reference that keeps the axis where it is).
  double next_offset_mm() const noexcept { return next_offset_mm_; }
  int direction() const noexcept { return direction_; }
  // Power-up: direction unknown, the lash assumed centred.
  void reset() noexcept { *this = ScrewCompensator{}; }

 private:
  int direction_ = 0;
  double backlash_offset_mm_ = 0.0;  // at x_ref,k
  double next_offset_mm_ = 0.0;
};

}  // namespace tnv::fw
