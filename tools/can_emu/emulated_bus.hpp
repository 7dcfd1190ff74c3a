#pragma once
// The in-process emulated controller behind a virtual CAN bus: the real
// firmware (fw::TickTask + fw::can::CanNode) on the emulated board and
// table (hil::HilRig), with its parameters loaded from a file at start as
// a real node loads them from flash. Time is simulated: waiting for a
// frame runs ticks (machine.advance_to_next_tick, task.tick, node.service)
// until the frame arrives or the simulated timeout passes; the wire
// between host and node is a VirtualCanBus at the node's bit rate.
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "drivers/storage/file_param_storage.hpp"
#include "drivers/storage/stepped_storage_worker.hpp"
#include "emulator/scenario.hpp"
#include "firmware/can/can_node.hpp"
#include "tools/can/host_bus.hpp"
#include "tools/can/virtual_can_bus.hpp"
#include "tools/can_emu/emulated_storage_path.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::can_host {

// Frames the emulated node's CAN port holds for the wire (a short kernel
// queue): the rest wait in the node's priority queue. 10 frames keep the
// wire busy for one tick (9 eight-byte frames per ms at 1 Mbit/s, so an
// upload runs at wire speed) and bound what a FAULT_EVENT or a reply can
// wait behind to about 1.1 ms.
inline constexpr std::size_t kNodeFramesInFlight = 10;

struct EmulatedNodeOptions {
  std::string scenario = "no-cut";  // built-in name or TOML file
  std::optional<emu::Scenario> scenario_value;  // instead of `scenario`: one built in code (validated here)
  int seed = 0;                     // hil::seeded(); 0 = the scenario as written (tnv-hil circle's default)
  std::string storage_path;         // "" = default_emulated_storage_path()
  std::uint8_t node = 1;            // the id of a node that has nothing stored yet
};

class EmulatedBus final : public HostBus {
 public:
  // nullptr with a one-line `error` when the scenario or the stored
  // parameters cannot make a node (a damaged image is not an error: the
  // node starts with defaults and reports it, like a real one; see
  // startup_note()).
  static std::unique_ptr<EmulatedBus> create(const EmulatedNodeOptions& options, std::string& error);
  ~EmulatedBus() override;

  void send(const hal::CanFrame& frame) override;
  std::optional<hal::CanFrame> receive(Micros timeout) override;
  Micros now() override;
  std::string describe() const override;
  BusCounters counters() const override;

  // One tick of the node: advance the machine, deliver what the wire
  // finished, tick, service (both charged to the board, HilRig's charged
  // time), then the storage worker's save or load, outside the charged time.
  void step();
  // Simulated time follows the wall clock while on (for `monitor`).
  void set_realtime(bool on);
  // Frames the node sends pass through `keep` before the wire; false drops
  // one (to test recovery from lost frames). Empty = keep all.
  void set_node_tx_filter(std::function<bool(const hal::CanFrame&)> keep) { node_tx_filter_ = std::move(keep); }
  // Called after every step() (the judge of a run watching the machine's
  // truth each tick); empty = none.
  void set_step_observer(std::function<void()> observer) { step_observer_ = std::move(observer); }

  std::uint8_t node_id() const noexcept;
  const emu::Scenario& scenario() const noexcept { return scenario_; }
  const std::string& storage_path() const noexcept { return storage_.path(); }
  // What happened to the stored parameters at start ("" when they loaded or none were stored).
  const std::string& startup_note() const noexcept { return startup_note_; }
  // Parameters of the set loaded at start that differ from a fresh node's (0: none loaded, or a fresh set).
  std::size_t saved_params_differing() const noexcept { return saved_params_differing_; }
  fw::can::CanNode& node() noexcept { return *node_; }
  const fw::can::CanNode& node() const noexcept { return *node_; }
  hil::HilRig& rig() noexcept { return *rig_; }
  const VirtualCanBus& wire() const noexcept { return wire_; }

 private:
  class NodePort;
  EmulatedBus(const emu::Scenario& scenario, const std::string& storage_path, std::uint32_t bitrate_bit_s);

  emu::Scenario scenario_;
  int seed_ = 0;
  drivers::FileParamStorage storage_;
  drivers::SteppedStorageWorker storage_worker_;
  VirtualCanBus wire_;
  std::unique_ptr<NodePort> port_;
  std::unique_ptr<hil::HilRig> rig_;
  std::unique_ptr<fw::can::CanNode> node_;
  std::function<bool(const hal::CanFrame&)> node_tx_filter_;
  std::function<void()> step_observer_;
  std::string startup_note_;
  std::size_t saved_params_differing_ = 0;
  BusCounters host_counters_{};
  bool realtime_ = false;
  Micros realtime_sim_origin_{0};
  std::chrono::steady_clock::time_point realtime_wall_origin_{};
};

}  // namespace tnv::can_host
