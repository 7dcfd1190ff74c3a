#pragma once
// The emulated board as the board-emulator process serves it: register
// access to emu::Machine where each read of the snapshot window (the
// firmware's once-per-tick batched read) first advances the table physics
// to the next tick latch. Simulated time therefore moves exactly one tick
// per tick the firmware runs, whatever the wall clock does: the two-process
// rig is deterministic.
#include <cstdint>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "emulator/machine.hpp"
#include "hal/register_bus.hpp"

namespace tnv::board_emu {

class TickingBus final : public hal::RegisterBus {
 public:
  explicit TickingBus(emu::Machine& machine) noexcept : machine_(machine), bus_(machine) {}

  hal::HalStatus read_block(std::uint16_t first_word, std::span<std::uint32_t> out) noexcept override;
  hal::HalStatus write_block(std::uint16_t first_word, std::span<const std::uint32_t> in) noexcept override {
    return bus_.write_block(first_word, in);
  }

  std::uint64_t ticks_served() const noexcept { return ticks_; }

 private:
  emu::Machine& machine_;
  drivers::EmulatedRegisterBus bus_;
  std::uint64_t ticks_ = 0;
};

}  // namespace tnv::board_emu
