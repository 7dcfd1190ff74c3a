// Canned cycles G73, G81, G82, G83 in the XY plane as LinuxCNC runs them:
// Z up to R if below it, exact path for the cycle, XY above R, down to R,
// the cycle's own moves, back to the clearance (R in G99, the Z the cycles
// began at in G98); R, Z, P and Q stay from the last cycle line; L repeats;
// polar @ ^ place the hole (in G91 once per repeat: a bolt circle).
#include <array>
#include <cmath>
#include <cstdio>

#include "tools/gcode/canon_state.hpp"
#include "tools/gcode/ngc_error.hpp"

namespace tnv::gcode {

void CanonMachine::canned_cycle(const NgcBlock& block, int motion, int column) {
  if (plane_ != 170) throw NgcError(column, "canned cycles only in the XY plane (G17) for now");
  const bool polar = block.polar_radius || block.polar_angle;  // never with X or Y (target() refused that)
  if (block.has('r')) { cycle_r_words_ = block.value('r'); cycle_r_ = length(cycle_r_words_); cycle_has_r_ = true; }
  if (block.has('z')) { cycle_z_words_ = block.value('z'); cycle_z_ = length(cycle_z_words_); cycle_has_z_ = true; }
  if (block.has('q')) { cycle_q_words_ = block.value('q'); cycle_q_ = length(cycle_q_words_); }
  if (block.has('p')) cycle_p_ = block.value('p');
  if (!cycle_has_r_) throw NgcError(column, "canned cycle needs R (the retract plane)");
  if (!cycle_has_z_) throw NgcError(column, "canned cycle needs Z (the bottom)");
  if ((motion == 730 || motion == 830) && !(cycle_q_ > 0.0))
    throw NgcError(block.has('q') ? block.column('q') : column, "G73/G83 need a peck depth Q > 0");
  if (motion == 820 && cycle_p_ < 0.0) throw NgcError(block.column('p'), "negative dwell time P");
  if (feed_ <= 0.0) throw NgcError(column, "cannot run a canned cycle with zero feed rate (F)");
  // G91: R from the Z the run of cycles began at, the bottom from R.
  const double r = absolute_ ? cycle_r_ : cycle_start_z_ + cycle_r_;
  const double bottom = absolute_ ? cycle_z_ : r + cycle_z_;
  if (bottom > r) throw NgcError(column, "canned cycle: R below the bottom Z");
  if ((motion == 730 || motion == 830) && (r - bottom) / cycle_q_ > 100000.0)
    throw NgcError(block.has('q') ? block.column('q') : column, "peck depth Q too small: more than 100000 pecks");
  int repeats = 1;
  if (block.has('l')) {
    repeats = static_cast<int>(block.value('l'));
    if (repeats < 0 || repeats > 100000) throw NgcError(block.column('l'), "canned cycle repeats L must be 0..100000");
  }
  const double clear = retract_old_z_ ? std::fmax(cycle_start_z_, r) : r;
  const double rapid_delta = 0.010 * 25.4;  // LinuxCNC's peck clearance, 0.010 inch
  // G91: X and Y step from the last hole, once per repeat.
  const double dx = block.has('x') ? length(block.value('x')) : 0.0;
  const double dy = block.has('y') ? length(block.value('y')) : 0.0;
  double x = absolute_ ? (block.has('x') ? dx : pos_[0]) : pos_[0];
  double y = absolute_ ? (block.has('y') ? dy : pos_[1]) : pos_[1];
  if (polar && absolute_) {  // G90: one hole at @ ^ (a missing one taken from here)
    const std::array<double, 2> xy = polar_xy(block, x, y);
    x = xy[0];
    y = xy[1];
  }
  // Up to R first, before the cycle's exact-path mode, when the run of
  // cycles began below it (LinuxCNC judges by that Z, not by Z now).
  if (cycle_start_z_ < r) move_traverse({pos_[0], pos_[1], r});
  double old_z = std::fmax(pos_[2], r);
  const bool switch_mode = control_ != 610;  // already exact path (G61): no switch, no switch back
  if (switch_mode) emit("SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)");
  for (int k = 0; k < repeats; ++k) {
    if (!absolute_ && polar) {  // G91: each repeat adds @ and ^ to the last hole's radius and angle
      const std::array<double, 2> xy = polar_xy(block, x, y);
      x = xy[0];
      y = xy[1];
    } else if (!absolute_) {
      x += dx;
      y += dy;
    }
    move_traverse({x, y, old_z});
    if (old_z != r) move_traverse({x, y, r});
    if (motion == 810 || motion == 820) {
      move_feed({x, y, bottom}, column);
      if (motion == 820) {
        char buf[48];
        std::snprintf(buf, sizeof buf, "DWELL(%.4f)", cycle_p_);
        emit(buf);
      }
    } else {
      // Pecks while above the bottom, then the last feed to the bottom. G83
      // retracts to R between pecks, G73 backs off by the clearance. The
      // pecks are counted as LinuxCNC counts them, in the program's units
      // from the words as written: a depth that lands on the bottom within
      // float noise pecks once more, or not, exactly as in rs274.
      const double r_words = absolute_ ? cycle_r_words_ : cycle_start_z_ / unit_mm_ + cycle_r_words_;
      const double bottom_words = absolute_ ? cycle_z_words_ : r_words + cycle_z_words_;
      for (double depth_words = r_words - cycle_q_words_; depth_words > bottom_words; depth_words -= cycle_q_words_) {
        const double depth = depth_words * unit_mm_;
        move_feed({x, y, depth}, column);
        if (motion == 830) move_traverse({x, y, r});
        move_traverse({x, y, depth + rapid_delta});
      }
      move_feed({x, y, bottom}, column);
    }
    move_traverse({x, y, clear});
    old_z = clear;
  }
  // Back to the program's path mode: the same call G61/G61.1/G64 makes,
  // and the naive-CAM tolerance whatever the mode.
  if (!switch_mode) return;
  emit_control_mode();
  if (control_ != 640) emit("SET_NAIVECAM_TOLERANCE(" + [this] {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4f", control_q_);
    return std::string(buf);
  }() + ")");
}

}  // namespace tnv::gcode
