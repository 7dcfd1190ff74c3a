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
  if (muted_probe_line_ != 0)
    throw NgcError(1, at + "line " + std::to_string(muted_probe_line_) +
                          " probes (G38.x) before it, and a skipped probe's result (#5061-#5070) is unknown; start at "
                          "or before that line");
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

}  // namespace tnv::gcode
