#pragma once
// Scores a run of a programmed path from its 1 ms samples (tnv-hil path,
// tnvctl run): the measured position against the exact programmed lines
// and arcs (contour error: distance to the nearest point of the geometry,
// not a radius), the commanded reference against them (the planner's own
// path deviation), the commanded acceleration and jerk per axis over their
// limits (backward differences of the reference, docs/motion.md "How the
// limits are measured"), and the feed ratio (programmed time over the
// cycle time).
#include <cstddef>
#include <vector>

#include "firmware/motion/motion_limits.hpp"
#include "tools/gcode/gcode_program.hpp"

namespace tnv::gcode {

struct PathSample {
  PlanePoint reference_mm{};  // x_ref,k of both axes, as the axis loops were given it
  PlanePoint position_mm{};   // measured (encoder) position
};

struct PathScore {
  double contour_error_max_um = 0.0;
  double contour_error_mean_um = 0.0;
  double contour_error_std_um = 0.0;  // population standard deviation
  double path_deviation_max_um = 0.0;
  double accel_ratio_max = 0.0;
  double jerk_ratio_max = 0.0;
  double feed_ratio = 0.0;    // programmed time (length / feed per element, dwells) / cycle time
  double cycle_time_s = 0.0;  // first tick that moves to the last one
  std::size_t scored_samples = 0;
  std::size_t first_moving = 0;  // index of the first scored sample
};

// samples: one per tick from the start of the program (the reference at
// rest before it); tick_s the sample period. The cycle runs from the first
// tick whose reference differs from the one before to the last such tick;
// the contour error is scored over it.
PathScore score_path(const GcodeProgram& program, const std::vector<PathSample>& samples,
                     const fw::motion::MotionLimits& limits, double tick_s = 1e-3);

}  // namespace tnv::gcode
