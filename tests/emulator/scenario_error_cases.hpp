#pragma once
// A scenario text that must be refused, with the one-line error it must
// give: the test (scenario_file_test.cpp: ScenarioFileErrors) and a name
// for each case, shared by every file that lists such cases
// (scenario_file_test.cpp, machine_keys_test.cpp).
#include <gtest/gtest.h>

#include <cctype>
#include <ostream>
#include <string>

namespace tnv::emu::test {

struct ScenarioErrorCase {
  const char* what;
  const char* text;
  const char* expected;  // the whole line after "scen.toml:"
};

inline void PrintTo(const ScenarioErrorCase& c, std::ostream* os) { *os << c.what; }

class ScenarioFileErrors : public ::testing::TestWithParam<ScenarioErrorCase> {};

// The case's `what`, as a test name.
inline std::string scenario_error_case_name(const ::testing::TestParamInfo<ScenarioErrorCase>& info) {
  std::string name = info.param.what;
  for (char& ch : name) {
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  }
  return name;
}

}  // namespace tnv::emu::test
