// LinuxCNC's predefined read-only parameters, answered from the
// interpreter's state as LinuxCNC's interpreter answers them (its G-code
// reference, "Predefined Named Parameters" and "Numbered Parameters"; each
// value below checked against the standalone rs274 with (DEBUG,...) lines,
// tests/tools/gcode/canon_predefined_test.cpp). Positions and feeds are in
// the program's units, as LinuxCNC gives them.
//
// Left undefined (reading one is "not defined", as for any unknown name):
// the pockets (_current_pocket, _selected_pocket: LinuxCNC's tool-changer
// bookkeeping, which this machine's manual change does not have), the
// LinuxCNC version (_vmajor, _vminor) and _task (whether LinuxCNC's task
// runs the program: a question about LinuxCNC, not about the program).
#include <string_view>
#include <utility>

#include "tools/gcode/canon_state.hpp"

namespace tnv::gcode {

namespace {

constexpr double flag(bool b) { return b ? 1.0 : 0.0; }

// G54..G59.3 as LinuxCNC numbers them in #<_coord_system>.
constexpr double kCoordSystem[] = {540, 550, 560, 570, 580, 590, 591, 592, 593};

}  // namespace

std::optional<double> CanonMachine::predefined(const std::string& name) const {
  const auto position = [&](std::size_t axis) { return pos_[axis] / unit_mm_; };
  // Axes this machine has not (A B C U V W) read 0, as on LinuxCNC without them.
  static constexpr std::string_view kZeroAxes[] = {"_a", "_b", "_c", "_u", "_v", "_w"};
  for (std::string_view a : kZeroAxes)
    if (name == a) return 0.0;
  const std::pair<std::string_view, double> values[] = {
      {"_x", position(0)},
      {"_y", position(1)},
      {"_z", position(2)},
      {"_line", source_line_},
      {"_motion_mode", motion_},
      {"_plane", plane_},
      {"_ccomp", comp_side_ == 0 ? 400.0 : comp_side_ == 1 ? 410.0 : 420.0},
      {"_metric", flag(unit_mm_ == 1.0)},
      {"_imperial", flag(unit_mm_ != 1.0)},
      {"_absolute", flag(absolute_)},
      {"_incremental", flag(!absolute_)},
      {"_inverse_time", flag(inverse_time_)},
      {"_units_per_minute", flag(!inverse_time_)},
      {"_units_per_rev", 0.0},
      {"_coord_system", kCoordSystem[origin_ - 1]},
      {"_tool_offset", flag(tool_length_ != 490)},
      {"_retract_old_z", flag(retract_old_z_)},
      {"_spindle_rpm_mode", 1.0},  // G97: G96 is refused here
      {"_spindle_css_mode", 0.0},
      {"_ijk_absolute_mode", flag(arc_absolute_)},
      {"_lathe_diameter_mode", 0.0},  // G8: G7 is refused here
      {"_lathe_radius_mode", 1.0},
      {"_spindle_on", flag(spindle_ != 5)},
      {"_spindle_cw", flag(spindle_ == 3)},
      {"_mist", flag(mist_)},
      {"_flood", flag(flood_)},
      // M48-M53 are refused here: the overrides and feed hold stay enabled.
      {"_speed_override", 1.0},
      {"_feed_override", 1.0},
      {"_adaptive_feed", 0.0},
      {"_feed_hold", 1.0},
      {"_feed", feed_},
      {"_rpm", speed_},
      {"_current_tool", tool_in_spindle_},
      {"_selected_tool", selected_tool_},
      {"_call_level", static_cast<double>(saved_modes_.size() - 1)},
      {"_remap_level", 0.0},
  };
  for (const auto& [key, value] : values)
    if (name == key) return value;
  return std::nullopt;
}

double CanonMachine::read_only_number(int number) const {
  if (number >= 5420) {  // #5420-#5428: X Y Z A B C U V W, program coordinates and units
    const int axis = number - 5420;
    return axis < 3 ? pos_[static_cast<std::size_t>(axis)] / unit_mm_ : 0.0;
  }
  if (number == 5400) return tool_in_spindle_;
  // #5401-#5413: the tool table's entry for the tool in the spindle, as the
  // table holds it (this machine's table is in millimetres).
  const ToolEntry* tool = tools_.find(tool_in_spindle_);
  if (tool == nullptr) return 0.0;
  if (number <= 5409) return tool->offset[number - 5401];
  if (number == 5410) return tool->diameter;
  if (number == 5411) return tool->front_angle;
  if (number == 5412) return tool->back_angle;
  return tool->orientation;
}

}  // namespace tnv::gcode
