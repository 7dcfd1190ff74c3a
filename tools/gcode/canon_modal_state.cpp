// M70 (save the modal state), M71 (forget it), M72 (restore it) and M73
// (save it for restoring when the subroutine returns), as LinuxCNC does
// them: one saved state per call level; a restore runs the codes of the
// modes that differ as lines the way rs274 does: the units on a line of
// their own, then F S G17-G19 G43/G49 G54.. G61/G64 G90/G91 G90.1/G91.1
// G98/G99 M3-M5 and the coolant (M9, or M7 and M8), the coolant on the
// next line after a spindle code and M8 on the next after M7. The motion
// mode, the tool and the offsets' values are not part of it.
#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "tools/gcode/canon_state.hpp"
#include "tools/gcode/ngc_error.hpp"

namespace tnv::gcode {

namespace {

bool is_modal_state_code(int m) { return m >= 70 && m <= 73; }

}  // namespace

CanonMachine::SavedModes CanonMachine::current_modes() const {
  SavedModes s;
  s.unit_mm = unit_mm_;
  s.absolute = absolute_;
  s.arc_absolute = arc_absolute_;
  s.plane = plane_;
  s.feed = feed_;
  s.speed = speed_;
  s.spindle = spindle_;
  s.mist = mist_;
  s.flood = flood_;
  s.tool_length = tool_length_;
  s.origin = origin_;
  s.control = control_;
  s.control_p = control_p_;
  s.control_q = control_q_;
  s.retract_old_z = retract_old_z_;
  s.inverse_time = inverse_time_;
  return s;
}

bool CanonMachine::modal_state_code(const NgcBlock& block) {
  const auto m = std::find_if(block.m.begin(), block.m.end(), [](const NgcCode& c) { return is_modal_state_code(c.code); });
  if (m == block.m.end()) return false;
  // LinuxCNC runs a restore as lines of its own and drops the rest of the
  // M72 line's motion; an M70..M73 line here holds nothing else.
  const bool other_words = std::any_of(block.words.begin(), block.words.end(), [](const auto& w) { return w.has_value(); });
  if (block.m.size() > 1 || !block.g.empty() || other_words || block.polar_radius || block.polar_angle ||
      !block.assignments.empty())
    throw NgcError(m->column, "M" + std::to_string(m->code) + " must be on a line of its own (only comments beside it)");
  comp_refuse(comp_side_ != 0 && m->code != 71, m->column, "save or restore the modal state (M70, M72, M73)");
  run_comments(block);
  std::optional<SavedModes>& slot = saved_modes_.back();
  if (m->code == 70 || m->code == 73) {
    slot = current_modes();
    slot->auto_restore = m->code == 73;
  } else if (m->code == 71) {
    slot.reset();
  } else {
    if (!slot) throw NgcError(m->column, "M72: no modal state saved at this call level (M70 or M73 first)");
    restore_modes(*slot, m->column);
  }
  return true;
}

void CanonMachine::restore_modes(const SavedModes& saved, int column) {
  auto code = [column](int c) { return NgcCode{c, column}; };
  auto set_word = [column](NgcBlock& b, char letter, double v) {
    b.words[static_cast<std::size_t>(letter - 'a')] = v;
    b.columns[static_cast<std::size_t>(letter - 'a')] = column;
  };
  std::vector<NgcBlock> blocks(2);  // the units, then the modes
  if (saved.unit_mm != unit_mm_) blocks[0].g.push_back(code(saved.unit_mm == 1.0 ? 210 : 200));
  NgcBlock& b = blocks[1];
  if (saved.inverse_time != inverse_time_) b.g.push_back(code(saved.inverse_time ? 930 : 940));
  if (saved.feed != feed_) set_word(b, 'f', saved.feed);
  if (saved.speed != speed_) set_word(b, 's', saved.speed);
  if (saved.plane != plane_) b.g.push_back(code(saved.plane));
  if (saved.tool_length != tool_length_) b.g.push_back(code(saved.tool_length));
  if (saved.origin != origin_) b.g.push_back(code(saved.origin <= 6 ? 540 + 10 * (saved.origin - 1) : 590 + (saved.origin - 6)));
  if (saved.control != control_ ||
      (saved.control == 640 && (saved.control_p != control_p_ || saved.control_q != control_q_))) {
    b.g.push_back(code(saved.control));
    if (saved.control == 640) {
      set_word(b, 'p', saved.control_p);
      set_word(b, 'q', saved.control_q);
    }
  }
  if (saved.absolute != absolute_) b.g.push_back(code(saved.absolute ? 900 : 910));
  if (saved.arc_absolute != arc_absolute_) b.g.push_back(code(saved.arc_absolute ? 901 : 911));
  if (saved.retract_old_z != retract_old_z_) b.g.push_back(code(saved.retract_old_z ? 980 : 990));
  // The coolant codes share the line unless a spindle code ends it; M7 and
  // M8 are one modal group, so M8 after M7 starts another line.
  if (saved.spindle != spindle_) {
    b.m.push_back(code(saved.spindle));
    blocks.emplace_back();
  }
  if (!saved.mist && !saved.flood && (mist_ || flood_)) blocks.back().m.push_back(code(9));
  if (saved.mist && !mist_) blocks.back().m.push_back(code(7));
  if (saved.flood && !flood_) {
    if (!blocks.back().m.empty() && blocks.back().m.back().code == 7) blocks.emplace_back();
    blocks.back().m.push_back(code(8));
  }
  const int line = line_;
  for (const NgcBlock& restore : blocks)
    if (!restore.g.empty() || !restore.m.empty() || restore.has('f') || restore.has('s')) execute(restore, line);
}

void CanonMachine::set_call_depth(std::size_t depth, int line) {
  while (saved_modes_.size() > depth + 1) {
    const std::optional<SavedModes> leaving = saved_modes_.back();
    saved_modes_.pop_back();
    if (leaving && leaving->auto_restore && saved_modes_.size() == depth + 1) {
      line_ = line;
      restore_modes(*leaving, 1);
    }
  }
  saved_modes_.resize(depth + 1);
}

}  // namespace tnv::gcode
