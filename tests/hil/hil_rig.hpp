#pragma once
// The full HIL rig for tests that step tick by tick: emulated machine,
// emulated register bus, the real FPGA driver and the firmware tick task.
#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/machine.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/io_board_registers.hpp"
#include "tools/hil/hil_firmware_config.hpp"

namespace tnv::test {

struct HilRig {
  explicit HilRig(const emu::Scenario& s, fw::FirmwareConfig base = fw::default_firmware_config())
      : scenario(s), machine(s), bus(machine), board(bus), task(board, hil::firmware_config_for(s, base)) {
    init_ok = board.init({}).ok();
  }
  void tick() {
    machine.advance_to_next_tick();
    task.tick();
  }
  std::uint32_t reg(std::uint16_t word) {
    std::uint32_t v = 0;
    machine.read_register(word, v);
    return v;
  }

  emu::Scenario scenario;
  emu::Machine machine;
  drivers::EmulatedRegisterBus bus;
  drivers::FpgaIoBoard board;
  fw::TickTask task;
  bool init_ok = false;
};

}  // namespace tnv::test
