#pragma once
// The closed-loop experiment's defaults, by the axis' controller
// (docs/frequency-response.md, "Defaults"). An option left unset in
// FreqResponseOptions takes them; one given is kept.
//
//   every controller: the excitation rides on a carrier, nudged from its
//     nominal speed so that neither the encoder counts per tick nor the
//     counts per multisine period are near a whole number (the quantisation
//     error then sweeps through its phases and averages out instead of
//     repeating with the excitation); every harmonic of 1 / period in the
//     band as a tone;
//   PID: 20 mm/s (the response near the phase crossover is then several
//     encoder counts) on a 10 mm/s carrier (faster than the table's speed
//     swing, so it never reverses), 12 s;
//   DVSC / R-DVSC+DDC: 2.4 x the axis' boundary layer phi (x 3.1, y 4.1
//     mm/s: the sliding variable stays inside the layer, where the
//     controller is linear) on a 3 mm/s carrier, 30 s (more periods
//     against the quantisation noise at the phase crossover).
#include <cstdint>

#include "firmware/tick/firmware_config.hpp"
#include "tools/can/freq_response_run.hpp"

namespace tnv::can_host {

inline constexpr double kPidCarrierNominalMmS = 10.0;
inline constexpr double kSlidingCarrierNominalMmS = 3.0;
inline constexpr double kPidLoopLevelMmS = 20.0;
inline constexpr double kSlidingLoopLevelPerPhi = 2.4;
inline constexpr double kPidDurationS = 12.0;
inline constexpr double kSlidingDurationS = 30.0;

// A speed near nominal_mm_s moving a + b counts per tick, a whole, with
// b = (k + 0.618...) / period_ticks the one of those nearest 0.382: the
// counts per period then end in the golden ratio's fraction and the counts
// per tick are far from whole. Its sign is nominal's; 0 for 0.
double incommensurate_carrier_mm_s(double nominal_mm_s, double count_mm, std::int64_t period_ticks);

// o with every unset option filled for the axis' controller and encoder.
FreqResponseOptions resolved_options(const FreqResponseOptions& o, const fw::AxisConfig& config);

}  // namespace tnv::can_host
