#pragma once
// The crash rule of the reference plant: engaging the stock with the
// spindle stopped, or below crash_speed_fraction of its commanded speed,
// is a crash. One crash per episode (the sub-step it begins); its time and
// tool point are kept for the first kKept, all are counted. "Stopped"
// includes a spindle commanded off and still coasting, and one turning
// against its command (a cutter turning backwards cuts nothing).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace tnv::emu {

struct CrashEvent {
  double time_s = 0.0;
  double x_mm = 0.0;
  double y_mm = 0.0;
  double z_mm = 0.0;
  double spindle_rpm = 0.0;
  double commanded_rpm = 0.0;
};

class SpindleCrashLog {
 public:
  static constexpr std::size_t kKept = 16;

  explicit SpindleCrashLog(double crash_speed_fraction) noexcept : fraction_(crash_speed_fraction) {}

  bool too_slow(double spindle_rpm, double commanded_rpm) const noexcept {
    if (commanded_rpm == 0.0) return true;
    return std::copysign(1.0, commanded_rpm) * spindle_rpm < fraction_ * std::abs(commanded_rpm);
  }

  void observe(bool engaged, const CrashEvent& at) noexcept {
    const bool crashing = engaged && too_slow(at.spindle_rpm, at.commanded_rpm);
    if (crashing && !crashing_) {
      if (count_ < kKept) events_[count_] = at;
      ++count_;
    }
    crashing_ = crashing;
  }

  std::uint64_t count() const noexcept { return count_; }
  bool crashing() const noexcept { return crashing_; }
  // The i-th crash (i < min(count, kKept)).
  const CrashEvent& event(std::size_t i) const noexcept { return events_[i]; }

 private:
  double fraction_;
  std::array<CrashEvent, kKept> events_{};
  std::uint64_t count_ = 0;
  bool crashing_ = false;
};

}  // namespace tnv::emu
