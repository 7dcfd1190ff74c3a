#include "firmware/can/telemetry_scheduler.hpp"

namespace tnv::fw::can {

std::uint32_t TelemetryScheduler::advance(const TelemetryPeriods& periods, std::uint64_t ticks) noexcept {
  const std::array<std::uint32_t, kCyclicCount> period{periods.heartbeat_ms, periods.position_ms,
                                                       periods.sliding_ms,   periods.output_ms,
                                                       periods.contour_ms,   periods.arsc_ms,
                                                       periods.spindle_ms};
  std::uint32_t due = 0;
  for (std::size_t i = 0; i < kCyclicCount; ++i) {
    if (period[i] != period_[i]) {  // changed (or first call): count the new period from here
      period_[i] = period[i];
      elapsed_[i] = 0;
    }
    if (period[i] == 0) continue;
    elapsed_[i] += ticks;
    if (elapsed_[i] >= period[i]) {
      elapsed_[i] %= period[i];
      due |= 1u << i;
    }
  }
  return due;
}

}  // namespace tnv::fw::can
