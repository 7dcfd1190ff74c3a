// Issue 8 item 3: one estimation + gain update of the ARSC (the paper
// needed 190 ms on an 8 MHz 8086 for estimation, input and gain update).
#include <benchmark/benchmark.h>

#include "firmware/adaptive/arsc/faithful_arsc.hpp"
#include "firmware/adaptive/arsc/arsc_source_params.hpp"
#include "firmware/adaptive/arsc/outer_arsc.hpp"
#include "firmware/adaptive/arsc/robust_arsc.hpp"
#include "tools/hil/arsc_run.hpp"
#include "tools/hil/arsc_tick_study.hpp"

namespace {

using namespace tnv::fw::arsc;

// A recorded closed-loop trace to feed the loops realistic samples.
std::vector<std::pair<double, double>> samples() {
  tnv::hil::ArscRunConfig c;
  c.poles = PoleSet::case1;
  const auto r = tnv::hil::run_arsc(c);
  std::vector<std::pair<double, double>> s;
  for (const auto& p : r.trace) s.emplace_back(p.force, p.feed);
  return s;
}

void BM_FaithfulStep(benchmark::State& state) {
  const auto data = samples();
  FaithfulArscConfig c;
  c.d_star = desired_coefficients(paper_poles(PoleSet::case1));
  FaithfulArsc arsc(c);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(arsc.step(data[i].first, data[i].second));  // RLS + input + (25)/(26)
    if (++i == data.size()) {
      i = 0;
      arsc.reset();
    }
  }
}
BENCHMARK(BM_FaithfulStep);

void BM_RobustStep(benchmark::State& state) {
  const auto data = samples();
  RobustArscConfig c;
  c.d_star = desired_coefficients(six_of_seven(paper_poles(PoleSet::case1)));
  RobustArsc arsc(c);
  std::size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(arsc.step(data[i].first, data[i].second));
    if (++i == data.size()) {
      i = 0;
      arsc.reset();
    }
  }
}
BENCHMARK(BM_RobustStep);

// The worst-case path of the faithful loop: one RLS update and a gain
// update that passes every guard and solves (26) (the loop above may stop
// early at a guard once its estimates drift).
void BM_FaithfulEstimateAndFullGainUpdate(benchmark::State& state) {
  const auto data = samples();
  const auto d = desired_coefficients(paper_poles(PoleSet::case1));
  Arv2Rls rls({0.98, 1.0}, paper_initial_model());
  const Arv2Model designable = paper_initial_model();
  std::size_t i = 2;
  for (auto _ : state) {
    benchmark::DoNotOptimize(rls.update(Arv2Rls::regressor(data[i - 1].first, data[i - 1].second, data[i - 2].first,
                                                           data[i - 2].second, 1.0),
                                        data[i].first, data[i].second));
    const GainDesign g = solve_faithful_gains(designable, d, FixedGains{}, GuardLimits{});
    benchmark::DoNotOptimize(g);
    if (g.reason != GuardReason::none) state.SkipWithError("the gain update must take the full path");
    if (++i == data.size()) {
      i = 2;
      rls.reset(paper_initial_model());
    }
  }
}
BENCHMARK(BM_FaithfulEstimateAndFullGainUpdate);

// The outer loop at the 1 ms tick (issue 8 item 5): one step = estimate,
// next feed command, delta-operator gain design, on samples recorded from
// the emulated machine.
void BM_OuterStepAtTheTick(benchmark::State& state) {
  tnv::hil::TickStudyConfig study;
  study.pole_speedup = 4.0;
  const tnv::hil::TickStudyResult run = tnv::hil::run_tick_study(study);
  if (!run.error.empty() || run.trace.empty()) {
    state.SkipWithError("the tick study did not run");
    return;
  }
  const OuterArscConfig c = outer_config(run.arsc);  // what the board ran with (arsc.*)
  if (!validate(c).ok) {
    state.SkipWithError("bad outer-loop config");
    return;
  }
  OuterArsc arsc(c);
  std::size_t i = 0;
  std::uint32_t refused = 0;
  for (auto _ : state) {
    const auto& p = run.trace[i];
    benchmark::DoNotOptimize(arsc.step(p.force_n, p.feed_mm_s, p.feed_mm_s));
    refused += arsc.signals().last_reason != GuardReason::none;
    if (++i == run.trace.size()) {
      i = 0;
      arsc.reset();
    }
  }
  if (refused) state.SkipWithError("every step must take the full design path");
}
BENCHMARK(BM_OuterStepAtTheTick);

}  // namespace
