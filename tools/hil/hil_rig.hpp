#pragma once
// The HIL rig as on the bench: the emulated machine, the emulated register
// bus, the real FPGA driver and the firmware tick task, wired once for
// every HIL run (circle, point-to-point move, jog).
//
// Charged time: the emulated board's clock waits for the firmware, but a
// real FPGA does not. The rig measures the CPU time of every firmware call
// the real-time loop makes (tick here, the CAN service in the CAN rigs,
// through charged_call()); a call over `charging.threshold_ns` is charged
// in full: before the next tick the board runs on by that time, so a slow
// call shows as missed ticks and, past the watchdog timeout, a trip, as on
// a board. Calls under the threshold (every normal call, by far) charge
// nothing, so normal runs stay deterministic (docs/safety.md "Charged time").
#include <cstdint>
#include <memory>
#include <string>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_task.hpp"
#include "tools/hil/thread_cpu_clock.hpp"

namespace tnv::hil {

// The firmware's control tick, as the rig steps it.
inline constexpr double kTickPeriodS = 1e-3;

struct ChargeOptions {
  bool enabled = true;
  // A normal tick or service costs a few us (Release) to ~100 us (TSan);
  // 300 us is far above that and well under the 1 ms period.
  std::int64_t threshold_ns = 300'000;
};

struct ChargedTime {
  std::uint64_t calls = 0;          // calls measured
  std::uint64_t charged_calls = 0;  // calls over the threshold
  std::int64_t charged_ns = 0;      // their total CPU time, given to the board
  std::int64_t max_call_ns = 0;     // the slowest call measured
  std::int64_t last_call_ns = 0;    // the most recent call
};

class HilRig {
 public:
  // Validates the scenario and the firmware config made for it from
  // `base`, initialises the board and selects `controller` on both axes.
  // nullptr, with a one-line `error`, when anything is refused.
  static std::unique_ptr<HilRig> create(const emu::Scenario& scenario, const fw::FirmwareConfig& base,
                                        fw::ControllerKind controller, std::string& error);

  void tick() noexcept {
    settle_charge();
    machine.advance_to_next_tick();
    charged_call([this]() noexcept { task.tick(); });
  }
  // Runs one firmware call of the real-time loop and charges its CPU time
  // (see the top of this file).
  template <class Call>
  void charged_call(Call&& call) noexcept {
    if (!charging.enabled) {
      call();
      return;
    }
    const std::int64_t start_ns = thread_cpu_ns();
    call();
    charge(thread_cpu_ns() - start_ns);
  }
  // Counts one call of `call_ns` (charged when over the threshold).
  void charge(std::int64_t call_ns) noexcept;
  // The board runs on by what was charged since the last tick.
  void settle_charge() noexcept;
  const ChargedTime& charged() const noexcept { return charged_; }
  // Servo-off ticks before the first command: the firmware reads home.
  void home() noexcept {
    for (int i = 0; i < kHomingTicks; ++i) tick();
  }
  static constexpr int kHomingTicks = 3;

  emu::Machine machine;
  drivers::EmulatedRegisterBus bus;
  drivers::FpgaIoBoard board;
  fw::TickTask task;
  ChargeOptions charging{};

 private:
  ChargedTime charged_{};
  std::int64_t pending_ns_ = 0;  // charged, not yet given to the board
  HilRig(const emu::Scenario& scenario, const fw::FirmwareConfig& config);
};

}  // namespace tnv::hil
