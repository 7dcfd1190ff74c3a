#include "tools/hil/hil_rig.hpp"

#include "emulator/scenario_validation.hpp"
#include "tools/hil/hil_firmware_config.hpp"

namespace tnv::hil {

void HilRig::charge_blocks(std::uint64_t blocks) noexcept {
  const auto call_ns = static_cast<std::int64_t>(static_cast<double>(blocks) * charging.ns_per_block);
  ++charged_.calls;
  charged_.last_call_ns = call_ns;
  charged_.last_call_blocks = blocks;
  if (call_ns > charged_.max_call_ns) charged_.max_call_ns = call_ns;
  if (blocks > charged_.max_call_blocks) charged_.max_call_blocks = blocks;
  if (!charging.enabled || call_ns <= charging.threshold_ns) return;
  ++charged_.charged_calls;
  charged_.charged_ns += call_ns;
  pending_ns_ += call_ns;
}

void HilRig::settle_charge() noexcept {
  if (pending_ns_ <= 0) return;
  // The board counts 10 MHz clocks (100 ns each).
  machine.advance_clocks(static_cast<std::uint64_t>((pending_ns_ + 99) / 100));
  pending_ns_ = 0;
}

HilRig::HilRig(const emu::Scenario& scenario, const fw::FirmwareConfig& config)
    : machine(scenario), bus(machine), board(bus), task(board, config) {}

std::unique_ptr<HilRig> HilRig::create(const emu::Scenario& scenario, const fw::FirmwareConfig& base,
                                       fw::ControllerKind controller, std::string& error) {
  if (const std::string bad = emu::validate_scenario(scenario); !bad.empty()) {
    error = "scenario ";
    error += scenario.name;
    error += ": ";
    error += bad;
    return nullptr;
  }
  const fw::FirmwareConfig config = firmware_config_for(scenario, base);
  if (const fw::ConfigError err = fw::validate(config); !err.ok()) {
    error = "firmware config: ";
    error.append(err.section).append(": ").append(err.field).append(": ").append(err.reason);
    return nullptr;
  }
  std::unique_ptr<HilRig> rig(new HilRig(scenario, config));
  if (const drivers::FpgaInitResult init = rig->board.init({}); !init.ok()) {
    error = "I/O board: ";
    error += init.message;
    return nullptr;
  }
  for (const hal::Axis a : hal::kAxes) rig->task.select_controller(a, controller);
  return rig;
}

}  // namespace tnv::hil
