// G10 L1, L10 and L11: a program edits the tool table it runs with, as
// LinuxCNC's convert_setup_tool does (docs/gcode.md "Tool table edits").
// The edit changes the interpreter's copy of the table from that line on
// (G43, G43 H, G41/G42 D, #5401-#5413); the .tbl file is not written.
#include <cmath>
#include <cstddef>
#include <string>

#include "tools/gcode/canon_state.hpp"
#include "tools/gcode/ngc_error.hpp"
#include "tools/gcode/ngc_parameters.hpp"

namespace tnv::gcode {

namespace {

constexpr int kFixtureSystem = 9;  // G10 L11 measures in G59.3, as LinuxCNC

// LinuxCNC's rounding of G10's P and Q (is_near_int): half up, toward zero below.
int near_int(double v) { return static_cast<int>(v + 0.5); }

std::string four(double v) { return fixed(v, 4); }

}  // namespace

void CanonMachine::setup_tool(const NgcBlock& block, int l, int column) {
  const std::string g10 = "G10 L" + std::to_string(l);
  // P: LinuxCNC rounds it, refuses one more than 0.0001 above a whole
  // number and any below 1, then looks the tool up in the table.
  const double p = block.has('p') ? block.value('p') : -1.0;
  const int p_column = block.has('p') ? block.column('p') : column;
  if (p > 1e6) throw NgcError(p_column, "requested tool P" + four(p) + " not found in the tool table");
  const int p_int = p >= 0.0 ? near_int(p) : static_cast<int>(p - 0.5);
  if (p + 0.0001 - p_int > 0.0002) throw NgcError(p_column, g10 + " P must be a whole tool number");
  if (p_int < 1) throw NgcError(p_column, g10 + " needs P, a tool number of 1 or more");
  const ToolEntry* found = tools_.find(p_int);
  if (!found) throw NgcError(p_column, "requested tool " + std::to_string(p_int) + " not found in the tool table");
  bool any = false;
  for (char c : {'x', 'y', 'z', 'r', 'q', 'i', 'j'}) any = any || block.has(c);
  if (!any) throw NgcError(column, g10 + " with no X, Y, Z, R, I, J or Q changes nothing");

  ToolEntry entry = *found;
  static constexpr char kAxes[3] = {'x', 'y', 'z'};
  if (l == 1) {
    for (std::size_t a = 0; a < 3; ++a)
      if (block.has(kAxes[a])) entry.offset[a] = length(block.value(kAxes[a]));
  } else {
    // L10 (the work offset in force) and L11 (G59.3): the offset that makes
    // the controlled point read the given value with this tool's G43 in
    // force. Measured from where the tool point is without its length
    // offset; L10 takes G92 off (when it is enabled, as #5210 says),
    // L11 does not.
    const int system = l == 11 ? kFixtureSystem : origin_;
    const bool g92 = l == 10 && params_.get(ngc_number::kG92Enabled, 1) != 0.0;
    const Vec3 machine = program_to_machine(pos_);
    for (std::size_t a = 0; a < 3; ++a) {
      if (!block.has(kAxes[a])) continue;
      const int axis = static_cast<int>(a);
      const double here = machine[a] - params_.get(ngc_number::kG5xBase + 20 * (system - 1) + axis, 1) -
                          (g92 ? params_.get(ngc_number::kG92Base + axis, 1) : 0.0);
      entry.offset[a] = here - length(block.value(kAxes[a]));
    }
  }
  if (block.has('r')) entry.diameter = 2.0 * length(block.value('r'));
  if (block.has('i')) entry.front_angle = block.value('i');
  if (block.has('j')) entry.back_angle = block.value('j');
  // Q -1 is LinuxCNC's "no Q" and changes nothing.
  if (block.has('q') && block.value('q') != -1.0) {
    const double q = block.value('q');
    if (std::fabs(q) > 1e6 || std::fabs(near_int(q) - q) >= 0.0001)
      throw NgcError(block.column('q'), g10 + " Q (the tool's orientation) must be a whole number");
    if (near_int(q) > 9) throw NgcError(block.column('q'), g10 + " Q: tool orientation " + std::to_string(near_int(q)) + " (0..9)");
    entry.orientation = near_int(q);
  }
  tools_.replace(entry);

  // rs274's call: the pocket (the tool's place in the table), the tool, the
  // nine offsets in the machine's units (millimetres here, inches in the
  // standalone rs274), the front and back angle, the orientation. The
  // diameter is not printed. Again as the spindle's entry (pocket 0) when
  // the tool is in the spindle.
  std::string values = std::to_string(entry.tool) + ", ";
  for (int a = 0; a < 9; ++a) values.append(four(entry.offset[a])).append(a < 8 ? " " : ", ");
  values.append(four(entry.front_angle)).append(", ").append(four(entry.back_angle)).append(", ");
  values.append(std::to_string(entry.orientation)).append(")");
  emit("SET_TOOL_TABLE_ENTRY(" + std::to_string(entry.index) + ", " + values);
  if (tool_in_spindle_ != 0 && tool_in_spindle_ == entry.tool) emit("SET_TOOL_TABLE_ENTRY(0, " + values);
}

}  // namespace tnv::gcode
