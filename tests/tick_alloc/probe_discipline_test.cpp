// Tick-path discipline of probe moves (firmware/motion/probe_move.hpp in
// the motion core): pushing probes and ticking them through a trip, an
// untripped end and a refusal at the start allocate nothing and make no
// system call.
#include <gtest/gtest.h>

#include <string>

#include "firmware/motion/motion_interpolator.hpp"
#include "tests/tick_alloc/alloc_guard.hpp"
#include "tests/tick_alloc/seccomp_guard.hpp"

namespace tnv::test {
namespace {

namespace motion = fw::motion;

// Three probes (a trip at x = 3, one untripped G38.3, one refused G38.2);
// true when each ended as expected.
bool probe_sequence(motion::MotionInterpolator& m) {
  auto run = [&m](bool (*touching)(double)) {
    double x_mm = m.reference_mm()[0];
    for (int k = 0; k < 20'000; ++k) {
      m.set_probe_input(touching(x_mm));
      x_mm = m.tick().axis[0].position_mm;
      if (m.probe_outcome() != motion::ProbeOutcome::none) return m.probe_outcome();
    }
    return motion::ProbeOutcome::none;
  };
  if (m.push(motion::probe_to(motion::ProbeKind::toward_or_error, {10.0, 0.0}, 5.0)) != motion::SegmentRefusal::none)
    return false;
  if (run([](double x) { return x >= 3.0; }) != motion::ProbeOutcome::tripped) return false;
  if (m.push(motion::probe_to(motion::ProbeKind::toward, {0.0, 0.0}, 5.0)) != motion::SegmentRefusal::none) return false;
  if (run([](double) { return false; }) != motion::ProbeOutcome::not_tripped) return false;
  if (m.push(motion::probe_to(motion::ProbeKind::toward_or_error, {5.0, 0.0}, 5.0)) != motion::SegmentRefusal::none)
    return false;
  return run([](double) { return true; }) == motion::ProbeOutcome::already_tripped;
}

motion::MotionInterpolator configured() {
  motion::MotionInterpolator m;
  (void)m.configure({}, {0.0, 0.0});
  return m;
}

TEST(ProbeDiscipline, ProbeMovesAllocateNothing) {
  motion::MotionInterpolator m = configured();
  bool ok = false;
  const long heap_calls = heap_calls_in([&] { ok = probe_sequence(m); });
  EXPECT_TRUE(ok);
  EXPECT_EQ(heap_calls, 0);
}

TEST(ProbeDiscipline, ProbeMovesMakeNoSystemCall) {
  if (!kSeccompUsable) GTEST_SKIP() << "the sanitizer runtime makes its own system calls; proven in the plain build";
  motion::MotionInterpolator m = configured();
  const int result = run_without_syscalls([&] { return probe_sequence(m) ? 0 : 3; });
  if (result == kSeccompUnavailable) GTEST_SKIP() << "seccomp is not available on this kernel";
  EXPECT_EQ(result, 0) << (result < 0 ? "killed by signal " + std::to_string(-result) + ": a system call"
                                      : "the probes did not end as expected");
}

}  // namespace
}  // namespace tnv::test
