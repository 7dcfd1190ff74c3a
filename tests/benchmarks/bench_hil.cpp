// Emulator speed: simulated seconds per wall second for the full S1 circle
// (19.45 s of motion + 0.5 s dwell), with and without the firmware in the
// loop. The "realtime_x" counter is the ratio (goal >= 500).
#include <benchmark/benchmark.h>

#include "emulator/axis_plant.hpp"
#include "emulator/machine.hpp"
#include "emulator/scenario_file.hpp"
#include "emulator/z_axis_plant.hpp"
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

// One more plant over one 1 ms tick (100 sub-steps, inputs held), as
// emu::Machine steps each axis: what a third axis adds to every tick.
// stuck: an idle head held by stiction (u = 0, its weight under f_s);
// cruise: 2 mm/s, clear of the Stribeck zone (the closed form);
// zone: 0.2 mm/s, inside it (every sub-step needs exp).
constexpr std::size_t kSubstepsPerTick = 100;

void BM_PlantTick(benchmark::State& state, double speed_mm_s) {
  const emu::AxisPlant plant(emu::kZAxisLaw);
  const double gravity_mm_s = emu::ZAxisParams{}.gravity_mm_s;
  for (auto _ : state) {
    emu::AxisState x{.position_mm = -100.0, .speed_mm_s = speed_mm_s, .stuck = speed_mm_s == 0.0};
    // The command that holds this speed against friction and the weight.
    const double command_mm_s =
        speed_mm_s == 0.0 ? 0.0 : speed_mm_s + plant.friction().magnitude_mm_s(speed_mm_s) - gravity_mm_s;
    plant.advance_held(x, command_mm_s, gravity_mm_s, kSubstepsPerTick);
    benchmark::DoNotOptimize(x);
  }
}
BENCHMARK_CAPTURE(BM_PlantTick, stuck, 0.0);
BENCHMARK_CAPTURE(BM_PlantTick, cruise, 2.0);
BENCHMARK_CAPTURE(BM_PlantTick, zone, 0.2);

// The same idle head stepped one sub-step at a time (ZAxisPlant::step, with
// its end-stop check), 100 per tick: the cost a per-sub-step loop would add.
void BM_ZPlantSubstepsPerTick(benchmark::State& state) {
  emu::ZAxisPlant z{emu::ZAxisParams{}};
  z.set_state(-100.0, 0.0, true);
  for (auto _ : state) {
    for (std::size_t i = 0; i < kSubstepsPerTick; ++i) z.step(0.0);
    benchmark::DoNotOptimize(z.position_mm());
  }
}
BENCHMARK(BM_ZPlantSubstepsPerTick);

}  // namespace
