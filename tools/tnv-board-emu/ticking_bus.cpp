#include "tools/tnv-board-emu/ticking_bus.hpp"

#include "hal/io_board_registers.hpp"

namespace tnv::board_emu {

hal::HalStatus TickingBus::read_block(std::uint16_t first_word, std::span<std::uint32_t> out) noexcept {
  if (first_word == hal::regs::kSnapshotFirst) {
    machine_.advance_to_next_tick();
    ++ticks_;
  }
  return bus_.read_block(first_word, out);
}

}  // namespace tnv::board_emu
