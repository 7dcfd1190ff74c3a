// libFuzzer target: raw CAN frames into the firmware node (fuzz_entries.hpp).
#include "tests/fuzz/fuzz_main.hpp"
TNV_FUZZ_TARGET(tnv::fuzz::can_frames)
