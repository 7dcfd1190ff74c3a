#pragma once
// tnv-fw --latency-test SECONDS: the control thread's wake-up latency with
// nothing else in the cycle, cyclictest style (absolute clock_nanosleep
// deadlines at the tick period, SCHED_FIFO as configured).
#include <cstdio>
#include <string>

#include "tools/tnv-fw/fw_config.hpp"

namespace tnv::fwd {

// Runs for `seconds`, prints the histogram to `out`; returns the exit code
// (0 ok, 1 the real-time policy was required and refused).
int run_latency_test(const RtConfig& rt, std::uint32_t period_us, double seconds, std::FILE* out, std::FILE* err);

}  // namespace tnv::fwd
