#pragma once
// The interpreter's machine model: modal state, offsets, position, and
// the canonical calls a block makes, in LinuxCNC's order of execution
// within a line (comments, feed mode, F, S, T, M6, M3-M5, M7-M9, G4,
// plane, units, G40, G43/G49, G54.., G61/G64, G90/G91, G10/G28/G30/G92,
// motion, M0/M1/M2/M30). Lengths are kept in millimetres and printed in
// the program's units, as rs274 prints them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tools/gcode/canon_interpreter.hpp"
#include "tools/gcode/ngc_block.hpp"

namespace tnv::gcode {

// v with `decimals` places as rs274 prints numbers (never "-0.0000").
std::string fixed(double v, int decimals);

class CanonMachine : private NgcMachineValues {
 public:
  CanonMachine(const CanonSetup& setup, const CanonSink& sink);
  CanonMachine(const CanonMachine&) = delete;  // its parameters point back at it
  CanonMachine& operator=(const CanonMachine&) = delete;
  void start();                                  // the start-up calls
  // The source line about to be read: #<_line> while its words are read.
  void begin_line(int line) { source_line_ = line; }
  // The file the next calls' line is in (CanonCall::file).
  void set_file(std::uint32_t file) { file_ = file; }
  void execute(const NgcBlock& block, int line);  // throws NgcError
  void comments(const NgcBlock& block, int line);
  void end_of_file(int line);                    // throws unless ended
  // CanonSetup::end_of_file_ends: the file ended without a program end;
  // moves compensation still holds back are made.
  void end_at_end_of_file(int line);
  // A '%' line: the first starts the program, the second ends it (FINISH()).
  void percent(int line, int column);
  bool ended() const { return ended_; }
  NgcParameters& parameters() { return params_; }
  // The subroutine call depth the next line runs at (0: the top level).
  // Leaving a level drops what M70/M73 saved there; an M73 state is
  // restored first, on the endsub/return line (canon_modal_state.cpp).
  void set_call_depth(std::size_t depth, int line);
  // Run from line (canon_run_from_line.cpp): a muted machine keeps its
  // state but makes no call; resume() refuses an unsafe start, makes the
  // modal state again and the approach to the start point, and unmutes.
  void mute() { muted_ = true; }
  bool muted() const { return muted_; }
  void resume(const RunFromLine& from, int line);  // throws NgcError

 private:
  using Vec3 = std::array<double, 3>;  // X Y Z, millimetres
  // LinuxCNC's predefined parameters (canon_predefined.cpp).
  std::optional<double> predefined(const std::string& name) const override;
  double read_only_number(int number) const override;
  // A probe skipped by a run from line (canon_run_from_line.cpp): its result
  // and the axes it moved are unknown until known again; what would store or
  // start from them is refused.
  void skip_probe(const Vec3& from, const Vec3& to);
  void refuse_unknown_position(const NgcBlock& block, int non_modal, int g10_l, int column) const;
  void learn_position(const NgcBlock& block, int motion, int non_modal, bool moved);
  void unknown_axis_known(std::size_t axis);
  std::string unknown_position_reason() const;  // empty when every axis is known
  void emit(const std::string& text, const CanonMotion& motion = {});
  // A move's structured form: its end (program coordinates) in machine coordinates.
  CanonMotion move_to(CanonMotion::Kind kind, const Vec3& program_mm) const;
  static CanonMotion valued(CanonMotion::Kind kind, double value) {
    CanonMotion m;
    m.kind = kind;
    m.value = value;
    return m;
  }
  static CanonMotion kind_only(CanonMotion::Kind kind) { return valued(kind, 0.0); }
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
  // G93: the feed rate of this move, length / (1 / F minutes), as
  // SET_FEED_RATE before it (LinuxCNC's inverse_time_rate_*; 0.1 at least).
  void inverse_time_rate(const NgcBlock& block, double length_mm);
  // G10 L1 / L10 / L11: a tool table entry from the block (canon_tool_setup.cpp).
  void setup_tool(const NgcBlock& block, int l, int column);
  void arc(const NgcBlock& block, bool clockwise, const Vec3& end, int column);
  // An arc's centre (plane coordinates, mm) and signed turns from a start
  // point, with LinuxCNC's checks of the I J K and R forms.
  struct ArcFit {
    double c1 = 0.0, c2 = 0.0;
    int turn = 1;  // > 0 counterclockwise, |turn| = P
  };
  ArcFit arc_fit(const NgcBlock& block, bool clockwise, double s1, double s2, double e1, double e2, int column) const;
  Vec3 target(const NgcBlock& block, bool machine) const;
  // LinuxCNC's polar words: @ (radius) and ^ (angle, degrees) about the XY
  // origin, absolute in G90, added to the radius and angle of (x0, y0) in G91.
  std::array<double, 2> polar_xy(const NgcBlock& block, double x0, double y0) const;
  // Where incremental and unspecified axes are measured from: the programmed
  // point once compensation has made its entry move, else the current point.
  const Vec3& base_point() const { return comp_side_ != 0 && !comp_first_ ? programmed_ : pos_; }
  Vec3 machine_to_program(const Vec3& machine) const;
  Vec3 program_to_machine(const Vec3& program) const;
  double length(double value) const { return value * unit_mm_; }
  void spline(const NgcBlock& block, const Vec3& to, int column);
  static bool is_probe(int motion) { return motion >= 382 && motion <= 385; }
  void probe(int motion, const Vec3& to, int column);
  void probe_on_machine(const CanonMotion& move, const Vec3& to, int column);  // CanonSetup::probe_input set
  void rigid_tap(const NgcBlock& block, const Vec3& to, int column);
  void program_end(bool m30);
  void emit_control_mode();
  // G73, G81-G89 in G17, G18 and G19 (canon_cycles.cpp).
  static bool is_cycle(int motion) { return motion == 730 || (motion >= 810 && motion <= 890); }
  void canned_cycle(const NgcBlock& block, int motion, int column);
  void cycle_dwell();  // DWELL(P) at the bottom of G82, G84, G86, G88, G89
  void check_words(const NgcBlock& block, int motion, int non_modal) const;

  // M70 save, M71 invalidate, M72 restore, M73 save for restore at return
  // (canon_modal_state.cpp): the modes LinuxCNC saves, per call level.
  struct SavedModes {
    double unit_mm = 1.0;
    bool absolute = true, arc_absolute = false;
    int plane = 170;
    double feed = 0.0, speed = 0.0;
    int spindle = 5;
    bool mist = false, flood = false;
    int tool_length = 490;
    int origin = 1;
    int control = 640;
    double control_p = 0.0, control_q = 0.0;
    bool retract_old_z = false;
    bool inverse_time = false;  // G93
    bool auto_restore = false;  // M73
  };
  bool modal_state_code(const NgcBlock& block);  // true: the line was M70..M73 and ran
  SavedModes current_modes() const;
  void restore_modes(const SavedModes& saved, int column);

  // Cutter radius compensation, G40/G41/G42/G41.1/G42.1 in the XY plane
  // (canon_comp.cpp), as LinuxCNC does it: moves wait in a queue until the
  // next move shows whether the corner between them is convex (an arc is
  // inserted) or concave (the waiting move's end is pulled back to the
  // intersection); non-motion calls made meanwhile wait with them.
  struct Queued {
    enum class Kind { text, traverse, feed, arc } kind = Kind::text;
    int line = 0;
    std::uint32_t file = 0;
    std::string text;          // Kind::text: the call as printed
    CanonMotion motion{};      // Kind::text: the call's structured form
    double dx = 0.0, dy = 0.0;  // lines: the programmed direction
    Vec3 end{};                // program coordinates, mm (arcs: end1, end2, end3)
    double c1 = 0.0, c2 = 0.0;  // arcs: centre, mm
    int turn = 0;
    double sweep = 0.0;        // arcs: radians swept as first queued (0: never moved)
  };
  bool comp_active() const { return comp_side_ != 0 && comp_radius_ > 0.0; }
  void comp_on(const NgcBlock& block, const NgcCode& g);
  void comp_off(int column);
  void comp_refuse(bool refused, int column, const std::string& what) const;
  void comp_straight(int motion, const Vec3& to, int column);
  void comp_arc(const NgcBlock& block, bool clockwise, const Vec3& end, int column);
  void comp_arc_first(const NgcBlock& block, bool clockwise, const Vec3& end, int column);
  void comp_line_first(int motion, const Vec3& to);
  void comp_line_next(int motion, const Vec3& to);
  void comp_flush_here();  // the queue ends where the tool is (M0/M1/M2/M30, G40)
  void enqueue_line(int motion, double dx, double dy, const Vec3& end);
  void enqueue_arc(double sweep, double e1, double e2, double c1, double c2, int turn, double e3);
  void move_endpoint_and_flush(double x, double y);
  void dequeue();
  void set_endpoint(double x, double y) {
    endpoint_ = {x, y};
    endpoint_valid_ = true;
  }
  void print_queued(const Queued& q);
  // A point's coordinates in the compensation plane (first, second) and
  // along its normal (third): X Y Z in G17, Z X Y in G18, as LinuxCNC orders them.
  double& first(Vec3& v) const { return v[comp_a1_]; }
  double& second(Vec3& v) const { return v[comp_a2_]; }
  double first(const Vec3& v) const { return v[comp_a1_]; }
  double second(const Vec3& v) const { return v[comp_a2_]; }
  double third(const Vec3& v) const { return v[comp_a3_]; }
  Vec3 point(double a, double b, double c) const {
    Vec3 v{};
    v[comp_a1_] = a;
    v[comp_a2_] = b;
    v[comp_a3_] = c;
    return v;
  }
  Vec3 lathe_origin(const Vec3& v) const;

  const CanonSetup& setup_;
  const CanonSink& sink_;
  NgcParameters params_;
  ToolTable tools_;  // the setup's table as G10 L1/L10/L11 change it
  int line_ = 0;            // the line the calls made now are tagged with
  int source_line_ = 0;      // the line being read and run (#<_line>)
  std::uint32_t file_ = 0;   // the file line_ is in (CanonCall::file)
  bool ended_ = false;
  bool percent_started_ = false;
  bool started_ = false;  // a line with words or comments ran
  double unit_mm_ = 1.0;   // 25.4 in G20
  bool absolute_ = true;   // G90
  bool arc_absolute_ = false;  // G90.1
  int plane_ = 170;        // 170 180 190
  int motion_ = 800;       // G-code x 10; 800: none
  double feed_ = 0.0;      // program units per minute, as given (G93: the last move's rate)
  bool inverse_time_ = false;  // G93: each G1/G2/G3 gives its own F, 1/minutes
  double speed_ = 0.0;
  int spindle_ = 5;        // 3, 4, 5
  bool mist_ = false, flood_ = false;
  int selected_tool_ = 0, tool_in_spindle_ = 0;
  Vec3 tool_offset_{};     // mm
  int tool_length_ = 490;  // G43 / G43.1 / G49 (x 10)
  int origin_ = 1;         // 1..9 (G54..G59.3)
  Vec3 g5x_{};             // mm
  Vec3 g92_{};             // mm
  Vec3 pos_{};             // program coordinates, mm
  int control_ = 640;      // G61 / G61.1 / G64 (x 10), with G64's P and Q
  double control_p_ = 0.0, control_q_ = 0.0;
  bool retract_old_z_ = false;  // G98; rs274 starts in G99 (retract to R)
  double cycle_start_z_ = 0.0;  // where the run of canned cycles began along the cycle's axis (mm)
  // Sticky words, mm (P seconds); cycle_z_ is the bottom along the cycle's axis (Z, Y or X).
  double cycle_r_ = 0.0, cycle_z_ = 0.0, cycle_q_ = 0.0, cycle_p_ = 0.0;
  std::array<double, 3> cycle_ijk_{};  // G87's I J K, mm
  double cycle_r_words_ = 0.0, cycle_z_words_ = 0.0, cycle_q_words_ = 0.0;  // the same, as written (program units)
  bool cycle_continues_ = false;  // this line's motion mode is the one before it
  Vec3 canon_pos_{};       // the last point moved to, as the machine knows it (program coordinates)
  int comp_side_ = 0;      // 0 off (G40), 1 left (G41), 2 right (G42)
  double comp_radius_ = 0.0;  // mm, >= 0
  int comp_orientation_ = 0;  // a lathe tool's orientation (1..8) in G18; 0 or 9: the centre is the tool's origin
  std::size_t comp_a1_ = 0, comp_a2_ = 1, comp_a3_ = 2;  // see first()
  bool comp_first_ = true;    // the next move is the entry move
  bool arc_not_allowed_ = false;  // the move after G40 must be straight
  Vec3 programmed_{};      // the programmed point while compensating (pos_ is the tool's)
  std::vector<Queued> queue_;
  std::array<double, 2> endpoint_{};  // where the first queued move starts
  bool endpoint_valid_ = false;
  int comp_column_ = 1;  // the word an error found while compensating is reported at
  bool muted_ = false;      // run from line: before the start line
  // Run from line past a probe (canon_run_from_line.cpp): per axis, the line
  // of the skipped probe its position came from (0: known).
  std::array<int, 3> unknown_axis_line_{};
  int comp_line_ = 0;      // the line compensation was turned on
  // After G40 and until the next move the tool stands beside the programmed
  // point (machine coordinates, so no offset change moves it).
  std::optional<Vec3> tool_after_g40_machine_;
  std::string log_file_;   // the file LOGOPEN/LOGAPPEND opened, until LOGCLOSE
  std::vector<std::optional<SavedModes>> saved_modes_ = std::vector<std::optional<SavedModes>>(1);  // per call level
};

}  // namespace tnv::gcode
