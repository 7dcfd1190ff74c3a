#include "emulator/circle_path_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tnv::emu {

CirclePathStepper::CirclePathStepper(const CircleParams& params) noexcept
    : circle_(params),
      dwell_s_(params.dwell_s),
      half_feed_mm_s_(0.5 * params.feed_mm_s),
      ramp_over_pi_s_(params.ramp_s / std::numbers::pi),
      inv_radius_per_mm_(1.0 / params.radius_mm),
      // With ramp_s == 0 the ramp segments are empty and this is never used.
      ramp_powers_(phasor_powers<kMaxRun>(params.ramp_s > 0.0 ? std::numbers::pi * kSubstep_s / params.ramp_s : 0.0)),
      cruise_powers_(phasor_powers<kMaxRun>(params.feed_mm_s * kSubstep_s / params.radius_mm)) {}

void CirclePathStepper::servo_on_at(double time_s) noexcept {
  scheduled_ = true;
  start_s_ = time_s + dwell_s_;
}

CirclePathPoint CirclePathStepper::at_substep(std::uint64_t substep) const noexcept {
  return scheduled_ ? circle_.at(since_start_s(substep)) : CirclePathPoint{};
}

std::uint64_t CirclePathStepper::segment_end(std::uint64_t substep, Segment segment,
                                             std::uint64_t limit) const noexcept {
  double boundary_s = 0.0;
  switch (segment) {
    case Segment::before_start: boundary_s = 0.0; break;
    case Segment::start_ramp: boundary_s = circle_.ramp_s(); break;
    case Segment::cruise: boundary_s = circle_.end_ramp_start_s(); break;
    case Segment::end_ramp: boundary_s = circle_.duration_s(); break;
    case Segment::after_end: return limit;
  }
  // Estimate, then settle on exactly what segment_at() says per sample.
  const double estimate = std::ceil((boundary_s + start_s_) / kSubstep_s);
  std::uint64_t end = estimate <= static_cast<double>(substep + 1) ? substep + 1
                      : estimate >= static_cast<double>(limit)     ? limit
                                                                   : static_cast<std::uint64_t>(estimate);
  while (end > substep + 1 && circle_.segment_at(since_start_s(end - 1)) != segment) --end;
  while (end < limit && circle_.segment_at(since_start_s(end)) == segment) ++end;
  return end;
}

void CirclePathStepper::fill(std::uint64_t first_substep, std::size_t count, double* speed_mm_s, double* cos_angle,
                             double* sin_angle) const noexcept {
  const std::uint64_t limit = first_substep + count;
  std::uint64_t run_start = first_substep;
  while (run_start < limit) {
    // Anchor: the exact point at the start of the run.
    const std::uint64_t run_limit = std::min<std::uint64_t>(limit, run_start + kMaxRun);
    const double t0 = scheduled_ ? since_start_s(run_start) : -1.0;
    const Segment segment = circle_.segment_at(t0);
    const std::uint64_t run_end = scheduled_ ? segment_end(run_start, segment, run_limit) : run_limit;
    const CirclePathPoint anchor = scheduled_ ? circle_.at(t0) : CirclePathPoint{};
    const std::size_t begin = run_start - first_substep;
    const std::size_t end = run_end - first_substep;
    const Phasor direction0{anchor.cos_angle, anchor.sin_angle};

    if (segment == Segment::cruise) {  // constant feed: sample j is turned by j F h / R
      for (std::size_t i = begin; i < end; ++i) {
        const Phasor direction = direction0.rotated(cruise_powers_[i - begin]);
        speed_mm_s[i] = anchor.speed_mm_s;
        cos_angle[i] = direction.cos_a;
        sin_angle[i] = direction.sin_a;
      }
    } else if (segment == Segment::start_ramp || segment == Segment::end_ramp) {
      const bool starting = segment == Segment::start_ramp;
      // Ramp phase pi (t - ramp start) / ramp; the end ramp mirrors the start
      // one: its phase pi t_end / ramp is pi minus this.
      const double ramp_start_s = starting ? 0.0 : circle_.end_ramp_start_s();
      const Phasor ramp0 = Phasor::at(std::numbers::pi * (t0 - ramp_start_s) / circle_.ramp_s());
      Phasor direction = direction0;
      double arc_mm = anchor.arc_mm;
      speed_mm_s[begin] = anchor.speed_mm_s;
      cos_angle[begin] = direction.cos_a;
      sin_angle[begin] = direction.sin_a;
      for (std::size_t i = begin + 1; i < end; ++i) {
        const Phasor ramp = ramp0.rotated(ramp_powers_[i - begin]);
        const double t = since_start_s(first_substep + i);
        double next_arc_mm = 0.0;
        if (starting) {  // speed = F/2 (1 - cos(pi t/ramp)), arc = its integral
          speed_mm_s[i] = half_feed_mm_s_ * (1.0 - ramp.cos_a);
          next_arc_mm = half_feed_mm_s_ * (t - ramp_over_pi_s_ * ramp.sin_a);
        } else {
          speed_mm_s[i] = half_feed_mm_s_ * (1.0 + ramp.cos_a);
          next_arc_mm = circle_.arc_length_mm() -
                        half_feed_mm_s_ * ((circle_.duration_s() - t) - ramp_over_pi_s_ * ramp.sin_a);
        }
        direction.rotate_small((next_arc_mm - arc_mm) * inv_radius_per_mm_);
        arc_mm = next_arc_mm;
        cos_angle[i] = direction.cos_a;
        sin_angle[i] = direction.sin_a;
      }
    } else {  // at rest before the start or after the end
      for (std::size_t i = begin; i < end; ++i) {
        speed_mm_s[i] = 0.0;
        cos_angle[i] = direction0.cos_a;
        sin_angle[i] = direction0.sin_a;
      }
    }
    run_start = run_end;
  }
}

}  // namespace tnv::emu
