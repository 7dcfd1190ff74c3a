// Tick-path discipline of the spindle's command logic
// (firmware/spindle/spindle_control.hpp): its commands and ticks allocate
// nothing and make no system call, over a start, a speed change, a
// reversal, a controlled stop and an e-stop.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "firmware/spindle/spindle_control.hpp"
#include "tests/tick_alloc/alloc_guard.hpp"
#include "tests/tick_alloc/seccomp_guard.hpp"

namespace tnv::test {
namespace {

static_assert(noexcept(std::declval<fw::SpindleControl&>().tick(0.0, 0.001)), "the spindle's tick must be noexcept");

// Every command and 10,000 ticks; a crude first-order spindle answers the
// command so that at-speed and standstill are reached. True when the
// sequence ended stopped with the e-stop's cause recorded.
bool spindle_sequence(fw::SpindleControl& spindle) {
  double rpm = 0.0;
  auto run = [&](int ticks) {
    for (int i = 0; i < ticks; ++i) {
      const fw::SpindleOutputs out = spindle.tick(rpm, 0.001);
      rpm += ((out.enable ? out.command_rpm : 0.0) - rpm) * 0.005;
    }
  };
  if (spindle.start(fw::SpindleDirection::forward, 3000.0) != fw::SpindleResult::ok) return false;
  run(2000);
  if (!spindle.at_speed()) return false;
  (void)spindle.set_speed(2000.0);
  run(1000);
  (void)spindle.start(fw::SpindleDirection::reverse, 2000.0);
  run(2000);
  spindle.stop(fw::SpindleStopCause::program_end);
  run(2000);
  if (spindle.start(fw::SpindleDirection::forward, 1000.0) != fw::SpindleResult::ok) return false;
  run(1000);
  spindle.set_inhibit(true, fw::SpindleStopCause::estop);
  run(2000);
  return !spindle.active() && spindle.last_stop_cause() == fw::SpindleStopCause::estop && std::isfinite(rpm);
}

TEST(SpindleDiscipline, CommandsAndTicksAllocateNothing) {
  fw::SpindleControl spindle;
  bool ok = false;
  const long heap_calls = heap_calls_in([&] { ok = spindle_sequence(spindle); });
  EXPECT_TRUE(ok);
  EXPECT_EQ(heap_calls, 0);
}

TEST(SpindleDiscipline, CommandsAndTicksMakeNoSystemCall) {
  if (!kSeccompUsable) GTEST_SKIP() << "the sanitizer runtime makes its own system calls; proven in the plain build";
  fw::SpindleControl spindle;
  const int result = run_without_syscalls([&] { return spindle_sequence(spindle) ? 0 : 3; });
  if (result == kSeccompUnavailable) GTEST_SKIP() << "seccomp is not available on this kernel";
  EXPECT_EQ(result, 0) << (result < 0 ? "killed by signal " + std::to_string(-result) + ": a system call"
                                      : "the sequence did not end stopped");
}

}  // namespace
}  // namespace tnv::test
