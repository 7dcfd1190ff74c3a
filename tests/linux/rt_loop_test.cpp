// The real-time loop on a fake clock and fake system calls: overruns,
// skipped deadlines, the latency histogram, the policy refusals, and
// start/stop from another thread (meaningful under TSan).
#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <deque>
#include <thread>

#include "drivers/linux/rt_loop.hpp"

namespace tnv {
namespace {

using drivers::RtLoop;
using drivers::RtPolicy;

// Time moves only when the loop sleeps (to the deadline plus a scripted
// wake-up latency) or when a cycle takes time. Used by the loop thread only.
class FakeClock final : public drivers::MonotonicClock {
 public:
  std::int64_t now = 1'000'000'000;
  std::deque<std::int64_t> wake_latency_ns;  // per sleep; empty = 0
  std::int64_t now_ns() noexcept override { return now; }
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override {
    std::int64_t late = 0;
    if (!wake_latency_ns.empty()) {
      late = wake_latency_ns.front();
      wake_latency_ns.pop_front();
    }
    if (deadline_ns + late > now) now = deadline_ns + late;
    std::this_thread::yield();
  }
};

class FakeSystem final : public drivers::RtSystem {
 public:
  int lock_error = 0, fifo_error = 0, cpu_error = 0;
  std::atomic<int> fifo_priority{0}, cpu{-1};
  int lock_memory() override { return lock_error; }
  int set_fifo_priority(int priority) override {
    if (fifo_error == 0) fifo_priority = priority;
    return fifo_error;
  }
  int set_cpu(int c) override {
    if (cpu_error == 0) cpu = c;
    return cpu_error;
  }
};

constexpr std::int64_t kPeriodNs = 1'000'000;

TEST(RtLoop, CountsOverrunsSkipsPastDeadlinesAndRecordsTheWakeLatency) {
  FakeClock clock;
  clock.wake_latency_ns = {3'000, 12'000, 7'000, 2'500'000, 1'000};
  FakeSystem system;
  drivers::DeadlineTickSource source(clock, kPeriodNs);
  drivers::LatencyHistogram latency;
  int cycle = 0;
  std::vector<std::int64_t> starts;
  RtLoop loop(source, clock, system, latency, [&]() noexcept {
    starts.push_back(clock.now);
    // Cycle 2 runs 2.5 periods: it overruns, and the deadlines it covered are skipped.
    clock.now += cycle == 1 ? 2'500'000 : 100'000;
    return ++cycle < 6;
  });
  RtPolicy policy;
  policy.priority = 70;
  policy.cpu = 1;
  ASSERT_EQ(loop.start(policy), "");
  while (!loop.finished()) std::this_thread::yield();
  loop.stop();
  const drivers::RtLoopCounters c = loop.counters();
  EXPECT_EQ(c.cycles, 6u);
  EXPECT_EQ(c.overruns, 2u) << "cycle 2 ran 2.5 ms; cycle 4 woke 2.5 ms late and so ended after the next tick";
  EXPECT_EQ(c.skipped_ticks, 4u) << "two deadlines passed during each overrun";
  EXPECT_EQ(system.fifo_priority.load(), 70);
  EXPECT_EQ(system.cpu.load(), 1);
  EXPECT_EQ(loop.warnings(), "");
  const drivers::LatencySummary s = latency.snapshot();
  EXPECT_EQ(s.count, 6u);
  EXPECT_EQ(s.max_ns, 2'500'000) << "the late wake-up";
  EXPECT_EQ(s.min_ns, 0) << "the 6th sleep had no scripted latency";
  EXPECT_EQ(s.buckets[12], 1u) << "12 us lands in [12, 13) us";
  EXPECT_EQ(s.buckets.back(), 1u) << "2.5 ms is beyond the histogram: overflow bucket";
  // Every cycle starts on the period grid plus its wake latency (no drift).
  ASSERT_EQ(starts.size(), 6u);
  EXPECT_EQ((starts[1] - 12'000 - starts[0] + 3'000) % kPeriodNs, 0);
}

TEST(RtLoop, ARefusedPolicyStopsTheStartWhenRequiredAndNamesWhatWasRefused) {
  FakeClock clock;
  FakeSystem system;
  system.fifo_error = EPERM;
  system.lock_error = ENOMEM;
  drivers::DeadlineTickSource source(clock, kPeriodNs);
  drivers::LatencyHistogram latency;
  int cycles = 0;
  RtLoop loop(source, clock, system, latency, [&]() noexcept { return ++cycles < 3; });
  RtPolicy policy;
  policy.priority = 80;
  EXPECT_EQ(loop.start(policy),
            "mlockall not permitted (Cannot allocate memory; needs CAP_IPC_LOCK or LimitMEMLOCK=infinity); "
            "set rt.require = false to run without it");
  system.lock_error = 0;
  EXPECT_EQ(loop.start(policy),
            "SCHED_FIFO priority 80 not permitted (Operation not permitted; needs CAP_SYS_NICE or LimitRTPRIO); "
            "set rt.require = false to run without it");
  EXPECT_EQ(cycles, 0) << "nothing ran";
  EXPECT_FALSE(loop.finished());

  policy.require = false;
  ASSERT_EQ(loop.start(policy), "");
  EXPECT_EQ(loop.warnings(), "SCHED_FIFO priority 80 not permitted (Operation not permitted; needs CAP_SYS_NICE or LimitRTPRIO)");
  while (!loop.finished()) std::this_thread::yield();
  loop.stop();
  EXPECT_EQ(cycles, 3);
}

TEST(RtLoop, StopFromAnotherThreadEndsARunningLoopWhileReadersWatch) {
  FakeClock clock;
  FakeSystem system;
  drivers::DeadlineTickSource source(clock, kPeriodNs);
  drivers::LatencyHistogram latency;
  std::uint64_t state = 0;  // touched by the loop thread only, read after stop()
  RtLoop loop(source, clock, system, latency, [&]() noexcept {
    ++state;
    return true;
  });
  RtPolicy policy;
  policy.require = false;
  ASSERT_EQ(loop.start(policy), "");
  // A reader thread takes histogram and counter snapshots while the loop runs.
  std::atomic<bool> reading{true};
  std::uint64_t max_seen = 0;
  std::thread reader([&] {
    while (reading.load()) {
      const drivers::LatencySummary s = latency.snapshot();
      std::uint64_t in_buckets = 0;
      for (const std::uint64_t b : s.buckets) in_buckets += b;
      EXPECT_GE(in_buckets, s.count) << "a snapshot never counts more samples than its buckets hold";
      max_seen = std::max(max_seen, loop.counters().cycles);
    }
  });
  while (loop.counters().cycles < 200) std::this_thread::yield();
  std::thread stopper([&] { loop.stop(); });
  stopper.join();
  reading = false;
  reader.join();
  EXPECT_TRUE(loop.finished());
  EXPECT_EQ(state, loop.counters().cycles) << "every cycle ran whole before the join";
  EXPECT_GE(state, 200u);
  EXPECT_LE(max_seen, state);
}

TEST(LatencySummary, PercentilesComeFromTheBuckets) {
  drivers::LatencyHistogram h;
  for (int i = 0; i < 98; ++i) h.record(5'500);  // 5 us bucket
  h.record(40'000);
  h.record(90'000);
  const drivers::LatencySummary s = h.snapshot();
  EXPECT_EQ(s.percentile_us(50.0), 6);
  EXPECT_EQ(s.percentile_us(99.0), 41);
  EXPECT_EQ(s.percentile_us(100.0), 91);
  EXPECT_EQ(s.one_line(), "min 5 us  avg 6.7 us  p99 41 us  max 90 us  (n = 100)");
  h.record(-3);  // a wake-up before the deadline counts as 0
  EXPECT_EQ(h.snapshot().min_ns, 0);
}

}  // namespace
}  // namespace tnv
