#include "firmware/compensation/excitation_signal.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace tnv::fw {

std::int64_t multisine_period_ticks(double f_min_hz, double period_s) noexcept {
  if (!(f_min_hz > 0.0) || !(period_s > 0.0) || !std::isfinite(f_min_hz) || !std::isfinite(period_s)) return 0;
  return std::llround(1.0 / (f_min_hz * period_s));
}

std::uint32_t multisine_tone_capacity(double f_min_hz, double f_max_hz, double period_s) noexcept {
  if (!std::isfinite(f_max_hz) || !(f_max_hz > f_min_hz)) return 0;
  const std::int64_t p = multisine_period_ticks(f_min_hz, period_s);
  if (p < 2) return 0;
  const double df_hz = 1.0 / (static_cast<double>(p) * period_s);
  const auto lo = static_cast<std::int64_t>(std::ceil(f_min_hz / df_hz - 1e-9));
  // Below Nyquist strictly: a tone at P/2 has no phase information.
  const std::int64_t hi = std::min(static_cast<std::int64_t>(std::floor(f_max_hz / df_hz + 1e-9)), (p - 1) / 2);
  return hi >= lo ? static_cast<std::uint32_t>(hi - lo + 1) : 0u;
}

MultisineTones multisine_tones(double f_min_hz, double f_max_hz, std::uint32_t count, double period_s) noexcept {
  MultisineTones t;
  const std::uint32_t capacity = multisine_tone_capacity(f_min_hz, f_max_hz, period_s);
  if (count < 1 || count > kMaxMultisineTones || count > capacity) return t;
  t.period_ticks = multisine_period_ticks(f_min_hz, period_s);
  const double df_hz = 1.0 / (static_cast<double>(t.period_ticks) * period_s);
  const auto lo = static_cast<std::int32_t>(std::ceil(f_min_hz / df_hz - 1e-9));
  const std::int32_t hi = lo + static_cast<std::int32_t>(capacity) - 1;
  const double ratio = static_cast<double>(hi) / static_cast<double>(lo);
  std::int32_t previous = lo - 1;
  for (std::uint32_t i = 0; i < count; ++i) {
    const double x = count == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(count - 1);
    auto m = static_cast<std::int32_t>(std::lround(lo * std::pow(ratio, x)));
    if (m <= previous) m = previous + 1;
    // Room for the tones still to come (capacity >= count guarantees some).
    const std::int32_t room = hi - static_cast<std::int32_t>(count - 1 - i);
    if (m > room) m = room;
    t.harmonic[i] = m;
    previous = m;
    const double n = static_cast<double>(count);
    const double idx = static_cast<double>(i + 1);
    t.phase_rad[i] = -std::numbers::pi * idx * (idx - 1.0) / n;  // Schroeder
  }
  t.count = count;
  return t;
}

void LogSweep::start(double f0_hz, double f1_hz, double duration_s, double amplitude, double period_s) noexcept {
  f0_hz_ = f0_hz;
  log_ratio_ = std::log(f1_hz / f0_hz);
  duration_s_ = duration_s;
  amplitude_ = amplitude;
  period_s_ = period_s;
}

double LogSweep::sample(std::int64_t k) const noexcept {
  const double t_s = static_cast<double>(k) * period_s_;
  const double phase_rad =
      2.0 * std::numbers::pi * f0_hz_ * duration_s_ / log_ratio_ * (std::exp(log_ratio_ * t_s / duration_s_) - 1.0);
  return amplitude_ * std::sin(phase_rad);
}

void Multisine::start(const MultisineTones& tones, double rms_total) noexcept {
  tones_ = tones;
  tone_amplitude_ = tones.count == 0 ? 0.0 : rms_total * std::sqrt(2.0 / static_cast<double>(tones.count));
}

double Multisine::sample(std::int64_t k) const noexcept {
  if (tones_.period_ticks <= 0) return 0.0;
  // n = k mod P keeps the argument small: the same sample every period.
  const double n = static_cast<double>(k % tones_.period_ticks);
  const double w = 2.0 * std::numbers::pi / static_cast<double>(tones_.period_ticks);
  double sum = 0.0;
  for (std::uint32_t i = 0; i < tones_.count; ++i) sum += std::sin(w * tones_.harmonic[i] * n + tones_.phase_rad[i]);
  return tone_amplitude_ * sum;
}

}  // namespace tnv::fw
