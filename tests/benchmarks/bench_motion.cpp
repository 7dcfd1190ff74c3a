// The motion core (firmware/motion/): how fast the queue and look-ahead
// accept segments, and the cost of one tick (backward pass within its budget,
// path follower, jerk filter) over whole programs, reported as the worst
// tick of the run, not only the mean.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <vector>

#include "firmware/motion/lookahead_planner.hpp"
#include "firmware/motion/motion_interpolator.hpp"

namespace {

using namespace tnv::fw::motion;

std::vector<Segment> chord_circle_program(double feed_mm_s) {
  std::vector<Segment> out;
  const double r = 10.0;
  const int n = static_cast<int>(std::ceil(2.0 * std::numbers::pi * r / 0.1));
  out.push_back(line_to({r, 0.0}, feed_mm_s));
  for (int lap = 0; lap < 3; ++lap) {
    for (int i = 1; i <= n; ++i) {
      const double th = 2.0 * std::numbers::pi * i / n;
      out.push_back(line_to({r * std::cos(th), r * std::sin(th)}, feed_mm_s));
    }
  }
  return out;
}

std::vector<Segment> spiral_program(double feed_mm_s) {
  std::vector<Segment> out;
  double pos = 0.0;
  for (int k = 1; k <= 40; ++k) {
    const double c = k % 2 == 1 ? 0.5 : 0.0;
    const double rad = std::fabs(pos - c);
    const double end = c + (pos < c ? rad : -rad);
    out.push_back(arc_to(false, {end, 0.0}, {c, 0.0}, feed_mm_s));
    pos = end;
  }
  return out;
}

std::vector<Segment> corner_program(double feed_mm_s) {
  std::vector<Segment> out;
  for (int i = 1; i <= 400; ++i) out.push_back(line_to({0.5 * i, (i % 2) * 0.5}, feed_mm_s));
  return out;
}

// Push (when the queue has room) and run its whole backward pass: the CPU
// cost of accepting one segment, outside the tick.
void BM_MotionAcceptSegment(benchmark::State& state) {
  const std::vector<Segment> program = chord_circle_program(20.0);
  SegmentQueue queue;
  LookaheadPlanner planner;
  queue.reset(MotionLimits{}, {0.0, 0.0});
  std::size_t next = 0;
  for (auto _ : state) {
    if (queue.free_slots() == 0) queue.pop_front();
    if (next == program.size()) {
      state.PauseTiming();
      queue.reset(MotionLimits{}, {0.0, 0.0});
      planner.reset();
      next = 0;
      state.ResumeTiming();
    }
    benchmark::DoNotOptimize(queue.push(program[next++]));
    planner.segment_added(queue);
    while (planner.pending()) planner.replan(queue, 1.0);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}
BENCHMARK(BM_MotionAcceptSegment);

// A whole program, segments pushed as the queue frees room, every tick
// timed. On a shared machine one timing of a tick may include a preemption,
// so each tick runs on kRepeats copies of the interpolator's state and its
// cost is the fastest of them; tick_max_ns is the worst tick of the run by
// that measure (tick_max_single_ns, one timing per tick, includes the noise).
constexpr int kRepeats = 5;

void run_ticks(benchmark::State& state, const std::vector<Segment>& program) {
  double worst_ns = 0.0, worst_single_ns = 0.0, sum_ns = 0.0;
  std::vector<double> tick_ns;
  tick_ns.reserve(1'000'000);
  std::size_t ticks = 0;
  for (auto _ : state) {
    MotionInterpolator m;
    m.configure(MotionLimits{}, {0.0, 0.0});
    std::size_t next = 0;
    for (std::size_t k = 0; k < 2'000'000; ++k) {
      while (next < program.size() && m.free_slots() > 0) m.push(program[next++]);
      if (next == program.size()) m.end_program();
      double best_ns = 1e300;
      for (int rep = 0; rep < kRepeats; ++rep) {
        MotionInterpolator copy = m;
        const auto t0 = std::chrono::steady_clock::now();
        const MotionReference r = copy.tick();
        const auto t1 = std::chrono::steady_clock::now();
        benchmark::DoNotOptimize(r);
        const double ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
        best_ns = std::min(best_ns, ns);
        if (rep == 0) worst_single_ns = std::max(worst_single_ns, ns);
      }
      benchmark::DoNotOptimize(m.tick());
      tick_ns.push_back(best_ns);
      worst_ns = std::max(worst_ns, best_ns);
      sum_ns += best_ns;
      ++ticks;
      if (next == program.size() && m.queued() == 0 && m.at_rest()) break;
    }
  }
  std::sort(tick_ns.begin(), tick_ns.end());
  state.counters["ticks"] = static_cast<double>(ticks);
  state.counters["tick_mean_ns"] = sum_ns / static_cast<double>(ticks);
  state.counters["tick_p99_9_ns"] = tick_ns[static_cast<std::size_t>(0.999 * static_cast<double>(tick_ns.size() - 1))];
  state.counters["tick_max_ns"] = worst_ns;
  state.counters["tick_max_single_ns"] = worst_single_ns;
}

void BM_MotionTickChordCircle20(benchmark::State& state) { run_ticks(state, chord_circle_program(20.0)); }
void BM_MotionTickSpiral20(benchmark::State& state) { run_ticks(state, spiral_program(20.0)); }
void BM_MotionTickZigzag20(benchmark::State& state) { run_ticks(state, corner_program(20.0)); }
BENCHMARK(BM_MotionTickChordCircle20)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MotionTickSpiral20)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MotionTickZigzag20)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
