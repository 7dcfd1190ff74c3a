#pragma once
// Word-addressed 32-bit register access to the FPGA I/O board.
// Implemented by a real transport (Linux) or by the emulator bridge; the
// FPGA driver cannot tell which (hostmot2's read/write function table).
#include <cstdint>
#include <span>

#include "hal/status.hpp"

namespace tnv::hal {

class RegisterBus {
 public:
  virtual ~RegisterBus() = default;
  // Reads out.size() consecutive registers starting at word address first_word.
  virtual HalStatus read_block(std::uint16_t first_word, std::span<std::uint32_t> out) noexcept = 0;
  // Writes in.size() consecutive registers starting at word address first_word.
  virtual HalStatus write_block(std::uint16_t first_word, std::span<const std::uint32_t> in) noexcept = 0;
};

}  // namespace tnv::hal
