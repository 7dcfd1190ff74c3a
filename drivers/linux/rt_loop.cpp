#include "drivers/linux/rt_loop.hpp"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <cerrno>
#include <cstring>
#include <future>

namespace tnv::drivers {

namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;

class LinuxRtSystem final : public RtSystem {
 public:
  int lock_memory() override { return ::mlockall(MCL_CURRENT | MCL_FUTURE) == 0 ? 0 : errno; }
  int set_fifo_priority(int priority) override {
    sched_param param{};
    param.sched_priority = priority;
    return ::pthread_setschedparam(::pthread_self(), SCHED_FIFO, &param);
  }
  int set_cpu(int cpu) override {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<unsigned>(cpu), &set);
    return ::pthread_setaffinity_np(::pthread_self(), sizeof set, &set);
  }
};

class LinuxMonotonicClock final : public MonotonicClock {
 public:
  std::int64_t now_ns() noexcept override {
    timespec ts{};
    ::clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec;
  }
  void sleep_until_ns(std::int64_t deadline_ns) noexcept override {
    timespec ts{};
    ts.tv_sec = static_cast<time_t>(deadline_ns / kNsPerS);
    ts.tv_nsec = static_cast<long>(deadline_ns % kNsPerS);
    while (::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    }
  }
};

std::string refused(const char* what, int error, const char* hint) {
  std::string message = what;
  message.append(" not permitted (").append(std::strerror(error)).append("; ").append(hint).append(")");
  return message;
}

void append(std::string& to, const std::string& what) {
  if (!to.empty()) to += "; ";
  to += what;
}

}  // namespace

RtSystem& linux_rt_system() {
  static LinuxRtSystem system;
  return system;
}

MonotonicClock& linux_monotonic_clock() {
  static LinuxMonotonicClock clock;
  return clock;
}

TickWait DeadlineTickSource::wait(std::int64_t& tick_ns) noexcept {
  if (next_ns_ < 0) next_ns_ = clock_.now_ns() + period_ns_;
  clock_.sleep_until_ns(next_ns_);
  tick_ns = next_ns_;
  next_ns_ += period_ns_;
  return TickWait::tick;
}

std::uint64_t DeadlineTickSource::after_cycle(std::int64_t end_ns) noexcept {
  if (end_ns < next_ns_) return 0;
  // Deadlines already past are skipped, not run back to back.
  const auto skipped = static_cast<std::uint64_t>((end_ns - next_ns_) / period_ns_ + 1);
  next_ns_ += static_cast<std::int64_t>(skipped) * period_ns_;
  return skipped;
}

TickWait GpioTickSource::wait(std::int64_t& tick_ns) noexcept {
  switch (lines_.wait_tick(wait_timeout_ms_, tick_ns)) {
    case TickEdge::rising: last_tick_ns_ = tick_ns; return TickWait::tick;
    case TickEdge::timeout: return TickWait::timeout;
    case TickEdge::error: return TickWait::error;
  }
  return TickWait::error;
}

std::uint64_t GpioTickSource::after_cycle(std::int64_t end_ns) noexcept {
  const std::int64_t late_ns = end_ns - (last_tick_ns_ + period_ns_);
  // The edges that came meanwhile are queued by the kernel; report how many were due.
  return late_ns < 0 ? 0 : static_cast<std::uint64_t>(late_ns / period_ns_ + 1);
}

std::string RtLoop::start(const RtPolicy& policy) {
  if (thread_.joinable()) return "the control thread is already running";
  warnings_.clear();
  stop_.store(false, std::memory_order_relaxed);
  finished_.store(false, std::memory_order_relaxed);
  std::string problems;
  if (policy.lock_memory) {
    if (const int e = system_.lock_memory(); e != 0) {
      append(problems, refused("mlockall", e, "needs CAP_IPC_LOCK or LimitMEMLOCK=infinity"));
    }
  }
  if (!problems.empty() && policy.require) return problems + "; set rt.require = false to run without it";

  std::promise<std::string> setup;
  std::future<std::string> setup_done = setup.get_future();
  const std::int64_t period_ns = source_.period_ns();
  // The promise moves into the thread: it stays alive through set_value()
  // however soon this thread wakes from get() and returns.
  thread_ = std::thread([this, policy, problems, period_ns, setup = std::move(setup)]() mutable {
    if (policy.priority > 0) {
      if (const int e = system_.set_fifo_priority(policy.priority); e != 0) {
        std::string what = "SCHED_FIFO priority ";
        what += std::to_string(policy.priority);
        append(problems, refused(what.c_str(), e, "needs CAP_SYS_NICE or LimitRTPRIO"));
      }
    }
    if (policy.cpu >= 0) {
      if (const int e = system_.set_cpu(policy.cpu); e != 0) {
        std::string what = "CPU affinity to CPU ";
        what += std::to_string(policy.cpu);
        append(problems, refused(what.c_str(), e, "is the CPU online and allowed?"));
      }
    }
    if (!problems.empty() && policy.require) {
      setup.set_value(problems + "; set rt.require = false to run without it");
      return;
    }
    warnings_ = problems;
    setup.set_value("");
    run(period_ns);
  });
  std::string error = setup_done.get();
  if (!error.empty()) {
    thread_.join();
    return error;
  }
  return "";
}

void RtLoop::run(std::int64_t period_ns) {
  while (!stop_.load(std::memory_order_acquire)) {
    std::int64_t tick_ns = 0;
    const TickWait w = source_.wait(tick_ns);
    if (w == TickWait::timeout) {
      timeouts_.fetch_add(1, std::memory_order_relaxed);
      continue;
    }
    if (w == TickWait::error) {
      errors_.fetch_add(1, std::memory_order_relaxed);
      break;
    }
    latency_.record(clock_.now_ns() - tick_ns);
    const bool go_on = cycle_();
    cycles_.fetch_add(1, std::memory_order_relaxed);
    const std::int64_t end_ns = clock_.now_ns();
    if (end_ns > tick_ns + period_ns) overruns_.fetch_add(1, std::memory_order_relaxed);
    if (const std::uint64_t skipped = source_.after_cycle(end_ns); skipped > 0) {
      skipped_.fetch_add(skipped, std::memory_order_relaxed);
    }
    if (!go_on) break;
  }
  finished_.store(true, std::memory_order_release);
}

void RtLoop::stop() {
  stop_.store(true, std::memory_order_release);
  if (thread_.joinable()) thread_.join();
}

RtLoopCounters RtLoop::counters() const noexcept {
  auto get = [](const std::atomic<std::uint64_t>& c) { return c.load(std::memory_order_relaxed); };
  return {get(cycles_), get(overruns_), get(skipped_), get(timeouts_), get(errors_)};
}

}  // namespace tnv::drivers
