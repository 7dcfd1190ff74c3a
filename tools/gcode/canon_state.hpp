#pragma once
// The interpreter's machine model: modal state, offsets, position, and
// the canonical calls a block makes, in LinuxCNC's order of execution
// within a line (comments, feed mode, F, S, T, M6, M3-M5, M7-M9, G4,
// plane, units, G40, G43/G49, G54.., G61/G64, G90/G91, G10/G28/G30/G92,
// motion, M0/M1/M2/M30). Lengths are kept in millimetres and printed in
// the program's units, as rs274 prints them.
#include <array>
#include <string>
#include <vector>

#include "tools/gcode/canon_interpreter.hpp"
#include "tools/gcode/ngc_block.hpp"

namespace tnv::gcode {

class CanonMachine {
 public:
  CanonMachine(const CanonSetup& setup, std::vector<CanonCall>& calls);
  void start();                                  // the start-up calls
  void execute(const NgcBlock& block, int line);  // throws NgcError
  void comments(const NgcBlock& block, int line);
  void end_of_file(int line);                    // throws unless ended
  // A '%' line: the first starts the program, the second ends it (FINISH()).
  void percent(int line, int column);
  bool ended() const { return ended_; }
  NgcParameters& parameters() { return params_; }

 private:
  using Vec3 = std::array<double, 3>;  // X Y Z, millimetres
  void emit(const std::string& text);
  std::string num(double mm) const;  // a length in program units, %.4f
  std::string xyz(const Vec3& program_mm) const;
  void apply_assignments(const NgcBlock& block);
  void run_comments(const NgcBlock& block);
  std::string substitute(const std::string& text) const;
  void set_origin(int index);
  void emit_g5x();
  void emit_g92();
  void move_traverse(const Vec3& to);
  void move_feed(const Vec3& to, int column);
  void arc(const NgcBlock& block, bool clockwise, const Vec3& end, int column);
  Vec3 target(const NgcBlock& block, bool machine) const;
  Vec3 machine_to_program(const Vec3& machine) const;
  Vec3 program_to_machine(const Vec3& program) const;
  double length(double value) const { return value * unit_mm_; }
  void program_end(bool m30);
  void emit_control_mode();
  // G73, G81, G82, G83 in the XY plane (canon_cycles.cpp).
  static bool is_cycle(int motion) { return motion == 730 || (motion >= 810 && motion <= 890); }
  void canned_cycle(const NgcBlock& block, int motion, int column);
  void check_words(const NgcBlock& block, int motion, int non_modal) const;

  const CanonSetup& setup_;
  std::vector<CanonCall>& calls_;
  NgcParameters params_;
  int line_ = 0;
  bool ended_ = false;
  bool percent_started_ = false;
  bool started_ = false;  // a line with words or comments ran
  double unit_mm_ = 1.0;   // 25.4 in G20
  bool absolute_ = true;   // G90
  bool arc_absolute_ = false;  // G90.1
  int plane_ = 170;        // 170 180 190
  int motion_ = 800;       // G-code x 10; 800: none
  double feed_ = 0.0;      // program units per minute, as given
  double speed_ = 0.0;
  int spindle_ = 5;        // 3, 4, 5
  bool mist_ = false, flood_ = false;
  int selected_tool_ = 0, tool_in_spindle_ = 0;
  Vec3 tool_offset_{};     // mm
  int origin_ = 1;         // 1..9 (G54..G59.3)
  Vec3 g5x_{};             // mm
  Vec3 g92_{};             // mm
  Vec3 pos_{};             // program coordinates, mm
  int control_ = 640;      // G61 / G61.1 / G64 (x 10), with G64's P and Q
  double control_p_ = 0.0, control_q_ = 0.0;
  bool retract_old_z_ = false;  // G98; rs274 starts in G99 (retract to R)
  double cycle_start_z_ = 0.0;  // Z where the run of canned cycles began (mm)
  double cycle_r_ = 0.0, cycle_z_ = 0.0, cycle_q_ = 0.0, cycle_p_ = 0.0;  // sticky words, mm (P seconds)
  bool cycle_has_r_ = false, cycle_has_z_ = false;
  Vec3 canon_pos_{};       // the last point moved to, as the machine knows it (program coordinates)
};

}  // namespace tnv::gcode
