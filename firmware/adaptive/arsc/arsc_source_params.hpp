#pragma once
// What the board is told about its force feed-override source (the outer
// ARSC loop of outer_arsc.hpp running in the tick, arsc_feed_source.hpp):
// the switch, the reference, the loop's own rate, the force-loop poles, the
// model from the test-and-learning stage, the estimator and the override
// range. Physical units; the CAN parameters arsc.* (0x0060..0x006E) map
// one to one. validate() also checks that the loop has gains at the
// model, so a set that passes can run.
#include <cstdint>

#include "firmware/control/param_check.hpp"

namespace tnv::fw::arsc {

struct OuterArscConfig;  // outer_arsc.hpp (kept out of FirmwareConfig's includes)

// The tick the source runs in (TickTask's 1 ms).
inline constexpr double kArscTickS = 1e-3;
// The longest outer period: half a second (the paper's loop took 0.19 s).
inline constexpr std::uint32_t kMaxArscPeriodTicks = 500;
// Normalisation inside the loop (the design's gain bound is in these
// units): the S3 experiment's 150 N and a 10 mm/s feed.
inline constexpr double kArscForceScaleN = 150.0;
inline constexpr double kArscFeedScaleMmS = 10.0;
// Any designed gain above this (normalised) is refused and the last good
// gains are kept (a design at a projection bound runs away).
inline constexpr double kArscMaxGain = 1.0e4;

struct ArscSourceParams {
  bool enabled = false;                  // the source sets the feed override of every program
  double force_ref_n = 150.0;            // f*, the S3 experiment's peak force
  std::uint32_t period_ticks = 1;        // the loop's period in 1 ms ticks (150 = the paper's 0.15 s)
  // The force-loop pole pair s = re +- j im, rad/s (im = 0: a double real
  // pole). Default: S3 case 1 (z = 0.21 at 0.15 s) four times faster.
  double pole_re_rad_s = -41.6;
  double pole_im_rad_s = 0.0;
  // Model (FeedForceModel) from the test-and-learning stage: the cut's
  // force lag, the cutting gain at the start of the cut and the lag from a
  // feed command to the table's feed (planner, jerk filter, axis loop).
  double force_time_constant_s = 0.2;
  double cutting_gain_n_per_mm_s = 3.0;  // 15 N per mm and mm/s at 0.2 mm
  double drive_time_constant_s = 0.015;
  // Estimator of the cutting gain: memory (lambda = exp(-T / memory_s)) and
  // projection onto [gain_min_ratio, gain_max_ratio] x the start gain.
  double memory_s = 0.15;
  double gain_min_ratio = 0.2;
  double gain_max_ratio = 20.0;
  bool adapt = true;                     // false: the start gain is kept (fixed gains)
  // The source's output: a feed override within [override_min, override_max]
  // (never outside 0 .. 1.5) of the running element's programmed feed.
  double override_min = 0.0;
  double override_max = 1.5;
  double soft_start_s = 1.0;             // f* ramps from 0 over this long after a program starts
  bool operator==(const ArscSourceParams&) const = default;
};

// Ranges, cross-field rules and a design at the model (gains exist).
ParamCheck validate(const ArscSourceParams& params) noexcept;

// The loop's configuration for these parameters. Its feed range is wide
// (0 .. kArscFeedCapMmS); the source narrows it every sample to the
// override range times the programmed feed, which is what binds.
inline constexpr double kArscFeedCapMmS = 1.0e4;
OuterArscConfig outer_config(const ArscSourceParams& params) noexcept;

}  // namespace tnv::fw::arsc
