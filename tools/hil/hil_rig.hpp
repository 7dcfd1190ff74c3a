#pragma once
// The HIL rig as on the bench: the emulated machine, the emulated register
// bus, the real FPGA driver and the firmware tick task, wired once for
// every HIL run (circle, point-to-point move, jog).
//
// Charged time: the emulated board's clock waits for the firmware, but a
// real FPGA does not. The rig meters the work of every firmware call the
// real-time loop makes (tick here, the CAN service in the CAN rigs,
// through charged_call()) in basic blocks of firmware code
// (firmware/tick/work_meter.hpp) and turns it into board time at a stated
// cost per block. A call over `charging.threshold_ns` is charged in full:
// before the next tick the board runs on by that time, so a slow call
// shows as missed ticks and, past the watchdog timeout, a trip, as on a
// board. Every normal call is far under the threshold and charges nothing.
// The meter counts what the firmware did, not how long the host took, so
// a loaded or paused host changes nothing: runs stay deterministic
// (docs/safety.md "Charged time").
#include <cstdint>
#include <memory>
#include <string>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_task.hpp"
#include "firmware/tick/work_meter.hpp"
#include "tools/hil/thread_cpu_clock.hpp"

namespace tnv::hil {

// The firmware's control tick, as the rig steps it.
inline constexpr double kTickPeriodS = 1e-3;

struct ChargeOptions {
  bool enabled = true;
  // The cost model: board time per basic block of firmware code. The build
  // host runs about 2 ns per block (a tick is ~220 blocks, ~0.5 us); a
  // board-class CPU (Cortex-A53 at 1.2 GHz) is taken as 2.5x slower.
  double ns_per_block = 5.0;
  // A tick costs ~1.1 us of modelled board time and a CAN service at most
  // ~100 us (SHAPER's design); 300 us is far above that and well under the
  // 1 ms period.
  std::int64_t threshold_ns = 300'000;
  // Also time each call in the host thread's CPU time (two clock reads, a
  // system call each on some virtual machines): for tnv-hil rt-budget's
  // table only, never charged.
  bool measure_cpu_time = false;
};

struct ChargedTime {
  std::uint64_t calls = 0;          // calls metered
  std::uint64_t charged_calls = 0;  // calls over the threshold
  std::int64_t charged_ns = 0;      // their total modelled time, given to the board
  std::int64_t max_call_ns = 0;     // the slowest call, modelled board time
  std::int64_t last_call_ns = 0;    // the most recent call, modelled board time
  std::uint64_t max_call_blocks = 0;
  std::uint64_t last_call_blocks = 0;
  std::int64_t last_call_cpu_ns = 0;  // host CPU time, when measure_cpu_time
};

// True when the scenario's [io] transport is on and this build's firmware is
// not metered (TNV_WORK_METER=OFF): each output write then lands with no
// firmware work before it, sooner than in a metered build, so the run's
// timing and what depends on it differ from a development build's
// (docs/performance.md "What an unmetered tnv-hil gives").
inline bool io_work_unmetered(const emu::Scenario& scenario) noexcept {
  return scenario.io.enabled() && !fw::work_meter_enabled();
}

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
    // [io]: the tick's output write lands after this work (emu::Machine; nothing without [io]).
    machine.set_firmware_work_ns(static_cast<double>(charged_.last_call_ns));
  }
  // Runs one firmware call of the real-time loop and charges its work
  // (see the top of this file).
  template <class Call>
  void charged_call(Call&& call) noexcept {
    const std::int64_t start_cpu_ns = charging.measure_cpu_time ? thread_cpu_ns() : 0;
    const std::uint64_t start_blocks = fw::work_blocks();
    call();
    const std::uint64_t blocks = fw::work_blocks() - start_blocks;
    if (charging.measure_cpu_time) charged_.last_call_cpu_ns = thread_cpu_ns() - start_cpu_ns;
    charge_blocks(blocks);
  }
  // Counts one call of `blocks` basic blocks (charged when its modelled
  // time is over the threshold and charging is on).
  void charge_blocks(std::uint64_t blocks) noexcept;
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
