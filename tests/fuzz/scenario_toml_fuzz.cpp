// libFuzzer target: scenario TOML parser, validation and fault timeline (fuzz_entries.hpp).
#include "tests/fuzz/fuzz_main.hpp"
TNV_FUZZ_TARGET(tnv::fuzz::scenario_toml)
