#pragma once
// Subroutines in files of their own, as LinuxCNC finds them: a call of
// o<name> that the program does not define runs the definition in
// name.ngc, looked for in the subroutine path's directories in order (for
// `tnvctl gcode canon FILE`: FILE's own directory first, as the standalone
// rs274 finds them in its working directory; then each --subroutine-path).
// The file's lines from `o<name> sub` to `o<name> endsub` join the program
// behind its last line (a definition reached in order is skipped, so they
// never run but when called); what the file has around them is not read,
// as in LinuxCNC (a file often ends with M2). Names with characters other
// than a-z 0-9 _ - are never looked up (no path in a name).
#include <cstddef>
#include <string>
#include <vector>

#include "tools/gcode/ngc_program_lines.hpp"

namespace tnv::gcode {

struct SubroutineFiles {
  struct Origin {
    std::size_t file = 0;  // index into files
    int line = 0;          // 1-based, in that file
  };
  std::vector<std::string> files;  // the files read, in the order they were needed
  std::vector<Origin> origins;     // one per line appended behind the program
};

// The most files one program may pull in (each at most kMaxProgramBytes).
inline constexpr std::size_t kMaxSubroutineFiles = 100;

// Appends to `lines` (the program, `program_lines` long) the definitions
// of the named subroutines it calls and does not define, and those they
// call in turn. A name found in no directory is left for the call to
// refuse when it runs (a call in a branch never taken is no error, as in
// LinuxCNC). Throws NgcError (column 1) for a file that cannot be read or
// has no whole definition of its name; `error_line` is then the program's
// (or an earlier file's) line calling it, 1-based in `lines`.
SubroutineFiles append_subroutine_files(ProgramLines& lines, const std::vector<std::string>& dirs,
                                        std::size_t& error_line);

}  // namespace tnv::gcode
