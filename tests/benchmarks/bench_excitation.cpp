// One tick of the excitation generator (firmware/compensation/excitation.hpp):
// the per-tick cost the frequency-response kinds add to the tick, against
// the step's. The multisine's cost grows with its tone count (one sin per
// tone), so it is measured at 8, 40 and the 64 tones the parameter allows.
#include <benchmark/benchmark.h>

#include "firmware/compensation/excitation.hpp"

namespace {

using namespace tnv;

fw::ExcitationSpec bench_spec(fw::ExcitationKind kind, std::uint32_t tones) {
  fw::ExcitationSpec s;
  s.kind = kind;
  s.level_mm_s = 3.0;
  s.duration_s = 40.0;  // 40000 drive ticks; run_generator restarts it before they end
  s.f_min_hz = 5.0;
  s.f_max_hz = 400.0;
  s.tones = tones;
  return s;
}

void run_generator(benchmark::State& state, fw::ExcitationKind kind, std::uint32_t tones) {
  const fw::ExcitationSpec spec = bench_spec(kind, tones);
  fw::ExcitationGenerator gen;
  gen.start(spec);
  std::int64_t k = 0;
  for (auto _ : state) {
    // Restart before the drive phase ends: every measured tick is a drive tick.
    if (++k == 30000) {
      gen.start(spec);
      k = 0;
    }
    benchmark::DoNotOptimize(gen.next(0));
  }
}

void BM_ExcitationStep(benchmark::State& state) {
  fw::ExcitationSpec s;
  s.duration_s = 10.0;
  fw::ExcitationGenerator gen;
  gen.start(s);
  std::int64_t k = 0;
  for (auto _ : state) {
    if (++k == 9000) {
      gen.start(s);
      k = 0;
    }
    benchmark::DoNotOptimize(gen.next(0));
  }
}
BENCHMARK(BM_ExcitationStep);

void BM_ExcitationSweep(benchmark::State& state) { run_generator(state, fw::ExcitationKind::sweep, 1); }
BENCHMARK(BM_ExcitationSweep);

void BM_ExcitationMultisine(benchmark::State& state) {
  run_generator(state, fw::ExcitationKind::multisine, static_cast<std::uint32_t>(state.range(0)));
}
BENCHMARK(BM_ExcitationMultisine)->Arg(8)->Arg(40)->Arg(64);

}  // namespace
