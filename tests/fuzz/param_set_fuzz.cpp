// libFuzzer target: PARAM_REQUEST get/set/stage/commit/discard sequences (fuzz_entries.hpp).
#include "tests/fuzz/fuzz_main.hpp"
TNV_FUZZ_TARGET(tnv::fuzz::param_set)
