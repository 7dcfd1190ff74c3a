// Run from line N (docs/gcode.md "Run from line"): at the start line the
// muted machine refuses a start that cannot be safe, makes the modal state
// the full run has there again as calls, and moves the tool to where the
// full run is: Z up to the clearance, XY at rapid, down.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "tools/gcode/canon_state.hpp"
#include "tools/gcode/ngc_error.hpp"
#include "tools/gcode/ngc_parameters.hpp"

namespace tnv::gcode {

namespace {

std::string four_decimals(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  return buf;
}

}  // namespace

void CanonMachine::resume(const RunFromLine& from, int line) {
  line_ = line;
  const std::string at = "cannot run from line " + std::to_string(line) + ": ";
  if (comp_side_ != 0)
    throw NgcError(1, at + "cutter radius compensation (line " + std::to_string(comp_line_) +
                          ") is in force there and would need an entry move; start at that G41/G42 or after its G40");
  // A probe before the start: its result stays unknown (a read is refused
  // where it comes); where the tool is must not depend on it.
  if (const std::string why = unknown_position_reason(); !why.empty()) throw NgcError(1, at + why);
  muted_ = false;

  emit("COMMENT(\"interpreter: run from line " + std::to_string(line) + "\")");
  // The state no motion depends on the order of: units first (every number
  // after is printed in them), offsets, plane, tool length.
  emit(unit_mm_ == 1.0 ? "USE_LENGTH_UNITS(CANON_UNITS_MM)" : "USE_LENGTH_UNITS(CANON_UNITS_INCHES)");
  emit_g5x();
  emit_g92();
  emit("SET_XY_ROTATION(0.0000)");
  emit(plane_ == 170 ? "SELECT_PLANE(CANON_PLANE_XY)" : plane_ == 180 ? "SELECT_PLANE(CANON_PLANE_XZ)"
                                                                      : "SELECT_PLANE(CANON_PLANE_YZ)");
  emit("USE_TOOL_LENGTH_OFFSET(" + num(tool_offset_[0]) + " " + num(tool_offset_[1]) + " " + num(tool_offset_[2]) +
       ", 0.0000 0.0000 0.0000, 0.0000 0.0000 0.0000)");
  if (!log_file_.empty()) emit("LOGAPPEND(\"" + log_file_ + "\")");  // appended: the log of the lines before is kept

  // 1. Z alone up to the clearance (never down: the machine may stand
  // higher), where the machine is.
  // Where the full run's tool is: the programmed point, or after G40 (no
  // move since) beside it, where the last compensated move left it.
  const Vec3 start = tool_after_g40_machine_ ? machine_to_program(*tool_after_g40_machine_) : pos_;
  const Vec3 here = machine_to_program(from.machine_position_mm);
  Vec3 clearance_machine = from.machine_position_mm;
  clearance_machine[2] = from.clearance_z_mm;
  const double travel_z = std::max({machine_to_program(clearance_machine)[2], here[2], start[2]});
  emit("STRAIGHT_TRAVERSE(" + xyz({here[0], here[1], travel_z}) + ")",
       move_to(CanonMotion::Kind::traverse, {here[0], here[1], travel_z}));

  // 2. At the clearance: the tool the line needs (a manual change: the
  // program pauses until the operator confirms), then the next one selected.
  if (tool_in_spindle_ != from.tool_in_spindle) {
    emit("SELECT_TOOL(" + std::to_string(tool_in_spindle_) + ")");
    emit("START_CHANGE()");
    emit("STOP_SPINDLE_TURNING(0)", kind_only(CanonMotion::Kind::spindle_stop));
    emit("CHANGE_TOOL(" + std::to_string(tool_in_spindle_) + ")", valued(CanonMotion::Kind::tool_change, tool_in_spindle_));
  }
  if (selected_tool_ != tool_in_spindle_) emit("SELECT_TOOL(" + std::to_string(selected_tool_) + ")");

  // 3. Spindle and coolant as the full run has them, the spindle at speed
  // before anything moves on.
  emit("SET_SPINDLE_SPEED(0, " + four_decimals(speed_) + ")", valued(CanonMotion::Kind::spindle_speed, speed_));
  if (spindle_ == 3 || spindle_ == 4) {
    emit(spindle_ == 3 ? "START_SPINDLE_CLOCKWISE(0)" : "START_SPINDLE_COUNTERCLOCKWISE(0)",
         valued(CanonMotion::Kind::spindle_on, spindle_ == 3 ? 1.0 : -1.0));
    emit("WAIT_SPINDLE_AT_SPEED(0)");
  } else {
    emit("STOP_SPINDLE_TURNING(0)", kind_only(CanonMotion::Kind::spindle_stop));
  }
  emit(mist_ ? "MIST_ON()" : "MIST_OFF()", kind_only(mist_ ? CanonMotion::Kind::coolant_on : CanonMotion::Kind::other));
  emit(flood_ ? "FLOOD_ON()" : "FLOOD_OFF()", kind_only(flood_ ? CanonMotion::Kind::coolant_on : CanonMotion::Kind::other));
  emit_control_mode();
  emit("SET_FEED_MODE(0, 0)");
  emit("SET_FEED_RATE(" + four_decimals(feed_) + ")", valued(CanonMotion::Kind::feed_rate, feed_ * unit_mm_));

  // 4. XY at the clearance, then down: at rapid to approach_mm above the
  // start, the rest at the feed rate in force. With none in force (no F
  // yet: every move before was a rapid; or a G94 since) all at rapid.
  emit("STRAIGHT_TRAVERSE(" + xyz({start[0], start[1], travel_z}) + ")",
       move_to(CanonMotion::Kind::traverse, {start[0], start[1], travel_z}));
  if (start[2] < travel_z) {
    const double above = start[2] + from.approach_mm;
    if (feed_ > 0.0 && from.approach_mm > 0.0) {
      if (above < travel_z)
        emit("STRAIGHT_TRAVERSE(" + xyz({start[0], start[1], above}) + ")",
             move_to(CanonMotion::Kind::traverse, {start[0], start[1], above}));
      emit("STRAIGHT_FEED(" + xyz(start) + ")", move_to(CanonMotion::Kind::feed, start));
    } else {
      emit("STRAIGHT_TRAVERSE(" + xyz(start) + ")", move_to(CanonMotion::Kind::traverse, start));
    }
  }
}

// Run from line past a probe (docs/gcode.md "Run from line"): the probe
// (G38.x) before the start line is skipped, so where it tripped is unknown.
// Its result (#5061-#5070) and the axes it moved stay unknown until the
// program gives them again: an axis by an absolute move (G90, G53, G28/G30),
// a result by an assignment or a probe that runs. Reading an unknown value
// is refused naming the line that reads it and the probe's line; so is
// storing an unknown position (G10 L10/L11/L20, G92, G28.1/G30.1) and a
// start where an axis is still unknown. LinuxCNC reads on with whatever the
// last real probe left in #5061-#5070: a program that touches off from the
// probe would run from a stale offset.

// A skipped probe's names (unity builds join files: names of their own).
namespace skipped_probe {

constexpr char kAxisLetters[3] = {'x', 'y', 'z'};
constexpr const char* kAxisNames[3] = {"X", "Y", "Z"};
constexpr const char* kPositionNames[3] = {"_x", "_y", "_z"};

}  // namespace skipped_probe

void CanonMachine::skip_probe(const Vec3& from, const Vec3& to) {
  const std::string probe_line = std::to_string(line_);
  const std::string start = setup_.from_line ? std::to_string(setup_.from_line->line) : "a later line";
  const std::string start_here = "; start at or before line " + probe_line;
  for (int n = ngc_number::kProbeResult; n <= ngc_number::kProbeTripped; ++n)
    params_.set_unknown(n, "is the result of the probe (G38.x) at line " + probe_line + ", which the run from line " +
                               start + " skips" + start_here);
  for (std::size_t a = 0; a < 3; ++a) {
    if (to[a] == from[a]) continue;
    unknown_axis_line_[a] = line_;
    const std::string why = "is the " + std::string(skipped_probe::kAxisNames[a]) +
                            " position where the probe (G38.x) at line " + probe_line +
                            " tripped, which the run from line " + start + " skips" + start_here;
    params_.set_unknown(ngc_number::kPositionFirst + static_cast<int>(a), why);
    params_.set_unknown(skipped_probe::kPositionNames[a], why);
  }
}

void CanonMachine::unknown_axis_known(std::size_t axis) {
  if (unknown_axis_line_[axis] == 0) return;
  unknown_axis_line_[axis] = 0;
  params_.known(ngc_number::kPositionFirst + static_cast<int>(axis));
  params_.known(skipped_probe::kPositionNames[axis]);
}

void CanonMachine::refuse_unknown_position(const NgcBlock& block, int non_modal, int g10_l, int column) const {
  if (unknown_axis_line_ == std::array<int, 3>{}) return;
  const std::string start = setup_.from_line ? std::to_string(setup_.from_line->line) : "a later line";
  const auto refuse = [&](std::size_t a, int at, const std::string& what) {
    const std::string probe_line = std::to_string(unknown_axis_line_[a]);
    throw NgcError(at, "cannot run from line " + start + ": " + what + " from the " + skipped_probe::kAxisNames[a] +
                           " position where the probe (G38.x) at line " + probe_line +
                           " tripped, which the run skips; start at or before line " + probe_line);
  };
  const bool per_axis = (non_modal == 100 && (g10_l == 10 || g10_l == 11 || g10_l == 20)) || non_modal == 920;
  if (per_axis) {
    const std::string what =
        non_modal == 920 ? "G92 sets an offset" : "G10 L" + std::to_string(g10_l) + " sets an offset";
    for (std::size_t a = 0; a < 3; ++a)
      if (unknown_axis_line_[a] != 0 && block.has(skipped_probe::kAxisLetters[a]))
        refuse(a, block.column(skipped_probe::kAxisLetters[a]), what);
  }
  if (non_modal == 281 || non_modal == 301) {
    for (std::size_t a = 0; a < 3; ++a)
      if (unknown_axis_line_[a] != 0)
        refuse(a, column, non_modal == 281 ? "G28.1 stores a home" : "G30.1 stores a home");
  }
}

void CanonMachine::learn_position(const NgcBlock& block, int motion, int non_modal, bool moved) {
  if (unknown_axis_line_ == std::array<int, 3>{}) return;
  if (comp_side_ != 0) return;  // a compensated point depends on the path to it
  // G28/G30 end at the home of the axes named (of all without words).
  if (non_modal == 280 || non_modal == 300) {
    const bool words = block.has('x') || block.has('y') || block.has('z');
    for (std::size_t a = 0; a < 3; ++a)
      if (!words || block.has(skipped_probe::kAxisLetters[a])) unknown_axis_known(a);
    return;
  }
  if (!moved || block.polar_radius || block.polar_angle) return;
  if (non_modal != 530 && !absolute_) return;  // incremental: from the unknown point
  const bool straight_or_arc = motion == 0 || motion == 10 || motion == 20 || motion == 30;
  if (straight_or_arc) {
    for (std::size_t a = 0; a < 3; ++a)
      if (block.has(skipped_probe::kAxisLetters[a])) unknown_axis_known(a);
    return;
  }
  // A cycle: the plane's axes go where given; along the cycle's axis G99 ends at R.
  if (is_cycle(motion)) {
    const std::size_t along = plane_ == 170 ? 2 : plane_ == 180 ? 1 : 0;
    for (std::size_t a = 0; a < 3; ++a)
      if (a != along && block.has(skipped_probe::kAxisLetters[a])) unknown_axis_known(a);
    if (!retract_old_z_) unknown_axis_known(along);
  }
}

std::string CanonMachine::unknown_position_reason() const {
  for (std::size_t a = 0; a < 3; ++a) {
    if (unknown_axis_line_[a] == 0) continue;
    const std::string probe_line = std::to_string(unknown_axis_line_[a]);
    return "the " + std::string(skipped_probe::kAxisNames[a]) +
           " position there comes from where the probe (G38.x) at line " + probe_line +
           " tripped, which the run skips; start at or before line " + probe_line +
           ", or at a line after one that gives " + skipped_probe::kAxisNames[a] + " absolutely (G90)";
  }
  return {};
}

}  // namespace tnv::gcode
