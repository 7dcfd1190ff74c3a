#pragma once
// Periodic and swept excitation signals for frequency-response measurement
// (docs/frequency-response.md). Fixed-size state, set up once, then one
// sample per tick at a fixed cost (no allocation, no exceptions).
//
//   log sweep:  d_k = a sin(phi(t_k)),  f(t) = f0 (f1/f0)^(t/T),
//               phi(t) = 2 pi f0 T / ln(f1/f0) ((f1/f0)^(t/T) - 1)
//   multisine:  d_k = a_tone sum_i sin(2 pi m_i n / P + phi_i),  n = k mod P,
//               m_i: log-spaced integer harmonics of 1/P in [f0, f1],
//               phi_i = -pi i (i - 1) / N  (Schroeder: low crest factor)
// Both signals start at zero. With a whole number of periods P in the
// record, the DFT at each harmonic m_i is exact (no leakage).
#include <array>
#include <cstdint>

namespace tnv::fw {

inline constexpr std::uint32_t kMaxMultisineTones = 64;

// The multisine's period for a lowest tone f_min_hz: round(1 / f_min) ticks
// of period_s, so that f_min is (about) its first harmonic.
std::int64_t multisine_period_ticks(double f_min_hz, double period_s) noexcept;

// How many distinct harmonics of 1 / period lie in [f_min, f_max] (0 if
// the arguments are not finite and positive or f_min >= f_max).
std::uint32_t multisine_tone_capacity(double f_min_hz, double f_max_hz, double period_s) noexcept;

struct MultisineTones {
  std::int64_t period_ticks = 0;
  std::uint32_t count = 0;
  std::array<std::int32_t, kMaxMultisineTones> harmonic{};  // m_i, strictly increasing
  std::array<double, kMaxMultisineTones> phase_rad{};       // phi_i
};

// Log-spaced harmonics between f_min and f_max (a harmonic that rounds onto
// its predecessor moves up one). count must be 1 .. min(kMaxMultisineTones,
// multisine_tone_capacity()); otherwise the result has count 0.
MultisineTones multisine_tones(double f_min_hz, double f_max_hz, std::uint32_t count, double period_s) noexcept;

class LogSweep {
 public:
  void start(double f0_hz, double f1_hz, double duration_s, double amplitude, double period_s) noexcept;
  double sample(std::int64_t k) const noexcept;

 private:
  double f0_hz_ = 1.0;
  double log_ratio_ = 0.0;  // ln(f1 / f0)
  double duration_s_ = 1.0;
  double amplitude_ = 0.0;
  double period_s_ = 1e-3;
};

class Multisine {
 public:
  // Per-tone amplitude a_tone = rms_total * sqrt(2 / N): the sum's RMS is rms_total.
  void start(const MultisineTones& tones, double rms_total) noexcept;
  double sample(std::int64_t k) const noexcept;
  const MultisineTones& tones() const noexcept { return tones_; }

 private:
  MultisineTones tones_{};
  double tone_amplitude_ = 0.0;
};

}  // namespace tnv::fw
