#pragma once
// RS274/NGC parameters as LinuxCNC keeps them: numbered #1..#5601 (0 until
// set), named locals #<name> (one scope per subroutine call) and globals
// #<_name>; reading a named parameter never set is an error. The persistent
// set (work offsets, G28/G30 homes, G92) is read from and written to a
// LinuxCNC-format .var file ("NUMBER VALUE" lines). LinuxCNC's predefined
// read-only parameters (#<_x>, #<_motion_mode>, ..., #5400-#5413 the tool,
// #5420-#5428 the position) are answered by the machine state
// (NgcMachineValues); a program that assigns one is refused.
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tnv::gcode {

// The numbered parameters the interpreter itself reads and writes
// (LinuxCNC's G-code reference, "Numbered Parameters"), named once here.
namespace ngc_number {
inline constexpr int kProbeResult = 5061;  // #5061-#5069: where the last probe tripped (X..W)
inline constexpr int kProbeTripped = 5070;  // 1 = it tripped
inline constexpr int kG28Home = 5161, kG30Home = 5181;
inline constexpr int kG92Enabled = 5210, kG92Base = 5211;
inline constexpr int kG5xSelected = 5220;
inline constexpr int kG5xBase = 5221;  // system n at 5221 + 20 (n - 1): X Y Z A B C U V W R
inline constexpr int kPositionFirst = 5420;  // #5420-#5428: the position in the program's frame
}  // namespace ngc_number

// The interpreter's state as LinuxCNC's predefined parameters show it.
class NgcMachineValues {
 public:
  virtual ~NgcMachineValues() = default;
  // `name` ("_x", lower case): its value, or none when it is not predefined.
  virtual std::optional<double> predefined(const std::string& name) const = 0;
  // A read-only number (NgcParameters::read_only(number)).
  virtual double read_only_number(int number) const = 0;
};

class NgcParameters {
 public:
  static constexpr int kCount = 5602;  // LinuxCNC's RS274NGC_MAX_PARAMETERS

  NgcParameters();
  // Where the predefined read-only values come from (none: they read as 0
  // and the names are undefined). The machine outlives this object's use.
  void set_machine(const NgcMachineValues* machine) { machine_ = machine; }
  // #5400-#5413 (the tool in the spindle) and #5420-#5428 (the position).
  static constexpr bool read_only(int number) {
    return (number >= 5400 && number <= 5413) || (number >= 5420 && number <= 5428);
  }
  // Numbered: throws NgcError(column) outside 1..5601 (#0 reads as 0 and is
  // read-only) and, for set, on a read-only number.
  double get(int number, int column) const;
  void set(int number, double value, int column);
  // Named: `name` lower-case without the brackets; a leading '_' is global.
  double get(const std::string& name, int column) const;
  bool exists(const std::string& name) const;
  // The interpreter's own writes (a subroutine's #<_value>).
  void set(const std::string& name, double value);
  // A program's assignment: throws NgcError(column) for a predefined name.
  void assign(const std::string& name, double value, int column);

  // Values a run from line cannot know (a skipped probe's result, a position
  // that came from it): reading `number` (or the predefined `name`) throws
  // NgcError(column, "#N " + why) until it is known again. set() of a
  // number makes it known; so does known().
  void set_unknown(int number, const std::string& why) { unknown_numbers_[number] = why; }
  void set_unknown(const std::string& name, const std::string& why) { unknown_names_[name] = why; }
  void known(int number) { unknown_numbers_.erase(number); }
  void known(const std::string& name) { unknown_names_.erase(name); }

  void push_scope();  // a subroutine call
  void pop_scope();   // its return

  // A .var file's text; false with `error` ("line N: why") and nothing changed.
  bool load_var_text(const std::string& text, std::string& error);

 private:
  std::array<double, kCount> numbered_{};
  std::map<std::string, double> globals_;
  std::vector<std::map<std::string, double>> locals_;
  const NgcMachineValues* machine_ = nullptr;
  std::map<int, std::string> unknown_numbers_;  // empty but after a run from line skipped a probe
  std::map<std::string, std::string> unknown_names_;
};

}  // namespace tnv::gcode
