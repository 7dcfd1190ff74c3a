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
// The lead error's periodic part within one turn of the screw (thread
// form, eccentricity) comes from a measured table: turn_error_mm[j] is the
// table's error at motor position j * P / 16 (mod P, P = turn_period_mm,
// from the firmware's zero), linearly interpolated in between. The motor
// position that puts the table at x_ref is then
//
//   x_motor = p0 - e_turn(p0),   p0 = x_ref / (1 + c) + d * b / 2
//
// (one fixed-point step: the error left is e_turn' * e_turn, about 0.01 um
// for the bench's +-4 um per 10 mm turn).
//
// What a motor-side encoder cannot tell: whether the lash really was
// centred at power-up (the first move's table position is off by up to
// b / 2 otherwise; homing takes the lash up in a known direction), nor any
// of b, c or the per-turn table: they are measured against the table
// (a laser interferometer's or gauge's file, tnv-hil screw-fit;
// docs/robustness.md), and the table holds only from the zero it was
// measured from (home).
#include <array>
#include <cstddef>

#include "firmware/control/param_check.hpp"

namespace tnv::fw {

inline constexpr std::size_t kTurnErrorPoints = 16;

struct ScrewCompensation {
  double backlash_mm = 0.0;          // b: lost motion at a reversal, 0 = off
  double backlash_rate_mm_s = 1.0;   // how fast the offset changes at a reversal (> 0)
  double lead_um_per_m = 0.0;        // c * 1e6: table travel error per metre of motor travel, 0 = off
  double turn_period_mm = 10.0;      // P: the per-turn table's period (the screw's lead)
  std::array<double, kTurnErrorPoints> turn_error_mm{};  // table error at j * P / 16; all 0 = off
  bool operator==(const ScrewCompensation&) const = default;
};

// Finite; 0 <= b <= 0.2 mm; 0.01 <= rate <= 100 mm/s; |c| <= 1000 um/m;
// 0.1 <= P <= 1000 mm; |turn error| <= 0.1 mm.
ParamCheck validate(const ScrewCompensation& c) noexcept;

// e_turn(motor_mm): the per-turn table, periodic, linearly interpolated.
double turn_error_mm(const ScrewCompensation& c, double motor_mm) noexcept;

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
