// libFuzzer target: stored parameter images through the file storage and the fallback loader (fuzz_entries.hpp).
#include "tests/fuzz/fuzz_main.hpp"
TNV_FUZZ_TARGET(tnv::fuzz::param_image)
