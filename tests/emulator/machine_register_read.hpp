#pragma once
// One register read through the machine's bus, failing the test when the
// bus refuses it; shared by the emulator tests that poke the register map.
#include <gtest/gtest.h>

#include <cstdint>

#include "emulator/machine.hpp"

namespace tnv::emu::test_support {

inline std::uint32_t read(Machine& m, std::uint16_t word) {
  std::uint32_t value = 0;
  EXPECT_TRUE(m.read_register(word, value)) << "read of 0x" << std::hex << word;
  return value;
}

}  // namespace tnv::emu::test_support
