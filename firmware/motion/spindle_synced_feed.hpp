#pragma once
// The spindle speed a feed per revolution runs at (Segment::feed_mm_rev,
// G95; as LinuxCNC's spindle-synchronised feed): the speed the firmware
// measures from the spindle's encoder this tick, never the commanded one
// and never one kept from before. While the spindle is not at speed
// (commanded off, stopping, ramping outside its at-speed window) it is 0:
// a feed per revolution does not move.
//
// The M-method's count quantisation (+-1 count a period: +-0.24 % at
// 6,000 rpm, +-2.4 % at 600 rpm) is smoothed by a first-order low-pass
// (kSyncTauS) and the speed handed on changes only when the smoothed one
// leaves a band of kSyncBand around it: the feed override it drives
// (MotionInterpolator::set_spindle_rpm) then changes when the speed
// really does, not every tick (each change starts a look-ahead walk).
//
// Tick path: noexcept, no heap, fixed work.
namespace tnv::fw::motion {

inline constexpr double kSyncTauS = 0.005;  // a ramp at the drive's 6,000 rpm/s lags by 30 rpm
inline constexpr double kSyncBand = 0.0025; // relative

class SpindleSyncedFeed {
 public:
  // One tick: whether the spindle is at speed, its measured speed (signed
  // rpm) and the period (s). Returns the speed (rpm, >= 0) a feed per
  // revolution runs at now.
  double tick(bool at_speed, double measured_rpm, double period_s) noexcept;
  double rpm() const noexcept { return held_rpm_; }

 private:
  bool running_ = false;      // at speed last tick: the filter holds a speed
  double filtered_rpm_ = 0.0;
  double held_rpm_ = 0.0;
};

}  // namespace tnv::fw::motion
