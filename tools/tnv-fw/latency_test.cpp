#include "tools/tnv-fw/latency_test.hpp"

#include <time.h>

#include "drivers/linux/latency_histogram.hpp"
#include "drivers/linux/rt_loop.hpp"

namespace tnv::fwd {

int run_latency_test(const RtConfig& rt, std::uint32_t period_us, double seconds, std::FILE* out, std::FILE* err) {
  drivers::MonotonicClock& clock = drivers::linux_monotonic_clock();
  const std::int64_t period_ns = static_cast<std::int64_t>(period_us) * 1000;
  const auto cycles = static_cast<std::uint64_t>(seconds * 1e9 / static_cast<double>(period_ns));
  drivers::DeadlineTickSource source(clock, period_ns);
  drivers::LatencyHistogram histogram;
  std::uint64_t done = 0;
  drivers::RtLoop loop(source, clock, drivers::linux_rt_system(), histogram,
                       [&done, cycles]() noexcept { return ++done < cycles; });
  drivers::RtPolicy policy;
  policy.priority = rt.priority;
  policy.cpu = rt.cpu;
  policy.require = rt.require;
  if (const std::string e = loop.start(policy); !e.empty()) {
    std::fprintf(err, "tnv-fw: %s\n", e.c_str());
    return 1;
  }
  if (!loop.warnings().empty()) {
    std::fprintf(err, "tnv-fw: WARNING: latency measured WITHOUT the real-time policy: %s\n",
                 loop.warnings().c_str());
  }
  while (!loop.finished()) {
    const timespec pause{0, 50'000'000};
    ::nanosleep(&pause, nullptr);
  }
  loop.stop();
  const drivers::RtLoopCounters c = loop.counters();
  std::fprintf(out, "# tnv-fw latency test: period %u us, %llu cycles, priority %d, cpu %d%s\n", period_us,
               static_cast<unsigned long long>(c.cycles), rt.priority, rt.cpu,
               loop.warnings().empty() ? "" : " (policy NOT applied)");
  std::fprintf(out, "# overruns %llu, skipped ticks %llu\n", static_cast<unsigned long long>(c.overruns),
               static_cast<unsigned long long>(c.skipped_ticks));
  std::fprintf(out, "%s", histogram.snapshot().histogram_text().c_str());
  return 0;
}

}  // namespace tnv::fwd
