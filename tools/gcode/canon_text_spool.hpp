#pragma once
// The calls' text held on disk, not in memory, until the run is known to
// end without an error (a refused program prints nothing: docs/gcode.md).
// `tnvctl gcode canon` writes each call here as the interpreter makes it
// and copies the file out only on success, so its memory does not grow
// with the program's calls. The file is anonymous (std::tmpfile: gone when
// closed or when the process ends, however it ends).
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>

#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::gcode {

class CanonTextSpool {
 public:
  CanonTextSpool();
  // Appends the call's text and a newline; a write error is kept for ok().
  void operator()(const CanonCall& call);
  // False with `error` if the file could not be made or written (a full disk).
  bool ok(std::string& error) const;
  // Copies everything written to `out`; false with `error` on a read or write error.
  bool copy_to(std::ostream& out, std::string& error);

 private:
  struct Close {
    void operator()(std::FILE* f) const noexcept { std::fclose(f); }
  };
  std::unique_ptr<std::FILE, Close> file_;
  int errno_ = 0;  // the first error, 0: none
};

}  // namespace tnv::gcode
