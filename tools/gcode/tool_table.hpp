#pragma once
// A LinuxCNC-format tool table (.tbl): one tool a line, "T<n> P<pocket>
// [X.. Y.. Z.. A.. B.. C.. U.. V.. W..] [D<diameter>] [I.. J.. Q..] [;comment]".
// Lengths are in the machine's units (millimetres on this machine).
#include <map>
#include <optional>
#include <string>

namespace tnv::gcode {

struct ToolEntry {
  int tool = 0;
  int pocket = 0;
  double offset[9] = {};  // X Y Z A B C U V W
  double diameter = 0.0;
  double front_angle = 0.0, back_angle = 0.0;
  int orientation = 0;
  // The tool's place in the file (1 for its first tool line): LinuxCNC's
  // pocket index for a non-random tool changer, what SET_TOOL_TABLE_ENTRY
  // names (not the P column).
  int index = 0;
};

class ToolTable {
 public:
  // False with `error` ("line N: why") and the table unchanged.
  bool load_text(const std::string& text, std::string& error);
  const ToolEntry* find(int tool) const;
  // Replaces the entry of entry.tool, which must be in the table (G10 L1,
  // L10, L11 edit a program's copy of the table; the file is not written).
  void replace(const ToolEntry& entry);
  std::size_t size() const { return tools_.size(); }

 private:
  std::map<int, ToolEntry> tools_;
};

}  // namespace tnv::gcode
