#pragma once
// Excitation of one axis for plant identification (issue 7, item 1) and
// frequency-response measurement (issue 17, docs/frequency-response.md),
// while the capture records what the axis does. Fixed cost per tick, no
// allocation.
//
// Open loop (step, ramp): the tick task drives the axis' speed command from
// this generator instead of its controller.
// Closed loop (sweep, multisine): the axis' controller keeps holding its
// position and the generator's d_k is added at the plant input,
// u_k = c_k + d_k (an integrator plant drifts away under open-loop
// sinusoids; the loop keeps it put and overcomes the friction).
//
//   step: u = level for duration_s, then 0 for settle_s (the speed loop's
//         step response, then the coast to rest).
//   ramp: u = sign(level) * rate * t, |u| <= |level|, until the axis has
//         moved breakaway_counts encoder counts (stiction broken) or
//         duration_s is over; then 0 for settle_s. The command at the
//         first moving tick is the breakaway level f_s / K.
//   sweep: d = level sin(phi(t)), a log chirp f_min -> f_max over
//          duration_s (excitation_signal.hpp); then 0 for settle_s.
//   multisine: Schroeder-phased tones, log-spaced harmonics of the period
//          round(1 / f_min) ticks between f_min and f_max, RMS level / sqrt(2)
//          (a sine of amplitude level); whole periods only: floor(duration /
//          period) of them, at least 2; then 0 for settle_s.
//   multisine_open: the same multisine as the speed command itself (open
//          loop, like step and ramp): the plant alone. A zero-mean periodic
//          command keeps an integrator plant's position periodic (bounded),
//          up to the offset of the start-up transient; see
//          docs/frequency-response.md for why the plant is measured this way.
//
// Carrier (sweep, multisine only): with carrier_mm_s != 0 the holding
// controller's reference moves at that constant speed through the drive
// phase (the tick task moves it) and stops with it, so the excitation is
// measured about a steady motion instead of a standing table: the encoder's
// quantisation phase sweeps and decorrelates from the excitation, and the
// table never reverses (docs/frequency-response.md).
#include <cstdint>

#include "firmware/compensation/excitation_signal.hpp"
#include "firmware/control/param_check.hpp"
#include "hal/listed_enum.hpp"

namespace tnv::fw {

// EXCITE.kind, in wire order: the enum and the protocol's value list come from this one list.
#define TNV_EXCITATION_KINDS(X) X(step) X(ramp) X(sweep) X(multisine) X(multisine_open)

TNV_LISTED_ENUM(ExcitationKind, TNV_EXCITATION_KINDS)

// Sweep and multisine add to the controller's command; step, ramp and the
// open-loop multisine replace it.
constexpr bool closed_loop(ExcitationKind kind) noexcept {
  return kind == ExcitationKind::sweep || kind == ExcitationKind::multisine;
}
// The kinds with a frequency band (excite.* parameters).
constexpr bool banded(ExcitationKind kind) noexcept {
  return closed_loop(kind) || kind == ExcitationKind::multisine_open;
}

// Frequency band of sweep and multisine: 0 < f_min < f_max <= kExcitationMaxFreqHz.
inline constexpr double kExcitationMaxFreqHz = 450.0;  // below the 500 Hz Nyquist frequency of the 1 kHz tick
inline constexpr double kExcitationMinFreqHz = 0.1;
// Longest sweep / multisine record: 3 channels at 1 kHz fill the capture in 43.7 s.
inline constexpr double kExcitationMaxRecordS = 40.0;
// Fastest carrier of a sweep / multisine (a slow, steady motion: the
// measurement is about it, not a traverse).
inline constexpr double kExcitationMaxCarrierMmS = 20.0;
// The carrier ramps in over this many ticks at the start of the drive phase
// and out over as many after it (in the settle), so the reference's speed
// never steps: at most 20 mm/s / 50 ms = 400 mm/s^2. The ramp in lies inside
// the multisine's first period, which the host drops as the transient; the
// travel is carrier x drive phase, as without a ramp.
inline constexpr std::int64_t kCarrierRampTicks = 50;

struct ExcitationSpec {
  ExcitationKind kind = ExcitationKind::step;
  double level_mm_s = 10.0;      // step level, or the ramp's sign and largest |u|
  double rate_mm_s2 = 2.0;       // ramp only, > 0
  double duration_s = 0.15;      // step length / longest ramp
  double settle_s = 0.2;         // u = 0 after, the axis comes to rest
  std::int32_t breakaway_counts = 12;  // ramp only: counts moved that end the ramp
  double f_min_hz = 1.0;         // sweep / multisine: lowest frequency
  double f_max_hz = 100.0;       // sweep / multisine: highest frequency
  std::uint32_t tones = 40;      // multisine only: number of tones, 1 .. kMaxMultisineTones
  double carrier_mm_s = 0.0;     // sweep / multisine only: the reference's constant speed during the drive phase
};

// Finite; 0 < |level| <= 100 mm/s; 0.001 <= duration_s <= 10;
// 0 <= settle_s <= 10; ramp: 0 < rate <= 1000, 1 <= breakaway_counts <= 10000;
// sweep / multisine(_open): 0.1 <= duration_s <= 40, kExcitationMinFreqHz <= f_min
// < f_max <= kExcitationMaxFreqHz, multisine(_open): 1 <= tones <= the distinct
// harmonics in the band (multisine_tone_capacity) and duration_s >= 2 periods;
// carrier_mm_s finite, |carrier| <= kExcitationMaxCarrierMmS, and 0 unless
// sweep / multisine; with a carrier, settle_s covers the ramp out.
ParamCheck validate(const ExcitationSpec& spec) noexcept;

class ExcitationGenerator {
 public:
  void start(const ExcitationSpec& spec) noexcept;
  // The command for this tick, from the counts moved since start().
  double next(std::int64_t counts_moved) noexcept;
  bool active() const noexcept { return active_; }
  bool closed_loop() const noexcept { return fw::closed_loop(spec_.kind); }
  // The reference's speed for the coming tick: the carrier through the drive
  // phase, ramped in over its first kCarrierRampTicks and out over as many
  // after it, then 0.
  double carrier_mm_s() const noexcept;
  bool has_carrier() const noexcept { return active_ && spec_.carrier_mm_s != 0.0; }
  // Ticks of the drive phase (the multisine's: whole periods), from start().
  std::int64_t drive_ticks() const noexcept { return drive_ticks_; }
  // Tick index (from 0) at which the ramp saw the axis move; -1 if not (yet).
  std::int64_t breakaway_tick() const noexcept { return breakaway_tick_; }

 private:
  ExcitationSpec spec_{};
  bool active_ = false;
  std::int64_t k_ = 0;
  std::int64_t drive_ticks_ = 0;
  std::int64_t settle_ticks_ = 0;
  std::int64_t stop_tick_ = -1;  // the tick the drive phase ended
  std::int64_t breakaway_tick_ = -1;
  LogSweep sweep_{};
  Multisine multisine_{};
};

}  // namespace tnv::fw
