#include "firmware/compensation/excitation.hpp"

#include <cmath>
#include <cstdlib>

namespace tnv::fw {

namespace {
constexpr double kPeriodS = 1e-3;

// Sweep and multisine: band, record length, tones.
ParamCheck validate_band(const ExcitationSpec& s) noexcept {
  if (!std::isfinite(s.duration_s) || s.duration_s < 0.1 || s.duration_s > kExcitationMaxRecordS)
    return param_error("duration_s", "must be 0.1 .. 40 s for a sweep or multisine");
  if (!std::isfinite(s.settle_s) || s.settle_s < 0.0 || s.settle_s > 10.0)
    return param_error("settle_s", "must be 0 .. 10 s");
  if (!std::isfinite(s.f_min_hz) || s.f_min_hz < kExcitationMinFreqHz || s.f_min_hz >= kExcitationMaxFreqHz)
    return param_error("f_min_hz", "must be 0.1 Hz <= f_min < 450 Hz");
  if (!std::isfinite(s.f_max_hz) || !(s.f_max_hz > s.f_min_hz) || s.f_max_hz > kExcitationMaxFreqHz)
    return param_error("f_max_hz", "must be f_min < f_max <= 450 Hz");
  if (s.kind != ExcitationKind::sweep) {
    if (s.tones < 1 || s.tones > kMaxMultisineTones ||
        s.tones > multisine_tone_capacity(s.f_min_hz, s.f_max_hz, kPeriodS))
      return param_error("tones", "must be 1 .. 64 and fit the band's harmonics of 1 / period");
    const auto period_ticks = static_cast<double>(multisine_period_ticks(s.f_min_hz, kPeriodS));
    if (std::floor(s.duration_s / kPeriodS + 1e-6) < 2.0 * period_ticks)
      return param_error("duration_s", "must hold at least 2 periods of the multisine (1 / f_min each)");
  }
  return param_ok();
}
}  // namespace

ParamCheck validate(const ExcitationSpec& s) noexcept {
  if (s.kind != ExcitationKind::step && s.kind != ExcitationKind::ramp && s.kind != ExcitationKind::sweep &&
      s.kind != ExcitationKind::multisine && s.kind != ExcitationKind::multisine_open)
    return param_error("kind", "must be step, ramp, sweep, multisine or multisine_open");
  if (!std::isfinite(s.level_mm_s) || !(std::fabs(s.level_mm_s) > 0.0) || std::fabs(s.level_mm_s) > 100.0)
    return param_error("level_mm_s", "must be finite, 0 < |level| <= 100 mm/s");
  if (!std::isfinite(s.carrier_mm_s) || std::fabs(s.carrier_mm_s) > kExcitationMaxCarrierMmS)
    return param_error("carrier_mm_s", "must be finite, |carrier| <= 20 mm/s");
  if (s.carrier_mm_s != 0.0 && !closed_loop(s.kind))
    return param_error("carrier_mm_s", "only a sweep or multisine (closed loop) runs on a carrier");
  if (s.carrier_mm_s != 0.0 && !(s.settle_s >= static_cast<double>(kCarrierRampTicks) * kPeriodS))
    return param_error("settle_s", "must cover the carrier's ramp out (0.05 s)");
  if (banded(s.kind)) return validate_band(s);
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
  if (spec.kind == ExcitationKind::sweep)
    sweep_.start(spec.f_min_hz, spec.f_max_hz, spec.duration_s, spec.level_mm_s, kPeriodS);
  if (spec.kind == ExcitationKind::multisine || spec.kind == ExcitationKind::multisine_open) {
    // A sine of amplitude level has RMS level / sqrt(2): the same power as the sweep.
    multisine_.start(multisine_tones(spec.f_min_hz, spec.f_max_hz, spec.tones, kPeriodS),
                     spec.level_mm_s / std::sqrt(2.0));
    const std::int64_t period = multisine_.tones().period_ticks;
    drive_ticks_ = period > 0 ? (std::llround(std::floor(spec.duration_s / kPeriodS + 1e-6)) / period) * period : 0;
  }
  stop_tick_ = -1;
  breakaway_tick_ = -1;
}

double ExcitationGenerator::carrier_mm_s() const noexcept {
  if (!active_ || spec_.carrier_mm_s == 0.0) return 0.0;
  // Ramp in: (k + 1) / R of the carrier for k < R; ramp out after the drive
  // phase: 1 - (j + 1) / R for j = k - drive < R. The two ramps leave out and
  // add back the same (R - 1) / 2 ticks of travel.
  const double ramp = static_cast<double>(kCarrierRampTicks);
  const double share = k_ < drive_ticks_ ? std::fmin(1.0, static_cast<double>(k_ + 1) / ramp)
                                         : std::fmax(0.0, 1.0 - static_cast<double>(k_ - drive_ticks_ + 1) / ramp);
  return share * spec_.carrier_mm_s;
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
      if (spec_.kind == ExcitationKind::sweep) return sweep_.sample(k);
      if (spec_.kind == ExcitationKind::multisine || spec_.kind == ExcitationKind::multisine_open)
        return multisine_.sample(k);
      const double magnitude = std::fmin(spec_.rate_mm_s2 * static_cast<double>(k) * kPeriodS, std::fabs(spec_.level_mm_s));
      return spec_.level_mm_s > 0.0 ? magnitude : -magnitude;
    }
    stop_tick_ = k;
  }
  if (k - stop_tick_ >= settle_ticks_) active_ = false;
  return 0.0;
}

}  // namespace tnv::fw
