#pragma once
// Work meter: how many basic blocks of firmware code this thread has run.
// The firmware library is compiled with the compiler's basic-block
// instrumentation (-fsanitize-coverage=trace-pc: a call to
// __sanitizer_cov_trace_pc() at the start of every block); work_meter.cpp,
// built without it, counts those calls in a thread-local counter. The HIL
// rig charges a call's blocks to the emulated board's clock at a stated
// cost per block (tools/hil/hil_rig.hpp): a measure of what the firmware
// did that is the same on every run, whatever the host's load or a virtual
// machine's pauses. One increment per block, no lock, no system call.
#include <cstdint>

namespace tnv::fw {

// Blocks run by this thread so far (0 forever when not metered).
std::uint64_t work_blocks() noexcept;

// False when the firmware was built without the instrumentation (the
// libFuzzer build, which owns the coverage callbacks; TNV_WORK_METER=OFF).
bool work_meter_enabled() noexcept;

}  // namespace tnv::fw
