#pragma once
// RS274/NGC parameters as LinuxCNC keeps them: numbered #1..#5601 (0 until
// set), named locals #<name> (one scope per subroutine call) and globals
// #<_name>; reading a named parameter never set is an error. The persistent
// set (work offsets, G28/G30 homes, G92) is read from and written to a
// LinuxCNC-format .var file ("NUMBER VALUE" lines).
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace tnv::gcode {

class NgcParameters {
 public:
  static constexpr int kCount = 5602;  // LinuxCNC's RS274NGC_MAX_PARAMETERS

  NgcParameters();
  // Numbered: throws NgcError(column) outside 1..5601 (#0 reads as 0 and is read-only).
  double get(int number, int column) const;
  void set(int number, double value, int column);
  // Named: `name` lower-case without the brackets; a leading '_' is global.
  double get(const std::string& name, int column) const;
  bool exists(const std::string& name) const;
  void set(const std::string& name, double value);

  void push_scope();  // a subroutine call
  void pop_scope();   // its return

  // A .var file's text; false with `error` ("line N: why") and nothing changed.
  bool load_var_text(const std::string& text, std::string& error);

 private:
  std::array<double, kCount> numbered_{};
  std::map<std::string, double> globals_;
  std::vector<std::map<std::string, double>> locals_;
};

}  // namespace tnv::gcode
