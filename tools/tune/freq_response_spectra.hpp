#pragma once
// Averaged cross and auto spectra of a frequency-response experiment, the
// excitation d as the reference signal (docs/frequency-response.md).
//
// The record (one sample per tick, index 0 = the excitation's first tick):
//   d  the excitation added at the plant input (excite_<axis>),
//   u  the command the plant received (the DAC code's speed),
//   c  the controller's part, c = u_cmd - d (command_<axis> - excite_<axis>),
//   y  the encoder position.
// Estimates use d as the instrument, so noise and friction that enter the
// loop (and so reach both u and y) do not bias them: S_xd = E[X conj(D)].
//
// Multisine: the DFT over each whole period at the excited harmonics is
// exact (no leakage), averaged over the periods after `skip_periods`
// (the loop's transient). Sweep (or any record): Welch, Hann windows of
// `segment_ticks`, half overlap, a direct DFT at each requested frequency.
#include <complex>
#include <cstdint>
#include <vector>

namespace tnv::tune {

struct LoopRecord {
  std::vector<double> excitation_mm_s;  // d
  std::vector<double> applied_mm_s;     // u
  std::vector<double> controller_mm_s;  // c
  std::vector<double> position_mm;      // y
  double period_s = 1e-3;
};

// At one frequency: the cross spectra with d and the auto spectra, averaged.
struct SpectraPoint {
  double freq_hz = 0.0;
  std::complex<double> s_yd, s_ud, s_cd;
  double s_dd = 0.0, s_yy = 0.0, s_uu = 0.0, s_cc = 0.0;
  int averages = 0;
};

// Harmonics m of the period (period_ticks samples): f = m / (period_ticks T).
// Throws std::invalid_argument when the record's series differ in length,
// the period is < 2 ticks, or fewer than skip_periods + 1 whole periods fit.
std::vector<SpectraPoint> multisine_spectra(const LoopRecord& record, std::int64_t period_ticks,
                                            const std::vector<std::int32_t>& harmonics, int skip_periods);

// Welch estimate at freqs_hz (each below Nyquist). skip_ticks are dropped
// from the start. Throws std::invalid_argument when the series differ in
// length, segment_ticks < 8, or the record holds no whole segment.
std::vector<SpectraPoint> welch_spectra(const LoopRecord& record, const std::vector<double>& freqs_hz,
                                        std::int64_t segment_ticks, std::int64_t skip_ticks = 0);

// Removes the least-squares straight line from x (a position ramping under a
// constant carrier speed), leaving what varies about it. Fewer than 2
// samples: unchanged.
void remove_linear_trend(std::vector<double>& x);

}  // namespace tnv::tune
