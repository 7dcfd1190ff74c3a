// Emulator speed: simulated seconds per wall second for the full S1 circle
// (19.45 s of motion + 0.5 s dwell), with and without the firmware in the
// loop. The "realtime_x" counter is the ratio (goal >= 500).
#include <benchmark/benchmark.h>

#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "hal/io_board_registers.hpp"
#include "tools/hil/circle_run.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/hil_rig.hpp"
#include "tools/hil/thread_cpu_clock.hpp"

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

// The rig's charged time (hil_rig.hpp): the same no-cut circle on a bare
// HilRig with the CPU-time measurement around every tick on and off. The
// difference of the two is its overhead.
void BM_HilRigCharging(benchmark::State& state) {
  const emu::Scenario scenario = *emu::builtin_scenario("no-cut");
  const bool charging = state.range(0) != 0;
  double simulated_s = 0.0;
  for (auto _ : state) {
    std::string error;
    auto rig = hil::HilRig::create(scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, error);
    if (!rig) {
      state.SkipWithError(error.c_str());
      break;
    }
    rig->charging.enabled = charging;
    rig->home();
    rig->task.start_circle(hil::circle_spec_for(scenario));
    while (rig->task.moving()) rig->tick();
    simulated_s += static_cast<double>(rig->task.counters().ticks) * 1e-3;
    benchmark::DoNotOptimize(rig->charged().charged_ns);
  }
  state.counters["realtime_x"] = benchmark::Counter(simulated_s, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_HilRigCharging)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// One read of the thread's CPU clock (two per charged call).
void BM_ThreadCpuClock(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(hil::thread_cpu_ns());
}
BENCHMARK(BM_ThreadCpuClock);

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
