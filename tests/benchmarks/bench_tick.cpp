// One firmware tick, both axes, every task (snapshot read, M-method, circle
// reference, R-DVSC+DDC, DAC codes, supervisor, batched write, watchdog).
// The board is a replay of the snapshots an HIL circle produced, so the
// figure is the firmware's cost alone, on real encoder data.
#include <benchmark/benchmark.h>

#include <optional>
#include <vector>

#include "drivers/emulated/emulated_register_bus.hpp"
#include "drivers/fpga/fpga_io_board.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/io_board_registers.hpp"
#include "tools/hil/hil_firmware_config.hpp"

namespace {

using namespace tnv;
namespace regs = hal::regs;
using Snapshot = std::array<std::uint32_t, regs::kSnapshotWords>;
constexpr int kHomingTicks = 3;

// Records the snapshot window of every read on its way through.
class RecordingBus final : public hal::RegisterBus {
 public:
  explicit RecordingBus(hal::RegisterBus& inner) : inner_(inner) {}
  std::vector<Snapshot> snapshots;
  hal::HalStatus read_block(std::uint16_t first, std::span<std::uint32_t> out) noexcept override {
    const hal::HalStatus st = inner_.read_block(first, out);
    if (first == regs::kSnapshotFirst && out.size() == regs::kSnapshotWords) {
      Snapshot s{};
      std::copy(out.begin(), out.end(), s.begin());
      snapshots.push_back(s);
    }
    return st;
  }
  hal::HalStatus write_block(std::uint16_t first, std::span<const std::uint32_t> in) noexcept override {
    return inner_.write_block(first, in);
  }

 private:
  hal::RegisterBus& inner_;
};

// Serves recorded snapshots in order; swallows writes.
class ReplayBus final : public hal::RegisterBus {
 public:
  explicit ReplayBus(const std::vector<Snapshot>& s) : snapshots_(s) {}
  std::size_t next = 0;
  hal::HalStatus read_block(std::uint16_t first, std::span<std::uint32_t> out) noexcept override {
    if (first == regs::kSnapshotFirst && out.size() == regs::kSnapshotWords) {
      const Snapshot& s = snapshots_[next++ % snapshots_.size()];
      std::copy(s.begin(), s.end(), out.begin());
      return hal::HalStatus::ok;
    }
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = first + i == regs::kId ? regs::kIdValue : first + i == regs::kVersion ? regs::kVersionValue : 0u;
    return hal::HalStatus::ok;
  }
  hal::HalStatus write_block(std::uint16_t, std::span<const std::uint32_t>) noexcept override { return hal::HalStatus::ok; }

 private:
  const std::vector<Snapshot>& snapshots_;
};

struct Recording {
  emu::Scenario scenario;
  fw::FirmwareConfig config;
  std::vector<Snapshot> snapshots;
};

const Recording& recording() {
  static const Recording rec = [] {
    Recording r;
    r.scenario = *emu::builtin_scenario("cut-1200");
    r.config = hil::firmware_config_for(r.scenario, fw::default_firmware_config());
    emu::Machine machine(r.scenario);
    drivers::EmulatedRegisterBus emulated(machine);
    RecordingBus bus(emulated);
    drivers::FpgaIoBoard board(bus);
    board.init({});
    bus.snapshots.clear();
    fw::TickTask task(board, r.config);
    for (int i = 0; i < kHomingTicks; ++i) machine.advance_to_next_tick(), task.tick();
    task.start_circle(hil::circle_spec_for(r.scenario));
    while (task.state() != fw::MotionState::holding && task.state() != fw::MotionState::faulted)
      machine.advance_to_next_tick(), task.tick();
    r.snapshots = bus.snapshots;
    return r;
  }();
  return rec;
}

void BM_TickBothAxes(benchmark::State& state) {
  const Recording& rec = recording();
  ReplayBus bus(rec.snapshots);
  drivers::FpgaIoBoard board(bus);
  board.init({});
  std::optional<fw::TickTask> task;
  auto restart = [&] {
    bus.next = 0;
    task.emplace(board, rec.config);
    task->select_controller(hal::Axis::x, static_cast<fw::ControllerKind>(state.range(0)));
    task->select_controller(hal::Axis::y, static_cast<fw::ControllerKind>(state.range(0)));
    for (int i = 0; i < kHomingTicks; ++i) task->tick();
    task->start_circle(hil::circle_spec_for(rec.scenario));
  };
  restart();
  for (auto _ : state) {
    if (bus.next >= rec.snapshots.size()) {
      state.PauseTiming();
      restart();
      state.ResumeTiming();
    }
    task->tick();
  }
  if (task->state() == fw::MotionState::faulted) state.SkipWithError("the replayed run faulted");
  state.SetLabel(fw::to_string(static_cast<fw::ControllerKind>(state.range(0))));
}
BENCHMARK(BM_TickBothAxes)->Arg(0)->Arg(1)->Arg(2);

}  // namespace
