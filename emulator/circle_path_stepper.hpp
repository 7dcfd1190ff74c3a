#pragma once
// The commanded circle sampled at runs of consecutive sub-step boundaries
// without sin/cos per sample: each run starts from the exact closed form
// (CommandedCircle::at) and then turns the ramp shape and the path direction
// by precomputed exact rotations (the path direction in a ramp, where the
// angular speed varies, by a small-angle rotation per sample). A run never spans a segment change and is at most
// kMaxRun samples long, so the exact form is re-anchored at least every
// 100 sub-steps.
#include <array>
#include <cstddef>
#include <cstdint>

#include "emulator/commanded_circle.hpp"
#include "emulator/phasor.hpp"
#include "emulator/substep_timing.hpp"

namespace tnv::emu {

class CirclePathStepper {
 public:
  static constexpr std::size_t kMaxRun = 100;

  explicit CirclePathStepper(const CircleParams& params) noexcept;

  const CommandedCircle& circle() const noexcept { return circle_; }
  // Motion starts dwell_s after servo-on; before that the path rests at (R, 0).
  void servo_on_at(double time_s) noexcept;
  bool motion_scheduled() const noexcept { return scheduled_; }
  double motion_start_s() const noexcept { return start_s_; }

  // Exact path point at sub-step boundary `substep` (time substep_time_s(substep)).
  CirclePathPoint at_substep(std::uint64_t substep) const noexcept;
  // Feed speed and direction for `count` consecutive sub-steps from `first_substep`.
  void fill(std::uint64_t first_substep, std::size_t count, double* speed_mm_s, double* cos_angle,
            double* sin_angle) const noexcept;

 private:
  using Segment = CommandedCircle::Segment;
  double since_start_s(std::uint64_t substep) const noexcept { return substep_time_s(substep) - start_s_; }
  // First sub-step after `substep` that is no longer in `segment` (or `limit`).
  std::uint64_t segment_end(std::uint64_t substep, Segment segment, std::uint64_t limit) const noexcept;

  CommandedCircle circle_;
  double dwell_s_;
  double half_feed_mm_s_;
  double ramp_over_pi_s_;
  double inv_radius_per_mm_;
  std::array<Phasor, kMaxRun> ramp_powers_;    // multiples of pi h / ramp
  std::array<Phasor, kMaxRun> cruise_powers_;  // multiples of F h / R, the cruise path angle per sub-step

  bool scheduled_ = false;
  double start_s_ = 0.0;
};

}  // namespace tnv::emu
