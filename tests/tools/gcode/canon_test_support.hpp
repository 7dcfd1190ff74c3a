#pragma once
// What the LinuxCNC-dialect interpreter's unit tests share: a setup with a
// tool table, the calls a program makes between its start-up calls and its
// end's resets, and the error a refused program gets (which must come with
// no call at all).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::gcode::test {

inline CanonSetup setup_with_tools(const std::string& tool_table) {
  CanonSetup setup;
  std::string error;
  EXPECT_TRUE(setup.tools.load_text(tool_table, error)) << error;
  return setup;
}

// The calls after the six start-up calls and before M2's resets
// (SET_G5X_OFFSET(1, ...), SET_XY_ROTATION(0.0000), SET_FEED_MODE(0, 0)).
inline std::vector<std::string> calls_between_start_and_end(const std::string& text, const CanonSetup& setup) {
  const CanonResult r = interpret_canon(text, setup);
  EXPECT_FALSE(r.error.has_value()) << (r.error ? to_string(*r.error) : "");
  std::vector<std::string> out;
  for (std::size_t k = 6; k < r.calls.size(); ++k) {
    if (r.calls[k].text.rfind("SET_G5X_OFFSET(1,", 0) == 0 && k + 2 < r.calls.size() &&
        r.calls[k + 1].text == "SET_XY_ROTATION(0.0000)" && r.calls[k + 2].text == "SET_FEED_MODE(0, 0)")
      break;
    out.push_back(r.calls[k].text);
  }
  return out;
}

inline GcodeError refusal_of(const std::string& text, const CanonSetup& setup) {
  const CanonResult r = interpret_canon(text, setup);
  EXPECT_TRUE(r.error.has_value()) << "accepted: " << text;
  EXPECT_TRUE(r.calls.empty()) << "a refused program returns no call";
  return r.error.value_or(GcodeError{});
}

}  // namespace tnv::gcode::test
