#include "tools/gcode/path_score.hpp"

#include <algorithm>
#include <cmath>

#include "tools/gcode/path_distance.hpp"

namespace tnv::gcode {

namespace {

// Per-axis speed, acceleration and jerk of the commanded reference by
// backward differences, each over its axis limit.
void score_limits(const std::vector<PathSample>& s, const fw::motion::MotionLimits& limits, double dt,
                  PathScore& out) {
  for (std::size_t k = 3; k < s.size(); ++k) {
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      const double x0 = s[k].reference_mm[i], x1 = s[k - 1].reference_mm[i];
      const double x2 = s[k - 2].reference_mm[i], x3 = s[k - 3].reference_mm[i];
      const double a = (x0 - 2.0 * x1 + x2) / (dt * dt);
      const double j = (x0 - 3.0 * x1 + 3.0 * x2 - x3) / (dt * dt * dt);
      out.accel_ratio_max = std::max(out.accel_ratio_max, std::fabs(a) / limits.axis[i].accel_mm_s2);
      out.jerk_ratio_max = std::max(out.jerk_ratio_max, std::fabs(j) / limits.axis[i].jerk_mm_s3);
    }
  }
}

}  // namespace

PathScore score_path(const GcodeProgram& program, const std::vector<PathSample>& samples,
                     const fw::motion::MotionLimits& limits, double tick_s) {
  PathScore out;
  score_limits(samples, limits, tick_s, out);
  std::size_t first = samples.size();
  std::size_t last = 0;
  for (std::size_t k = 1; k < samples.size(); ++k) {
    if (samples[k].reference_mm != samples[k - 1].reference_mm) {
      first = std::min(first, k - 1);
      last = k;
    }
  }
  if (first >= samples.size()) return out;  // nothing moved
  out.first_moving = first;
  out.cycle_time_s = static_cast<double>(last - first) * tick_s;
  if (out.cycle_time_s > 0.0) out.feed_ratio = program.programmed_time_s() / out.cycle_time_s;

  const ProgrammedPath path(program.geometry);
  double sum = 0.0;
  double sum_sq = 0.0;
  for (std::size_t k = first; k <= last; ++k) {
    const double e_um = path.distance_mm(samples[k].position_mm) * 1e3;
    const double d_um = path.distance_mm(samples[k].reference_mm) * 1e3;
    out.contour_error_max_um = std::max(out.contour_error_max_um, e_um);
    out.path_deviation_max_um = std::max(out.path_deviation_max_um, d_um);
    sum += e_um;
    sum_sq += e_um * e_um;
  }
  const auto n = static_cast<double>(last - first + 1);
  out.scored_samples = last - first + 1;
  out.contour_error_mean_um = sum / n;
  out.contour_error_std_um = std::sqrt(std::max(0.0, sum_sq / n - out.contour_error_mean_um * out.contour_error_mean_um));
  return out;
}

}  // namespace tnv::gcode
