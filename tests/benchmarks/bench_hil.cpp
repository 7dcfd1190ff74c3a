// Emulator speed: simulated seconds per wall second for the full S1 circle
// (19.45 s of motion + 0.5 s dwell), with and without the firmware in the
// loop. The "realtime_x" counter is the ratio (goal >= 500).
#include <benchmark/benchmark.h>

#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "hal/io_board_registers.hpp"
#include "tools/hil/circle_run.hpp"

namespace {

using namespace tnv;

void BM_HilCircle(benchmark::State& state, const char* scenario_name) {
  const emu::Scenario scenario = *emu::builtin_scenario(scenario_name);
  const fw::FirmwareConfig config = fw::default_firmware_config();
  double simulated_s = 0.0;
  for (auto _ : state) {
    const hil::CircleRunResult r = hil::run_circle(scenario, config, fw::ControllerKind::rdvsc);
    if (!r.completed) state.SkipWithError(r.error.c_str());
    // homing + dwell + motion ticks, 1 ms each
    simulated_s += static_cast<double>(r.counters.ticks) * 1e-3;
    benchmark::DoNotOptimize(r.stats.max_um);
  }
  state.counters["realtime_x"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(BM_HilCircle, no_cut, "no-cut")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_HilCircle, cut_1200, "cut-1200")->Unit(benchmark::kMillisecond);

// The emulated machine alone: two axes, cutting on, a constant command.
void BM_EmulatorOnly(benchmark::State& state) {
  const emu::Scenario scenario = *emu::builtin_scenario("cut-1200");
  constexpr int kTicks = 19'950;
  double simulated_s = 0.0;
  for (auto _ : state) {
    emu::Machine machine(scenario);
    machine.write_register(hal::regs::kDacX, 2048 + 25);
    machine.write_register(hal::regs::kDacY, 2048 - 25);
    machine.write_register(hal::regs::kOutputs, hal::regs::kOutputEnableX | hal::regs::kOutputEnableY);
    for (int k = 0; k < kTicks; ++k) machine.advance_to_next_tick();
    benchmark::DoNotOptimize(machine.truth(hal::Axis::x).position_mm);
    simulated_s += kTicks * 1e-3;
  }
  state.counters["realtime_x"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_EmulatorOnly)->Unit(benchmark::kMillisecond);

}  // namespace
