#include "tools/can/freq_response_defaults.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/compensation/excitation_signal.hpp"

namespace tnv::can_host {

namespace {
constexpr double kTickS = 1e-3;
constexpr double kGoldenFraction = 0.6180339887498949;  // (sqrt 5 - 1) / 2
}  // namespace

double incommensurate_carrier_mm_s(double nominal_mm_s, double count_mm, std::int64_t period_ticks) {
  if (nominal_mm_s == 0.0 || !(count_mm > 0.0) || period_ticks < 1) return 0.0;
  const double per_tick = std::fabs(nominal_mm_s) * kTickS / count_mm;
  const auto p = static_cast<double>(period_ticks);
  const double k = std::max(0.0, std::round((1.0 - kGoldenFraction) * p - kGoldenFraction));
  // count_mm arrives as an f32: within a millionth of a count is whole (10 mm/s: 24 counts, not 23.9999993).
  const double counts_per_tick = std::floor(per_tick + 1e-6) + (k + kGoldenFraction) / p;
  return std::copysign(counts_per_tick * count_mm / kTickS, nominal_mm_s);
}

FreqResponseOptions resolved_options(const FreqResponseOptions& o, const fw::AxisConfig& config) {
  FreqResponseOptions r = o;
  const bool pid = config.controller == fw::ControllerKind::pid;
  if (!r.loop_level_mm_s)
    r.loop_level_mm_s = pid ? kPidLoopLevelMmS : kSlidingLoopLevelPerPhi * config.sliding.phi_mm_s;
  if (!r.duration_s) r.duration_s = pid ? kPidDurationS : kSlidingDurationS;
  if (!r.loop_tones)
    r.loop_tones = std::min<std::uint32_t>(fw::kMaxMultisineTones,
                                           fw::multisine_tone_capacity(r.loop_f_min_hz, r.loop_f_max_hz, kTickS));
  if (!r.carrier_mm_s)
    r.carrier_mm_s = incommensurate_carrier_mm_s(pid ? kPidCarrierNominalMmS : kSlidingCarrierNominalMmS,
                                                 config.count_mm, fw::multisine_period_ticks(r.loop_f_min_hz, kTickS));
  return r;
}

}  // namespace tnv::can_host
