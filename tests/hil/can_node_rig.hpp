#pragma once
// The CAN node on the emulated bench: tools/hil's HilRig (emulated TNV-40,
// register bus, real FPGA driver, the firmware tick) plus the node, an
// in-memory CAN port and storage. step() = one tick, then service(), as
// the firmware's main loop runs them, both charged to the board (HilRig's
// charged time); then the storage worker runs a posted save/load, outside
// the charged time, as a non-real-time thread would.
#include <memory>
#include <string>
#include <vector>

#include "emulator/scenario_file.hpp"
#include "firmware/can/can_node.hpp"
#include "drivers/storage/stepped_storage_worker.hpp"
#include "tests/firmware/can/can_test_doubles.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::test {

inline constexpr std::uint8_t kRigNode = 1;

struct CanRig {
  // Telemetry off unless the test turns it on (then the answers are the only frames).
  static std::unique_ptr<CanRig> make(const std::string& scenario_name = "no-cut",
                                      fw::ControllerKind controller = fw::ControllerKind::rdvsc) {
    auto r = std::make_unique<CanRig>();
    r->scenario = *emu::builtin_scenario(scenario_name);
    std::string error;
    r->rig = hil::HilRig::create(r->scenario, fw::default_firmware_config(), controller, error);
    if (!r->rig) return nullptr;
    r->rig->home();
    fw::can::NodeSettings s = fw::can::default_node_settings();
    s.firmware = r->rig->task.config();
    s.telemetry = {0, 0, 0, 0, 0, 0, 0};
    r->node = std::make_unique<fw::can::CanNode>(r->rig->task, r->port, r->storage, s, false, nullptr, &r->worker);
    r->port.send(command(kRigNode, fw::can::CommandCode::take_ownership));  // the test host (kTestTag) commands
    r->node->service();
    r->port.drain();
    return r;
  }
  fw::TickTask& task() { return rig->task; }
  void step() {
    rig->tick();
    service();
    worker.run_pending();
  }
  void service() {
    rig->charged_call([this]() noexcept { node->service(); });
  }
  std::vector<hal::CanFrame> request(const hal::CanFrame& f) {
    port.send(f);
    service();
    return port.drain();
  }
  // A request whose answer may come later (save, load): steps until a frame comes out (or max_ticks).
  std::vector<hal::CanFrame> request_and_wait(const hal::CanFrame& f, int max_ticks = 10) {
    std::vector<hal::CanFrame> out = request(f);
    for (int k = 0; k < max_ticks && out.empty(); ++k) {
      step();
      out = port.drain();
    }
    return out;
  }
  // The result byte of the single answer (COMMAND_ACK / PARAM_REPLY / CAPTURE_STATUS), 255 if not one answer.
  std::uint32_t result(const hal::CanFrame& f) {
    const std::vector<hal::CanFrame> out = request(f);
    if (out.size() != 1) return 255;
    const auto id = static_cast<fw::can::MessageId>(fw::can::message_of(out[0].id));
    return raw_of(out[0], id, "result");
  }
  // Ticks until the task is in `state` (or max_ticks); true when it got there.
  bool run_until(fw::MotionState state, int max_ticks) {
    for (int k = 0; k < max_ticks; ++k) {
      if (task().state() == state) return true;
      step();
    }
    return task().state() == state;
  }

  emu::Scenario scenario;
  std::unique_ptr<hil::HilRig> rig;
  FakeCanPort port;
  MemoryStorage storage;
  drivers::SteppedStorageWorker worker;
  std::unique_ptr<fw::can::CanNode> node;
};

inline std::uint16_t param_id(const char* name) { return fw::can::find_param(name)->id; }

// The result field of a reply that accepted the request.
inline constexpr auto kOk = static_cast<std::uint32_t>(fw::can::ErrorCode::ok);

}  // namespace tnv::test
