#include "tools/tune/freq_response_spectra.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tnv::tune {

namespace {

using cplx = std::complex<double>;

void check_lengths(const LoopRecord& r) {
  const std::size_t n = r.excitation_mm_s.size();
  if (r.applied_mm_s.size() != n || r.controller_mm_s.size() != n || r.position_mm.size() != n)
    throw std::invalid_argument("frequency response: the record's series differ in length");
  if (!(r.period_s > 0.0)) throw std::invalid_argument("frequency response: the sample period must be > 0");
}

// One block's DFT at normalised angular frequency w (rad/sample), windowed.
struct BlockDft {
  cplx d, u, c, y;
};

BlockDft block_dft(const LoopRecord& r, std::size_t begin, std::size_t length, double w_rad,
                   const std::vector<double>& window) {
  BlockDft out{};
  for (std::size_t n = 0; n < length; ++n) {
    const cplx e = std::polar(window.empty() ? 1.0 : window[n], -w_rad * static_cast<double>(n));
    out.d += r.excitation_mm_s[begin + n] * e;
    out.u += r.applied_mm_s[begin + n] * e;
    out.c += r.controller_mm_s[begin + n] * e;
    out.y += r.position_mm[begin + n] * e;
  }
  return out;
}

void accumulate(SpectraPoint& p, const BlockDft& b) {
  const cplx dc = std::conj(b.d);
  p.s_yd += b.y * dc;
  p.s_ud += b.u * dc;
  p.s_cd += b.c * dc;
  p.s_dd += std::norm(b.d);
  p.s_yy += std::norm(b.y);
  p.s_uu += std::norm(b.u);
  p.s_cc += std::norm(b.c);
  ++p.averages;
}

void normalise(SpectraPoint& p) {
  if (p.averages == 0) return;
  const double k = 1.0 / p.averages;
  p.s_yd *= k;
  p.s_ud *= k;
  p.s_cd *= k;
  p.s_dd *= k;
  p.s_yy *= k;
  p.s_uu *= k;
  p.s_cc *= k;
}

}  // namespace

std::vector<SpectraPoint> multisine_spectra(const LoopRecord& record, std::int64_t period_ticks,
                                            const std::vector<std::int32_t>& harmonics, int skip_periods) {
  check_lengths(record);
  if (period_ticks < 2) throw std::invalid_argument("frequency response: the multisine period must be >= 2 ticks");
  if (skip_periods < 0) throw std::invalid_argument("frequency response: skip_periods must be >= 0");
  const auto length = static_cast<std::size_t>(period_ticks);
  const std::size_t periods = record.excitation_mm_s.size() / length;
  if (periods < static_cast<std::size_t>(skip_periods) + 1)
    throw std::invalid_argument("frequency response: the record holds " + std::to_string(periods) +
                                " whole multisine periods, needs more than the " + std::to_string(skip_periods) +
                                " skipped");
  std::vector<SpectraPoint> out;
  out.reserve(harmonics.size());
  for (const std::int32_t m : harmonics) {
    SpectraPoint p;
    p.freq_hz = m / (static_cast<double>(period_ticks) * record.period_s);
    const double w = 2.0 * std::numbers::pi * m / static_cast<double>(period_ticks);
    for (std::size_t k = static_cast<std::size_t>(skip_periods); k < periods; ++k)
      accumulate(p, block_dft(record, k * length, length, w, {}));
    normalise(p);
    out.push_back(p);
  }
  return out;
}

std::vector<SpectraPoint> welch_spectra(const LoopRecord& record, const std::vector<double>& freqs_hz,
                                        std::int64_t segment_ticks, std::int64_t skip_ticks) {
  check_lengths(record);
  if (segment_ticks < 8) throw std::invalid_argument("frequency response: a Welch segment must be >= 8 ticks");
  if (skip_ticks < 0) throw std::invalid_argument("frequency response: skip_ticks must be >= 0");
  const auto length = static_cast<std::size_t>(segment_ticks);
  const auto skip = static_cast<std::size_t>(skip_ticks);
  const std::size_t total = record.excitation_mm_s.size();
  if (total < skip + length) throw std::invalid_argument("frequency response: the record is shorter than one segment");
  std::vector<double> hann(length);
  for (std::size_t n = 0; n < length; ++n)
    hann[n] = 0.5 - 0.5 * std::cos(2.0 * std::numbers::pi * static_cast<double>(n) / static_cast<double>(length));
  const std::size_t hop = length / 2;
  std::vector<SpectraPoint> out;
  out.reserve(freqs_hz.size());
  for (const double f : freqs_hz) {
    if (!(f > 0.0) || f >= 0.5 / record.period_s)
      throw std::invalid_argument("frequency response: every frequency must be in (0, Nyquist)");
    SpectraPoint p;
    p.freq_hz = f;
    const double w = 2.0 * std::numbers::pi * f * record.period_s;
    for (std::size_t begin = skip; begin + length <= total; begin += hop) accumulate(p, block_dft(record, begin, length, w, hann));
    normalise(p);
    out.push_back(p);
  }
  return out;
}

void remove_linear_trend(std::vector<double>& x) {
  const std::size_t n = x.size();
  if (n < 2) return;
  // Centred time t = k - (n - 1) / 2: slope = sum(t x) / sum(t^2), offset = mean(x).
  const double mid = 0.5 * static_cast<double>(n - 1);
  double sum_x = 0.0, sum_tx = 0.0, sum_tt = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) - mid;
    sum_x += x[k];
    sum_tx += t * x[k];
    sum_tt += t * t;
  }
  const double mean = sum_x / static_cast<double>(n);
  const double slope = sum_tx / sum_tt;
  for (std::size_t k = 0; k < n; ++k) x[k] -= mean + slope * (static_cast<double>(k) - mid);
}

}  // namespace tnv::tune
