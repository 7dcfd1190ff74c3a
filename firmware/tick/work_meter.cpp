// Built without the block instrumentation (firmware/CMakeLists.txt): the
// callback must not count, nor call, itself.
#include "firmware/tick/work_meter.hpp"

namespace {
thread_local std::uint64_t t_blocks = 0;
}  // namespace

#if defined(TNV_WORK_METER)
extern "C" void __sanitizer_cov_trace_pc() { ++t_blocks; }
#endif

namespace tnv::fw {

std::uint64_t work_blocks() noexcept { return t_blocks; }

bool work_meter_enabled() noexcept {
#if defined(TNV_WORK_METER)
  return true;
#else
  return false;
#endif
}

}  // namespace tnv::fw
