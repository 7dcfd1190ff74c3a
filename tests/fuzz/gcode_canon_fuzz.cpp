// libFuzzer target: bytes as an RS274/NGC program through the LinuxCNC-dialect interpreter (fuzz_entries.hpp).
#include "tests/fuzz/fuzz_main.hpp"
TNV_FUZZ_TARGET(tnv::fuzz::gcode_canon)
