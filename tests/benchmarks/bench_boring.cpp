// One S4 planner update: a finished part's two bore measurements through
// eq. (11), the band check / variance perturbation and two RLS updates
// (eqs. (5), (6)), then the next part's infeed at both positions (eq. (3)).
// And the same as the node runs it on BORE_GAUGE (boring_station.hpp): the
// settings and the learned state checked, a planner built and restored
// from them, the part recorded, the state taken back.
// Global operator new is counted in this program: the update must not
// allocate (counter "allocs_per_update").
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <new>
#include <random>
#include <vector>

#include "firmware/adaptive/boring/boring_infeed_planner.hpp"
#include "firmware/adaptive/boring/boring_station.hpp"

namespace {
std::atomic<bool> g_counting{false};
std::atomic<long> g_allocations{0};
}  // namespace

namespace {
void* counted_alloc(std::size_t n) {
  if (g_counting.load(std::memory_order_relaxed)) g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
// Not inlined, so GCC does not pair a malloc'd pointer with a built-in new.
[[gnu::noinline]] void counted_free(void* p) noexcept { std::free(p); }
}  // namespace

void* operator new(std::size_t n) { return counted_alloc(n); }
void* operator new[](std::size_t n) { return counted_alloc(n); }
void operator delete(void* p) noexcept { counted_free(p); }
void operator delete[](void* p) noexcept { counted_free(p); }
void operator delete(void* p, std::size_t) noexcept { counted_free(p); }
void operator delete[](void* p, std::size_t) noexcept { counted_free(p); }

namespace {

using namespace tnv;

// Gauge readings of in-band parts of the Table 1 process (sigma 0.016231 mm).
std::vector<std::array<fw::BoreMeasurement, 2>> readings(const fw::BoringInfeedPlanner& planner) {
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0.0, 0.016231);
  std::vector<std::array<fw::BoreMeasurement, 2>> out;
  for (int k = 0; k < 1024; ++k) {
    std::array<fw::BoreMeasurement, 2> part{};
    const double ls[2] = {40.0, 310.0};
    for (int i = 0; i < 2; ++i) {
      const double s = planner.infeed(ls[i]).infeed_mm_rev;
      const double d = 0.0871 * std::pow(s, 0.5025) * std::pow(ls[i], 0.2676) + std::clamp(noise(rng), -0.04, 0.04);
      part[static_cast<std::size_t>(i)] = {ls[i], s, fw::bore_error_from_deflection_mm(d, 0.1165, 60.0)};
    }
    out.push_back(part);
  }
  return out;
}

void BM_BoringPlannerPartUpdate(benchmark::State& state) {
  fw::BoringPlannerParams params;
  params.alpha0 = 0.5025;
  fw::BoringInfeedPlanner planner(params);
  const fw::BoreMeasurement first[2] = {{40.0, 0.5, fw::bore_error_from_deflection_mm(0.1650, 0.1165, 60.0)},
                                        {310.0, 0.5, fw::bore_error_from_deflection_mm(0.2854, 0.1165, 60.0)}};
  planner.record_part(first);
  const auto parts = readings(planner);
  std::size_t k = 0;
  double sink = 0.0;
  g_allocations = 0;
  g_counting = true;
  for (auto _ : state) {
    const fw::BoringPartReport r = planner.record_part(parts[k++ & 1023]);
    sink += planner.infeed(40.0).infeed_mm_rev + planner.infeed(310.0).infeed_mm_rev + r.out_of_band;
    benchmark::DoNotOptimize(sink);
  }
  g_counting = false;
  state.counters["allocs_per_update"] =
      benchmark::Counter(static_cast<double>(g_allocations.load()) / static_cast<double>(state.iterations()));
  state.counters["resets"] = planner.resets();
}
BENCHMARK(BM_BoringPlannerPartUpdate);

void BM_BoringRlsUpdate(benchmark::State& state) {
  fw::LogModelRls rls;
  rls.reset(fw::BoringTheta(std::log(0.0871), 0.5, 0.27), 1.0);
  const fw::BoringRegressor x = fw::boring_regressor(0.2, 100.0, fw::BoringLogBase::natural);
  double y = std::log(0.1165);
  for (auto _ : state) {
    y += 1e-9;
    benchmark::DoNotOptimize(rls.update(x, y, 1.0, 1.0));
  }
}
BENCHMARK(BM_BoringRlsUpdate);

void BM_BoringNodeRecord(benchmark::State& state) {
  fw::BoringStationSettings settings;
  settings.enabled = true;
  settings.alpha0 = 0.5025;
  fw::BoringStationState learned;
  fw::record_bored_part(settings, learned,
                        {fw::bore_error_from_deflection_mm(0.1650, 0.1165, 60.0),
                         fw::bore_error_from_deflection_mm(0.2854, 0.1165, 60.0)},
                        2e-5);
  fw::BoringInfeedPlanner planner(fw::planner_params(settings));
  planner.restore(learned.planner);
  const auto parts = readings(planner);
  std::size_t k = 0;
  g_allocations = 0;
  g_counting = true;
  for (auto _ : state) {
    const auto& p = parts[k++ & 1023];
    fw::BoringStationState s = learned;  // every part on the same learned state: the cost of one, not a drift
    const fw::BoringStationAnswer a = fw::record_bored_part(settings, s, {p[0].bore_error_mm, p[1].bore_error_mm}, 2e-5);
    benchmark::DoNotOptimize(a);
    benchmark::DoNotOptimize(s);
  }
  g_counting = false;
  state.counters["allocs_per_record"] =
      benchmark::Counter(static_cast<double>(g_allocations.load()) / static_cast<double>(state.iterations()));
}
BENCHMARK(BM_BoringNodeRecord);

}  // namespace
