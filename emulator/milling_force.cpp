#include "emulator/milling_force.hpp"

#include <algorithm>
#include <cmath>

#include "emulator/milling_process.hpp"

namespace tnv::emu {

MillingForce::MillingForce(const MillingParams& params, double substep_s) noexcept
    : enabled_(params.enabled),
      params_(params),
      decay_(std::exp(-substep_s / params.time_constant_s)),
      feed_load_(params.feed_load_mm_s_per_n) {}

double MillingForce::depth_mm(double time_s) const noexcept { return depth_profile_mm(params_.depth, time_s); }

void MillingForce::advance(double speed_mm_s, double time_s) noexcept {
  // S3 eq. (28), exact for inputs held over the sub-step.
  const double target_n = params_.force_n_per_mm_mm_s * depth_mm(time_s) * std::max(speed_mm_s, 0.0);
  force_n_ = decay_ * force_n_ + (1.0 - decay_) * target_n;
}

}  // namespace tnv::emu
