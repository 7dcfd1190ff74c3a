// Canned cycles G73, G81-G86 and G89 in the XY plane as LinuxCNC runs them:
// Z up to R if below it, exact path for the cycle, XY above R, down to R,
// the cycle's own moves, back to the clearance (R in G99, the Z the cycles
// began at in G98); R, Z, P and Q stay from the last line of the same
// cycle; L repeats; polar @ ^ place the hole (in G91 once per repeat: a
// bolt circle). The drilling cycles: G81 (feed in), G82 (and dwell), G83
// (pecks, out to R between), G73 (pecks, a small back-off between); the
// tapping cycle G84; the boring cycles G85 (feed out), G86 (spindle
// stopped, rapid out), G89 (dwell, feed out).
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>

#include "tools/gcode/canon_state.hpp"
#include "tools/gcode/ngc_error.hpp"

namespace tnv::gcode {

void CanonMachine::cycle_dwell() {
  char buf[48];
  std::snprintf(buf, sizeof buf, "DWELL(%.4f)", cycle_p_);
  emit(buf, valued(CanonMotion::Kind::dwell, cycle_p_));
}

void CanonMachine::canned_cycle(const NgcBlock& block, int motion, int column) {
  if (plane_ != 170) throw NgcError(column, "canned cycles only in the XY plane (G17) for now");
  const bool polar = block.polar_radius || block.polar_angle;  // never with X or Y (target() refused that)
  // R, Z, Q and the dwell P of G82/G86/G89 carry over from the line before
  // only while the same cycle goes on: a new cycle, or one after G80 or
  // another motion, names them again (an R or Z left from an earlier cycle
  // would be a guess at where the stock is). G84's P is kept whatever came between.
  // The cycles are whole codes. Appended, not "G" + std::to_string(...):
  // GCC 12 warns a false -Wrestrict on that operator+ when this file is
  // compiled on its own at -O2 (the plain, non-unity build).
  std::string cycle = "G";
  cycle += std::to_string(motion / 10);
  const auto needed = [&](char word, const char* what) {
    if (!block.has(word) && !cycle_continues_)
      throw NgcError(column, cycle + " needs " + static_cast<char>(std::toupper(static_cast<unsigned char>(word))) +
                                 " (" + what + "): a cycle's words carry over only while the same cycle goes on");
  };
  needed('r', "the retract plane");
  needed('z', "the bottom");
  if (motion == 730 || motion == 830) needed('q', "the peck depth");
  if (motion == 820 || motion == 860 || motion == 890) needed('p', "the dwell at the bottom, seconds");
  if (block.has('r')) { cycle_r_words_ = block.value('r'); cycle_r_ = length(cycle_r_words_); }
  if (block.has('z')) { cycle_z_words_ = block.value('z'); cycle_z_ = length(cycle_z_words_); }
  if (block.has('q')) { cycle_q_words_ = block.value('q'); cycle_q_ = length(cycle_q_words_); }
  if (block.has('p')) cycle_p_ = block.value('p');
  if ((motion == 730 || motion == 830) && !(cycle_q_ > 0.0))
    throw NgcError(block.has('q') ? block.column('q') : column, "G73/G83 need a peck depth Q > 0");
  if (block.has('p') && cycle_p_ < 0.0) throw NgcError(block.column('p'), "negative dwell time P");
  if (feed_ <= 0.0) throw NgcError(column, "cannot run a canned cycle with zero feed rate (F)");
  // G84 taps right-hand: the spindle must turn clockwise. G86 stops and
  // restarts the spindle: it must turn.
  if (motion == 840 && spindle_ != 3)
    throw NgcError(column, spindle_ == 4 ? "G84 with the spindle turning counterclockwise (it taps right-hand: M3)"
                                         : "G84 with the spindle stopped (it taps right-hand: M3)");
  if (motion == 860 && spindle_ == 5) throw NgcError(column, "G86 with the spindle stopped (M3 or M4 first)");
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
  // The first hole is reached at the clearance when the tool is below it
  // (a G98 line after G99 ones in the same run rises to the Z the run began
  // at on the way, as rs274 does), else where it is.
  double old_z = std::fmax(pos_[2], clear);
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
      if (motion == 820) cycle_dwell();
    } else if (motion == 840) {  // tap: in at feed, reverse, dwell, out at feed, forward again
      emit("DISABLE_FEED_OVERRIDE()");
      emit("DISABLE_SPEED_OVERRIDE(0)");
      move_feed({x, y, bottom}, column);
      emit("STOP_SPINDLE_TURNING(0)");
      emit("START_SPINDLE_COUNTERCLOCKWISE(0)", kind_only(CanonMotion::Kind::spindle_on));
      cycle_dwell();
      move_feed({x, y, clear}, column);
      emit("STOP_SPINDLE_TURNING(0)");
      emit("START_SPINDLE_CLOCKWISE(0)", kind_only(CanonMotion::Kind::spindle_on));
      emit("ENABLE_FEED_OVERRIDE()");
      emit("ENABLE_SPEED_OVERRIDE(0)");
    } else if (motion == 850) {  // bore: in and out to R at feed, then up to the clearance
      move_feed({x, y, bottom}, column);
      move_feed({x, y, r}, column);
      move_traverse({x, y, clear});
    } else if (motion == 860) {  // bore: in at feed, dwell, spindle stopped out at rapid, restarted
      move_feed({x, y, bottom}, column);
      cycle_dwell();
      emit("STOP_SPINDLE_TURNING(0)");
      move_traverse({x, y, clear});
      emit(spindle_ == 3 ? "START_SPINDLE_CLOCKWISE(0)" : "START_SPINDLE_COUNTERCLOCKWISE(0)", kind_only(CanonMotion::Kind::spindle_on));
    } else if (motion == 890) {  // bore: in at feed, dwell, out at feed
      move_feed({x, y, bottom}, column);
      cycle_dwell();
      move_feed({x, y, clear}, column);
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
    if (motion != 840 && motion != 850 && motion != 860 && motion != 890) move_traverse({x, y, clear});
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
