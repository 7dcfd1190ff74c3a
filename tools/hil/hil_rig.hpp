#pragma once
// The HIL rig as on the bench: the emulated machine, the emulated register
// bus, the real FPGA driver and the firmware tick task, wired once for
// every HIL run (circle, point-to-point move, jog).
#include <memory>
#include <string>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_task.hpp"

namespace tnv::hil {

// The firmware's control tick, as the rig steps it.
inline constexpr double kTickPeriodS = 1e-3;

class HilRig {
 public:
  // Validates the scenario and the firmware config made for it from
  // `base`, initialises the board and selects `controller` on both axes.
  // nullptr, with a one-line `error`, when anything is refused.
  static std::unique_ptr<HilRig> create(const emu::Scenario& scenario, const fw::FirmwareConfig& base,
                                        fw::ControllerKind controller, std::string& error);

  void tick() noexcept {
    machine.advance_to_next_tick();
    task.tick();
  }
  // Servo-off ticks before the first command: the firmware reads home.
  void home() noexcept {
    for (int i = 0; i < kHomingTicks; ++i) tick();
  }
  static constexpr int kHomingTicks = 3;

  emu::Machine machine;
  drivers::EmulatedRegisterBus bus;
  drivers::FpgaIoBoard board;
  fw::TickTask task;

 private:
  HilRig(const emu::Scenario& scenario, const fw::FirmwareConfig& config);
};

}  // namespace tnv::hil
