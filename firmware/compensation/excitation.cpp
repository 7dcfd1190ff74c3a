#include "firmware/compensation/excitation.hpp"

#include <cmath>
#include <cstdlib>

namespace tnv::fw {

namespace {
constexpr double kPeriodS = 1e-3;
}

ParamCheck validate(const ExcitationSpec& s) noexcept {
  if (s.kind != ExcitationKind::step && s.kind != ExcitationKind::ramp) return param_error("kind", "must be step or ramp");
  if (!std::isfinite(s.level_mm_s) || !(std::fabs(s.level_mm_s) > 0.0) || std::fabs(s.level_mm_s) > 100.0)
    return param_error("level_mm_s", "must be finite, 0 < |level| <= 100 mm/s");
  if (!std::isfinite(s.duration_s) || s.duration_s < 0.001 || s.duration_s > 10.0)
    return param_error("duration_s", "must be 0.001 .. 10 s");
  if (!std::isfinite(s.settle_s) || s.settle_s < 0.0 || s.settle_s > 10.0)
    return param_error("settle_s", "must be 0 .. 10 s");
  if (s.kind == ExcitationKind::ramp) {
    if (!std::isfinite(s.rate_mm_s2) || !(s.rate_mm_s2 > 0.0) || s.rate_mm_s2 > 1000.0)
      return param_error("rate_mm_s2", "must be finite, 0 < rate <= 1000 mm/s^2");
    if (s.breakaway_counts < 1 || s.breakaway_counts > 10000)
      return param_error("breakaway_counts", "must be 1 .. 10000");
  }
  return param_ok();
}

void ExcitationGenerator::start(const ExcitationSpec& spec) noexcept {
  spec_ = spec;
  active_ = true;
  k_ = 0;
  drive_ticks_ = std::llround(spec.duration_s / kPeriodS);
  settle_ticks_ = std::llround(spec.settle_s / kPeriodS);
  stop_tick_ = -1;
  breakaway_tick_ = -1;
}

double ExcitationGenerator::next(std::int64_t counts_moved) noexcept {
  if (!active_) return 0.0;
  const std::int64_t k = k_++;
  if (stop_tick_ < 0) {
    bool end = k >= drive_ticks_;
    if (spec_.kind == ExcitationKind::ramp && std::llabs(counts_moved) > 0 && breakaway_tick_ < 0) breakaway_tick_ = k;
    if (spec_.kind == ExcitationKind::ramp && std::llabs(counts_moved) >= spec_.breakaway_counts) end = true;
    if (!end) {
      if (spec_.kind == ExcitationKind::step) return spec_.level_mm_s;
      const double magnitude = std::fmin(spec_.rate_mm_s2 * static_cast<double>(k) * kPeriodS, std::fabs(spec_.level_mm_s));
      return spec_.level_mm_s > 0.0 ? magnitude : -magnitude;
    }
    stop_tick_ = k;
  }
  if (k - stop_tick_ >= settle_ticks_) active_ = false;
  return 0.0;
}

}  // namespace tnv::fw
