#include "tools/score/path_score.hpp"

#include <algorithm>
#include <cmath>

#include "tools/gcode/path_distance.hpp"
#include "tools/score/contour_stats.hpp"

namespace tnv::hil {

using fw::motion::PlanePoint;

namespace {

// Over every axis (a plunge is motion too); hypot(h, 0) is h exactly, so Z held changes nothing.
double distance_mm(const PlanePoint& a, const PlanePoint& b) noexcept {
  double d = std::hypot(a[0] - b[0], a[1] - b[1]);
  for (std::size_t i = 2; i < a.size(); ++i) d = std::hypot(d, a[i] - b[i]);
  return d;
}

}  // namespace

PathScore score_path(const gcode::GcodeProgram& program, std::span<const PathSample> samples,
                     const fw::motion::MotionLimits& limits, const PathScoreOptions& options) {
  PathScore score;
  const std::size_t n = samples.size();
  if (n < 2) return score;
  const PlanePoint& first_ref = samples.front().reference_mm;
  const PlanePoint& last_ref = samples.back().reference_mm;
  std::size_t begin = n;
  for (std::size_t k = 0; k < n && begin == n; ++k)
    if (distance_mm(samples[k].reference_mm, first_ref) > options.rest_tolerance_mm) begin = k > 0 ? k - 1 : 0;
  if (begin == n) return score;  // never moved
  std::size_t end = begin;
  for (std::size_t k = n; k-- > begin;)
    if (distance_mm(samples[k].reference_mm, last_ref) > options.rest_tolerance_mm) {
      end = std::min(k + 1, n - 1);
      break;
    }

  const gcode::ProgrammedPath path(program.geometry);
  ContourAccumulator contour;
  for (std::size_t k = begin; k <= end; ++k) {
    contour.add(path.distance_mm(samples[k].position_mm));
    score.path_deviation_max_um = std::max(score.path_deviation_max_um, path.distance_mm(samples[k].reference_mm) * 1e3);
  }
  const ContourStats stats = contour.stats();
  score.contour_error_max_um = stats.max_um;
  score.contour_error_mean_um = stats.mean_um;
  score.contour_error_std_um = stats.std_um;
  score.window_samples = stats.samples;
  score.window_begin = begin;

  // Backward differences of the reference over every sample, as the motion tests measure them.
  const double dt = options.tick_period_s;
  for (std::size_t k = 3; k < n; ++k) {
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const double x0 = samples[k].reference_mm[i], x1 = samples[k - 1].reference_mm[i];
      const double x2 = samples[k - 2].reference_mm[i], x3 = samples[k - 3].reference_mm[i];
      const double a = (x0 - 2.0 * x1 + x2) / (dt * dt);
      const double j = (x0 - 3.0 * x1 + 3.0 * x2 - x3) / (dt * dt * dt);
      score.accel_ratio_max = std::max(score.accel_ratio_max, std::fabs(a) / limits.axis[i].accel_mm_s2);
      score.jerk_ratio_max = std::max(score.jerk_ratio_max, std::fabs(j) / limits.axis[i].jerk_mm_s3);
    }
  }
  score.cycle_time_s = static_cast<double>(end - begin) * dt;
  if (score.cycle_time_s > 0.0) score.feed_ratio = program.programmed_time_s() / score.cycle_time_s;
  return score;
}

}  // namespace tnv::hil
