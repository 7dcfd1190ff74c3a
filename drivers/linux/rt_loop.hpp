#pragma once
// The real-time control thread: SCHED_FIFO at a priority, pinned to a CPU,
// memory locked; wakes on the tick (the board's tick line, or an absolute
// CLOCK_MONOTONIC deadline when there is none), runs one cycle (tick +
// CAN service), counts overruns (a cycle that ends after the next tick is
// due) and records the wake-up latency.
//
// When the real-time policy is not permitted (containers, no
// CAP_SYS_NICE / LimitRTPRIO / LimitMEMLOCK), start() fails with a message
// naming what was refused, unless policy.require is false: then the loop
// runs with what it got and warnings() says what is missing.
//
// Threads: start() and stop() belong to one controlling thread; the cycle
// runs only on the loop's thread, between start() and stop() (thread start
// and join order it with the controlling thread). The counters and the
// histogram may be read from any thread at any time.
#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>

#include "drivers/linux/gpio_lines.hpp"
#include "drivers/linux/latency_histogram.hpp"

namespace tnv::drivers {

// The system calls behind the policy (a fake in tests): 0 or an errno.
class RtSystem {
 public:
  virtual ~RtSystem() = default;
  virtual int lock_memory() = 0;                 // mlockall(MCL_CURRENT | MCL_FUTURE)
  virtual int set_fifo_priority(int priority) = 0;  // calling thread -> SCHED_FIFO
  virtual int set_cpu(int cpu) = 0;               // calling thread -> one CPU
};
RtSystem& linux_rt_system();

class MonotonicClock {
 public:
  virtual ~MonotonicClock() = default;
  virtual std::int64_t now_ns() noexcept = 0;
  virtual void sleep_until_ns(std::int64_t deadline_ns) noexcept = 0;  // absolute
};
MonotonicClock& linux_monotonic_clock();  // CLOCK_MONOTONIC, clock_nanosleep(TIMER_ABSTIME)

enum class TickWait : std::uint8_t { tick, timeout, error };

class TickSource {
 public:
  virtual ~TickSource() = default;
  // Blocks until the next tick (or a timeout short enough for stop() to be
  // seen); tick_ns = when the tick was due / happened.
  virtual TickWait wait(std::int64_t& tick_ns) noexcept = 0;
  // After a cycle that ended at end_ns: ticks the next wait must skip
  // because they are already past (0 when on time).
  virtual std::uint64_t after_cycle(std::int64_t end_ns) noexcept = 0;
  virtual std::int64_t period_ns() const noexcept = 0;
};

// Absolute deadlines every period on `clock`; overrun deadlines are skipped.
class DeadlineTickSource final : public TickSource {
 public:
  DeadlineTickSource(MonotonicClock& clock, std::int64_t period_ns) noexcept : clock_(clock), period_ns_(period_ns) {}
  TickWait wait(std::int64_t& tick_ns) noexcept override;
  std::uint64_t after_cycle(std::int64_t end_ns) noexcept override;
  std::int64_t period_ns() const noexcept override { return period_ns_; }

 private:
  MonotonicClock& clock_;
  std::int64_t period_ns_;
  std::int64_t next_ns_ = -1;
};

// Rising edges of the board's tick line (timestamps from the kernel).
class GpioTickSource final : public TickSource {
 public:
  GpioTickSource(BoardLines& lines, std::int64_t period_ns, int wait_timeout_ms = 100) noexcept
      : lines_(lines), period_ns_(period_ns), wait_timeout_ms_(wait_timeout_ms) {}
  TickWait wait(std::int64_t& tick_ns) noexcept override;
  std::uint64_t after_cycle(std::int64_t end_ns) noexcept override;
  std::int64_t period_ns() const noexcept override { return period_ns_; }

 private:
  BoardLines& lines_;
  std::int64_t period_ns_;
  int wait_timeout_ms_;
  std::int64_t last_tick_ns_ = 0;
};

struct RtPolicy {
  int priority = 80;   // SCHED_FIFO 1..99; 0 = stay SCHED_OTHER
  int cpu = -1;        // -1 = no affinity
  bool lock_memory = true;
  bool require = true;  // refuse to run without the policy
};

struct RtLoopCounters {
  std::uint64_t cycles = 0;
  std::uint64_t overruns = 0;        // cycles that ended after the next tick was due
  std::uint64_t skipped_ticks = 0;   // ticks lost to overruns
  std::uint64_t wait_timeouts = 0;   // waits that saw no tick (tick line silent)
  std::uint64_t wait_errors = 0;
};

class RtLoop {
 public:
  // The cycle returns false to end the loop (e.g. after N ticks).
  using Cycle = std::function<bool()>;

  RtLoop(TickSource& source, MonotonicClock& clock, RtSystem& system, LatencyHistogram& latency, Cycle cycle)
      : source_(source), clock_(clock), system_(system), latency_(latency), cycle_(std::move(cycle)) {}
  ~RtLoop() { stop(); }
  RtLoop(const RtLoop&) = delete;
  RtLoop& operator=(const RtLoop&) = delete;

  // Locks memory, starts the thread and waits until it has applied its
  // scheduling policy. "" when running; else the reason (no thread left).
  std::string start(const RtPolicy& policy);
  // Asks the thread to finish after its current wait/cycle and joins it.
  void stop();
  // The loop ended on its own (cycle returned false, or a tick-source error).
  bool finished() const noexcept { return finished_.load(std::memory_order_acquire); }
  // What the policy could not get (require = false), "" when everything applied.
  const std::string& warnings() const noexcept { return warnings_; }
  RtLoopCounters counters() const noexcept;

 private:
  void run(std::int64_t period_ns);

  TickSource& source_;
  MonotonicClock& clock_;
  RtSystem& system_;
  LatencyHistogram& latency_;
  Cycle cycle_;
  std::thread thread_;
  std::string warnings_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> finished_{false};
  std::atomic<std::uint64_t> cycles_{0}, overruns_{0}, skipped_{0}, timeouts_{0}, errors_{0};
};

}  // namespace tnv::drivers
