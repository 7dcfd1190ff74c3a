#include "drivers/emulated/emulated_register_bus.hpp"

namespace tnv::drivers {

hal::HalStatus EmulatedRegisterBus::read_block(std::uint16_t first_word, std::span<std::uint32_t> out) noexcept {
  ++reads_;
  return machine_.read_registers(first_word, out) ? hal::HalStatus::ok : hal::HalStatus::bad_address;
}

hal::HalStatus EmulatedRegisterBus::write_block(std::uint16_t first_word, std::span<const std::uint32_t> in) noexcept {
  ++writes_;
  return machine_.write_registers(first_word, in) ? hal::HalStatus::ok : hal::HalStatus::bad_address;
}

}  // namespace tnv::drivers
