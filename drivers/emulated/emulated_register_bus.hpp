#pragma once
// RegisterBus into the emulated machine: what a UIO window or SPI link is
// on the real board. A bad address fails the whole transfer, as a bus
// error would.
#include "emulator/machine.hpp"
#include "hal/register_bus.hpp"

namespace tnv::drivers {

class EmulatedRegisterBus final : public hal::RegisterBus {
 public:
  explicit EmulatedRegisterBus(emu::Machine& machine) noexcept : machine_(machine) {}

  hal::HalStatus read_block(std::uint16_t first_word, std::span<std::uint32_t> out) noexcept override;
  hal::HalStatus write_block(std::uint16_t first_word, std::span<const std::uint32_t> in) noexcept override;

  std::uint64_t reads() const noexcept { return reads_; }
  std::uint64_t writes() const noexcept { return writes_; }

 private:
  emu::Machine& machine_;
  std::uint64_t reads_ = 0;
  std::uint64_t writes_ = 0;
};

}  // namespace tnv::drivers
