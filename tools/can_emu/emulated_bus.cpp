#include "tools/can_emu/emulated_bus.hpp"

#include <thread>

#include "emulator/scenario_file.hpp"
#include "emulator/scenario_validation.hpp"
#include "firmware/can/param_fallback.hpp"
#include "firmware/can/param_table.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/seeded_scenario.hpp"

namespace tnv::can_host {

namespace {

VirtualCanBusOptions wire_options(std::uint32_t bitrate_bit_s) {
  VirtualCanBusOptions o;
  o.bitrate_bit_s = bitrate_bit_s;
  // Frames in flight between the node and the wire, kept short as tnv-fw
  // keeps its SocketCAN socket's kernel queue short (drivers/linux/
  // socketcan_port.cpp): the port sends what it holds first come, first
  // served, so the node's priority order holds only if little waits there.
  o.node_tx_capacity = kNodeFramesInFlight;
  return o;
}

}  // namespace

// The node's side of the wire: what fw::can::CanNode sees as its CAN controller.
class EmulatedBus::NodePort final : public hal::CanPort {
 public:
  explicit NodePort(EmulatedBus& owner) : owner_(owner) {}
  hal::HalStatus try_send(const hal::CanFrame& frame) noexcept override {
    if (owner_.node_tx_filter_ && !owner_.node_tx_filter_(frame)) return hal::HalStatus::ok;  // lost on the wire
    return owner_.wire_.enqueue(BusSide::node, frame, owner_.now()) ? hal::HalStatus::ok : hal::HalStatus::timeout;
  }
  bool try_receive(hal::CanFrame& frame) noexcept override {
    const std::optional<hal::CanFrame> f = owner_.wire_.take(BusSide::node);
    if (!f) return false;
    frame = *f;
    return true;
  }

 private:
  EmulatedBus& owner_;
};

EmulatedBus::EmulatedBus(const emu::Scenario& scenario, const std::string& storage_path, std::uint32_t bitrate_bit_s)
    : scenario_(scenario), storage_(storage_path), wire_(wire_options(bitrate_bit_s)) {}

EmulatedBus::~EmulatedBus() = default;

std::unique_ptr<EmulatedBus> EmulatedBus::create(const EmulatedNodeOptions& options, std::string& error) {
  emu::ScenarioResult found;
  if (options.scenario_value) {
    if (const std::string why = emu::validate_scenario(*options.scenario_value); !why.empty()) {
      error = "scenario: " + why;
      return nullptr;
    }
    found.scenario = *options.scenario_value;
  } else {
    found = emu::resolve_scenario(options.scenario);
  }
  if (!found.scenario) {
    error = found.error;
    if (error.empty()) error.append("no scenario ").append(options.scenario);
    return nullptr;
  }
  const emu::Scenario scenario = hil::seeded(*found.scenario, options.seed);
  const std::string path = options.storage_path.empty() ? default_emulated_storage_path() : options.storage_path;

  // A fresh node: the papers' defaults, the scenario's circle timing (so a
  // CIRCLE with its radius and feed is tnv-hil's circle), the requested id.
  namespace can = fw::can;
  can::NodeSettings settings = can::default_node_settings();
  settings.motion.circle_ramp_s = scenario.circle.ramp_s;
  settings.motion.circle_dwell_s = scenario.circle.dwell_s;
  settings.can.node_id = options.node;

  // Start-up load, before the tick task is built, as on a real node: the
  // current image, else the previous generation, else the defaults.
  drivers::FileParamStorage storage(path);
  const can::NodeSettings fresh = settings;
  const can::LoadReport loaded = can::load_settings_with_fallback(storage, &storage.previous(), settings);
  // A saved set changes every later --emu result: count what differs from a fresh node.
  const std::size_t differing =
      loaded.source != can::LoadSource::nothing_stored ? can::differing_params(settings, fresh) : 0;
  std::string note;
  if (loaded.fault()) {
    note = path;
    note.append(": stored parameters not loaded (").append(can::to_string(loaded.current));
    if (!storage.last_error().empty()) note.append(": ").append(storage.last_error());
    if (loaded.source == can::LoadSource::rolled_back)
      note.append(": generation ").append(std::to_string(loaded.current_generation)).append(" is older than the previous file's ")
          .append(std::to_string(loaded.previous_generation)).append("); the node starts with the newer, previous set");
    else
      note += loaded.source == can::LoadSource::previous ? "); the node starts with the previous saved set"
                                                          : "); the node starts with defaults";
  }
  // The board's hardware facts (encoder, DAC, home) come from the scenario.
  settings.firmware = hil::firmware_config_for(scenario, settings.firmware);
  if (const can::SettingsCheck check = can::validate(settings); !check.ok) {
    error = "emulated node: parameters refused: ";
    error.append(check.section).append(": ").append(check.reason);
    return nullptr;
  }

  std::unique_ptr<EmulatedBus> bus(new EmulatedBus(scenario, path, settings.can.bitrate_kbit * 1000u));
  bus->seed_ = options.seed;
  bus->startup_note_ = note;
  bus->saved_params_differing_ = differing;
  bus->port_ = std::make_unique<NodePort>(*bus);
  bus->rig_ = hil::HilRig::create(scenario, settings.firmware, settings.firmware.axis[0].controller, error);
  if (!bus->rig_) return nullptr;
  bus->node_ = std::make_unique<can::CanNode>(bus->rig_->task, *bus->port_, bus->storage_, settings,
                                              loaded.fault(), &bus->storage_.previous(), &bus->storage_worker_);
  return bus;
}

Micros EmulatedBus::now() {
  // The board counts 10 MHz clocks.
  return Micros{static_cast<Micros::rep>(rig_->machine.elapsed_clocks() / 10u)};
}

void EmulatedBus::step() {
  rig_->settle_charge();
  rig_->machine.advance_to_next_tick();
  wire_.advance_to(now());
  rig_->charged_call([this]() noexcept { rig_->task.tick(); });
  rig_->charged_call([this]() noexcept { node_->service(); });
  storage_worker_.run_pending();
  if (step_observer_) step_observer_();
  if (realtime_) {
    const auto sim = now() - realtime_sim_origin_;
    std::this_thread::sleep_until(realtime_wall_origin_ + sim);
  }
}

void EmulatedBus::set_realtime(bool on) {
  realtime_ = on;
  realtime_sim_origin_ = now();
  realtime_wall_origin_ = std::chrono::steady_clock::now();
}

void EmulatedBus::send(const hal::CanFrame& frame) {
  wire_.enqueue(BusSide::host, frame, now());
  ++host_counters_.tx_frames;
}

std::optional<hal::CanFrame> EmulatedBus::receive(Micros timeout) {
  const Micros deadline = now() + timeout;
  for (;;) {
    if (std::optional<hal::CanFrame> f = wire_.take(BusSide::host)) {
      ++host_counters_.rx_frames;
      return f;
    }
    if (now() >= deadline) return std::nullopt;
    step();
  }
}

std::string EmulatedBus::describe() const {
  std::string out = "emulated node (";
  out.append(scenario_.name).append(", seed ").append(std::to_string(seed_)).append(")");
  return out;
}

BusCounters EmulatedBus::counters() const {
  BusCounters c = host_counters_;
  c.rx_overflow = wire_.counters().dropped_at_host;
  return c;
}

std::uint8_t EmulatedBus::node_id() const noexcept { return node_->node_id(); }

}  // namespace tnv::can_host
