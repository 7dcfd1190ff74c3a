#pragma once
// LLVMFuzzerTestOneInput around one entry of fuzz_entries.hpp: a broken
// invariant is printed and aborts, so libFuzzer records it as a crash.
#include <cstdio>
#include <cstdlib>

#include "tests/fuzz/fuzz_entries.hpp"

#define TNV_FUZZ_TARGET(entry)                                                      \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    const std::string broken = entry(data, size);                                   \
    if (!broken.empty()) {                                                          \
      std::fprintf(stderr, "invariant broken: %s\n", broken.c_str());              \
      std::abort();                                                                 \
    }                                                                               \
    return 0;                                                                       \
  }
