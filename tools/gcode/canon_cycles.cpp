// Canned cycles G73 and G81-G89 as LinuxCNC runs them, in G17 (along Z),
// G18 (along Y) and G19 (along X); below for G17: Z up to R if below it,
// exact path for the cycle, XY above R, down to R, the cycle's own moves,
// back to the clearance (R in G99, the Z the cycles began at in G98); R,
// Z, P, Q and I J K stay from the last line of the same cycle; L repeats;
// polar @ ^ place the hole (in G91 once per repeat: a bolt circle). The
// drilling cycles: G81 (feed in), G82 (and dwell), G83 (pecks, out to R
// between), G73 (pecks, a small back-off between); the tapping cycle G84;
// the boring cycles G85 (feed out), G86 (spindle stopped, rapid out), G87
// (back boring), G88 (spindle stopped, program stop for a retract by
// hand), G89 (dwell, feed out).
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
  // The cycle's axes as LinuxCNC names them: the hole is placed on the
  // plane's two (a, b) and the tool moves along the third (c).
  std::size_t ia = 0, ib = 1, ic = 2;             // G17: X Y, along Z
  if (plane_ == 180) { ia = 2; ib = 0; ic = 1; }  // G18: Z X, along Y
  if (plane_ == 190) { ia = 1; ib = 2; ic = 0; }  // G19: Y Z, along X
  static constexpr char kAxis[] = "xyz";
  static constexpr char kOffset[] = "ijk";  // G87's offset along X, Y, Z
  const char word_a = kAxis[ia], word_b = kAxis[ib], word_c = kAxis[ic];
  const auto at = [&](double a, double b, double c) {
    Vec3 v{};
    v[ia] = a;
    v[ib] = b;
    v[ic] = c;
    return v;
  };
  const bool polar = block.polar_radius || block.polar_angle;  // G17 only, never with X or Y (execute() refused that)
  // R, the bottom, Q, the dwell P of G82/G86/G88/G89 and G87's I J K carry
  // over from the line before only while the same cycle goes on: a new
  // cycle, or one after G80 or another motion, names them again (an R or a
  // bottom left from an earlier cycle would be a guess at where the stock
  // is). G84's P is kept whatever came between.
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
  needed(word_c, "the bottom");
  if (motion == 730 || motion == 830) needed('q', "the peck depth");
  if (motion == 820 || motion == 860 || motion == 880 || motion == 890) needed('p', "the dwell at the bottom, seconds");
  if (motion == 870) {
    needed('i', "the offset along X to pass through the hole");
    needed('j', "the offset along Y to pass through the hole");
    needed('k', "the offset along Z to pass through the hole");
  }
  if (block.has('r')) { cycle_r_words_ = block.value('r'); cycle_r_ = length(cycle_r_words_); }
  if (block.has(word_c)) { cycle_z_words_ = block.value(word_c); cycle_z_ = length(cycle_z_words_); }
  if (block.has('q')) { cycle_q_words_ = block.value('q'); cycle_q_ = length(cycle_q_words_); }
  if (block.has('p')) cycle_p_ = block.value('p');
  for (std::size_t n = 0; n < 3; ++n)
    if (motion == 870 && block.has(kOffset[n])) cycle_ijk_[n] = length(block.value(kOffset[n]));
  if ((motion == 730 || motion == 830) && !(cycle_q_ > 0.0))
    throw NgcError(block.has('q') ? block.column('q') : column, "G73/G83 need a peck depth Q > 0");
  if (block.has('p') && cycle_p_ < 0.0) throw NgcError(block.column('p'), "negative dwell time P");
  if (feed_ <= 0.0) throw NgcError(column, "cannot run a canned cycle with zero feed rate (F)");
  // G84 taps right-hand: the spindle must turn clockwise. G86, G87 and G88
  // stop and restart the spindle: it must turn.
  if (motion == 840 && spindle_ != 3)
    throw NgcError(column, spindle_ == 4 ? "G84 with the spindle turning counterclockwise (it taps right-hand: M3)"
                                         : "G84 with the spindle stopped (it taps right-hand: M3)");
  // rs274 (LinuxCNC 2.9) taps outside G17 along permuted axes (G18: the
  // feed goes to X = the bottom, Y = Z, Z = X): a diagonal into the part.
  // Refused rather than imitated (docs/gcode.md, deviations).
  if (motion == 840 && plane_ != 170)
    throw NgcError(column, "G84 only in the XY plane (G17): LinuxCNC's rs274 taps along the wrong axes in G18/G19");
  if ((motion == 860 || motion == 870 || motion == 880) && spindle_ == 5)
    throw NgcError(column, cycle + " with the spindle stopped (M3 or M4 first)");
  // G91: R from where the run of cycles began along the cycle's axis, the bottom from R.
  const double r = absolute_ ? cycle_r_ : cycle_start_z_ + cycle_r_;
  const double bottom = absolute_ ? cycle_z_ : r + cycle_z_;
  if (bottom > r)
    throw NgcError(column, std::string("canned cycle: R below the bottom ") +
                               static_cast<char>(std::toupper(static_cast<unsigned char>(word_c))));
  if ((motion == 730 || motion == 830) && (r - bottom) / cycle_q_ > 100000.0)
    throw NgcError(block.has('q') ? block.column('q') : column, "peck depth Q too small: more than 100000 pecks");
  int repeats = 1;
  if (block.has('l')) {
    repeats = static_cast<int>(block.value('l'));
    if (repeats < 0 || repeats > 100000) throw NgcError(block.column('l'), "canned cycle repeats L must be 0..100000");
  }
  const double clear = retract_old_z_ ? std::fmax(cycle_start_z_, r) : r;
  const double rapid_delta = 0.010 * 25.4;  // LinuxCNC's peck clearance, 0.010 inch
  // G91: the hole steps from the last one, once per repeat.
  const double da = block.has(word_a) ? length(block.value(word_a)) : 0.0;
  const double db = block.has(word_b) ? length(block.value(word_b)) : 0.0;
  double a = absolute_ ? (block.has(word_a) ? da : pos_[ia]) : pos_[ia];
  double b = absolute_ ? (block.has(word_b) ? db : pos_[ib]) : pos_[ib];
  if (polar && absolute_) {  // G90: one hole at @ ^ (a missing one taken from here)
    const std::array<double, 2> xy = polar_xy(block, a, b);
    a = xy[0];
    b = xy[1];
  }
  // G87's top of the back bore: absolute in G90, from the bottom in G91.
  const double middle = absolute_ ? cycle_ijk_[ic] : bottom + cycle_ijk_[ic];
  const char* spindle_on = spindle_ == 3 ? "START_SPINDLE_CLOCKWISE(0)" : "START_SPINDLE_COUNTERCLOCKWISE(0)";
  // ORIENT_SPINDLE's last argument is the canon's direction: 2 clockwise, 3 counterclockwise.
  const char* orient = spindle_ == 3 ? "ORIENT_SPINDLE(0, 0.0000, 2)" : "ORIENT_SPINDLE(0, 0.0000, 3)";
  // Up to R first, before the cycle's exact-path mode, when the run of
  // cycles began below it (LinuxCNC judges by that height, not by where the tool is now).
  if (cycle_start_z_ < r) {
    Vec3 up = pos_;
    up[ic] = r;
    move_traverse(up);
  }
  // The first hole is reached at the clearance when the tool is below it
  // (a G98 line after G99 ones in the same run rises to the height the run
  // began at on the way, as rs274 does), else where it is.
  double old_z = std::fmax(pos_[ic], clear);
  const bool switch_mode = control_ != 610;  // already exact path (G61): no switch, no switch back
  if (switch_mode) emit("SET_MOTION_CONTROL_MODE(CANON_EXACT_PATH)");
  for (int k = 0; k < repeats; ++k) {
    if (!absolute_ && polar) {  // G91: each repeat adds @ and ^ to the last hole's radius and angle
      const std::array<double, 2> xy = polar_xy(block, a, b);
      a = xy[0];
      b = xy[1];
    } else if (!absolute_) {
      a += da;
      b += db;
    }
    move_traverse(at(a, b, old_z));
    if (old_z != r) move_traverse(at(a, b, r));
    if (motion == 810 || motion == 820) {
      move_feed(at(a, b, bottom), column);
      if (motion == 820) cycle_dwell();
    } else if (motion == 840) {  // tap: in at feed, reverse, dwell, out at feed, forward again
      emit("DISABLE_FEED_OVERRIDE()");
      emit("DISABLE_SPEED_OVERRIDE(0)");
      move_feed(at(a, b, bottom), column);
      emit("STOP_SPINDLE_TURNING(0)", kind_only(CanonMotion::Kind::spindle_stop));
      emit("START_SPINDLE_COUNTERCLOCKWISE(0)", valued(CanonMotion::Kind::spindle_on, -1.0));
      cycle_dwell();
      move_feed(at(a, b, clear), column);
      emit("STOP_SPINDLE_TURNING(0)", kind_only(CanonMotion::Kind::spindle_stop));
      emit("START_SPINDLE_CLOCKWISE(0)", valued(CanonMotion::Kind::spindle_on, 1.0));
      emit("ENABLE_FEED_OVERRIDE()");
      emit("ENABLE_SPEED_OVERRIDE(0)");
    } else if (motion == 850) {  // bore: in and out to R at feed, then up to the clearance
      move_feed(at(a, b, bottom), column);
      move_feed(at(a, b, r), column);
      move_traverse(at(a, b, clear));
    } else if (motion == 860) {  // bore: in at feed, dwell, spindle stopped out at rapid, restarted
      move_feed(at(a, b, bottom), column);
      cycle_dwell();
      emit("STOP_SPINDLE_TURNING(0)", kind_only(CanonMotion::Kind::spindle_stop));
      move_traverse(at(a, b, clear));
      emit(spindle_on, valued(CanonMotion::Kind::spindle_on, spindle_ == 3 ? 1.0 : -1.0));
    } else if (motion == 870) {
      // Back bore: the spindle stopped and oriented, through the hole at
      // the offset I J K, back over the hole's axis at the bottom, spindle
      // on, up at feed to the top of the bore and down again, stopped and
      // oriented, out through the hole at the offset, back over the hole.
      const double oa = a + cycle_ijk_[ia], ob = b + cycle_ijk_[ib];
      move_traverse(at(oa, ob, r));
      emit("STOP_SPINDLE_TURNING(0)", kind_only(CanonMotion::Kind::spindle_stop));
      emit(orient);
      move_traverse(at(oa, ob, bottom));
      move_traverse(at(a, b, bottom));
      emit(spindle_on, valued(CanonMotion::Kind::spindle_on, spindle_ == 3 ? 1.0 : -1.0));
      move_feed(at(a, b, middle), column);
      move_feed(at(a, b, bottom), column);
      emit("STOP_SPINDLE_TURNING(0)", kind_only(CanonMotion::Kind::spindle_stop));
      emit(orient);
      move_traverse(at(oa, ob, bottom));
      move_traverse(at(oa, ob, clear));
      move_traverse(at(a, b, clear));
      emit(spindle_on, valued(CanonMotion::Kind::spindle_on, spindle_ == 3 ? 1.0 : -1.0));
    } else if (motion == 880) {
      // Bore, dwell, spindle stopped, a program stop: the operator takes
      // the tool out by hand, and the program goes on from the clearance.
      move_feed(at(a, b, bottom), column);
      cycle_dwell();
      emit("STOP_SPINDLE_TURNING(0)", kind_only(CanonMotion::Kind::spindle_stop));
      emit("PROGRAM_STOP()", kind_only(CanonMotion::Kind::pause));
      emit(spindle_on, valued(CanonMotion::Kind::spindle_on, spindle_ == 3 ? 1.0 : -1.0));
    } else if (motion == 890) {  // bore: in at feed, dwell, out at feed
      move_feed(at(a, b, bottom), column);
      cycle_dwell();
      move_feed(at(a, b, clear), column);
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
        move_feed(at(a, b, depth), column);
        if (motion == 830) move_traverse(at(a, b, r));
        move_traverse(at(a, b, depth + rapid_delta));
      }
      move_feed(at(a, b, bottom), column);
    }
    if (motion == 730 || motion == 810 || motion == 820 || motion == 830) move_traverse(at(a, b, clear));
    old_z = clear;
  }
  // After G88 the interpreter takes the tool to be at the clearance (the
  // operator retracted it); the machine's last point is still the bottom
  // (canon_pos_, where a tool change takes the position back from).
  if (motion == 880 && repeats > 0) pos_ = at(a, b, clear);
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
