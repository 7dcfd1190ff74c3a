// The streaming input shaper: one step (one axis, position and speed) for
// short, long and the longest shapers the ring is sized for, and the cost
// of designing one (the configure_shaper command, between ticks).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "firmware/shaper/shaper_design.hpp"
#include "firmware/shaper/stream_shaper.hpp"

namespace {

using namespace tnv;

fw::ShaperSpec spec_for(int which) {
  switch (which) {
    case 0: return {fw::ShaperType::zv, {30.0, 0.02}, {0.0, 0.0}};
    case 1: return {fw::ShaperType::zvdd, {30.0, 0.02}, {0.0, 0.0}};
    case 2: return {fw::ShaperType::zvd, {30.0, 0.02}, {100.0, 0.02}};
    default:
      return {
          fw::ShaperType::zvdd, {fw::kShaperMinFreqHz, fw::kShaperMaxZeta}, {fw::kShaperMinFreqHz, fw::kShaperMaxZeta}};
  }
}

const char* name_for(int which) {
  switch (which) {
    case 0: return "ZV 30 Hz";
    case 1: return "ZVDD 30 Hz";
    case 2: return "ZVD 30 Hz x 100 Hz";
    default: return "ZVDD 5 Hz x 5 Hz, zeta 0.3 (longest)";
  }
}

void BM_StreamShaperStep(benchmark::State& state) {
  const int which = static_cast<int>(state.range(0));
  const fw::ShaperDesign design = fw::design_shaper(spec_for(which), 1e-3);
  fw::StreamShaper shaper;
  shaper.request_taps(design.taps);
  shaper.request_enabled(true);
  shaper.reset({0.0, 0.0});
  // A jog-like input: 4096 samples of a smooth back-and-forth, replayed.
  std::vector<fw::AxisSample> in(4096);
  for (std::size_t k = 0; k < in.size(); ++k) {
    const double t = static_cast<double>(k) * 1e-3;
    in[k] = {10.0 * std::sin(1.5 * t), 15.0 * std::cos(1.5 * t)};
  }
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(shaper.step(in[k++ & 4095]));
  }
  state.SetLabel(std::string(name_for(which)) + ", " + std::to_string(design.taps.count) + " taps, span " +
                 std::to_string(design.taps.span()));
}
BENCHMARK(BM_StreamShaperStep)->DenseRange(0, 3);

void BM_DesignShaper(benchmark::State& state) {
  const fw::ShaperSpec spec = spec_for(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(fw::design_shaper(spec, 1e-3));
  state.SetLabel(name_for(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_DesignShaper)->DenseRange(0, 3)->Unit(benchmark::kMicrosecond);

}  // namespace
