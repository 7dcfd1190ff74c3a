#pragma once
// The score of a program run (the keys of `tnv-hil path` and `tnvctl run
// --json`), from one sample per 1 ms tick of the measured position and the
// reference the loop followed, against the program as parsed:
//
//   contour_error_max/mean/std_um  distance from the measured position to the
//                                  nearest point of the programmed lines and
//                                  arcs (tools/gcode/path_distance.hpp)
//   path_deviation_max_um          the same for the reference
//   accel_ratio_max, jerk_ratio_max  largest |second| / |third| backward
//                                  difference of the reference over dt^2 /
//                                  dt^3, over that axis' path limit
//                                  (tests/firmware/motion/motion_run.hpp)
//   feed_ratio                     programmed time (length / F, dwells
//                                  included) over the cycle time
//   cycle_time_s                   the motion window's length
//
// The motion window runs from the last sample at the starting reference to
// the first sample at the final reference (within rest_tolerance_mm, so a
// reference rebuilt from rounded telemetry does not count its rounding as
// motion); contour error and path deviation are taken over it.
#include <cstddef>
#include <span>

#include "firmware/motion/motion_limits.hpp"
#include "tools/gcode/gcode_program.hpp"

namespace tnv::hil {

struct PathSample {
  fw::motion::PlanePoint position_mm{};   // measured (encoder)
  fw::motion::PlanePoint reference_mm{};  // what the axis loops followed
};

struct PathScoreOptions {
  double tick_period_s = 1e-3;      // one sample per tick, no gaps
  double rest_tolerance_mm = 1e-5;  // 10 nm: telemetry rounds position and following error to 1 nm each
};

struct PathScore {
  double contour_error_max_um = 0.0;
  double contour_error_mean_um = 0.0;
  double contour_error_std_um = 0.0;  // population standard deviation
  double path_deviation_max_um = 0.0;
  double accel_ratio_max = 0.0;
  double jerk_ratio_max = 0.0;
  double feed_ratio = 0.0;
  double cycle_time_s = 0.0;
  std::size_t window_samples = 0;  // samples in the motion window (0: the reference never moved)
  std::size_t window_begin = 0;    // index of the window's first sample
};

// `limits`: the axis path limits the node planned with (accel_ratio_max and
// jerk_ratio_max divide by them).
PathScore score_path(const gcode::GcodeProgram& program, std::span<const PathSample> samples,
                     const fw::motion::MotionLimits& limits, const PathScoreOptions& options = {});

}  // namespace tnv::hil
