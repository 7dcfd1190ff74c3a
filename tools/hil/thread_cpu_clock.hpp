#pragma once
// The calling thread's CPU time (CLOCK_THREAD_CPUTIME_ID), ns. Host side
// only: what a call of the firmware costs, without the time the OS gave
// other threads while it ran (so a loaded machine does not make it look slow).
#include <cstdint>

namespace tnv::hil {

std::int64_t thread_cpu_ns() noexcept;

}  // namespace tnv::hil
