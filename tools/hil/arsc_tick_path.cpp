#include "tools/hil/arsc_tick_path.hpp"

#include <cmath>
#include <numbers>

namespace tnv::hil {

namespace {

constexpr double kArcRadiusMm = 20.0;
constexpr double kArcTurnRad = std::numbers::pi / 4.0;

// Straight pieces of at most segment_mm from `from` to `to`.
void push_line(StudyProgram& p, fw::motion::PlanePoint& from, const fw::motion::PlanePoint& to, double feed_mm_s,
               double segment_mm) {
  const double length = std::hypot(to[0] - from[0], to[1] - from[1]);
  const auto pieces = static_cast<std::size_t>(std::ceil(length / segment_mm - 1e-9));
  for (std::size_t i = 1; i <= pieces; ++i) {
    const double s = static_cast<double>(i) / static_cast<double>(pieces);
    const fw::motion::PlanePoint end{from[0] + s * (to[0] - from[0]), from[1] + s * (to[1] - from[1])};
    p.segments.push_back(fw::motion::line_to(i == pieces ? to : end, feed_mm_s,
                                             static_cast<std::uint32_t>(p.segments.size() + 1)));
  }
  p.length_mm += length;
  from = to;
}

// Straight pieces of at most segment_mm in X, Y and Z from `from` to `to`.
void push_line_3d(StudyProgram& p, fw::motion::PlanePoint& from, const fw::motion::PlanePoint& to, double feed_mm_s,
                  double segment_mm) {
  double sum_sq = 0.0;
  for (std::size_t a = 0; a < hal::kAxisCount; ++a) sum_sq += (to[a] - from[a]) * (to[a] - from[a]);
  const double length = std::sqrt(sum_sq);
  const auto pieces = static_cast<std::size_t>(std::ceil(length / segment_mm - 1e-9));
  for (std::size_t i = 1; i <= pieces; ++i) {
    const double s = static_cast<double>(i) / static_cast<double>(pieces);
    fw::motion::PlanePoint end{};
    for (std::size_t a = 0; a < hal::kAxisCount; ++a) end[a] = from[a] + s * (to[a] - from[a]);
    p.segments.push_back(fw::motion::line_to(i == pieces ? to : end, feed_mm_s,
                                             static_cast<std::uint32_t>(p.segments.size() + 1)));
  }
  p.length_mm += length;
  from = to;
}

}  // namespace

StudyProgram stock_step_program(const fw::motion::PlanePoint& start_mm, double step_at_x_mm, double step_mm,
                                double ramp_mm, double end_x_mm, double feed_mm_s, double segment_mm) {
  constexpr std::size_t kX = hal::index(hal::Axis::x), kZ = hal::index(hal::Axis::z);
  StudyProgram p;
  p.start_mm = start_mm;
  fw::motion::PlanePoint at = start_mm;
  fw::motion::PlanePoint to = at;
  to[kX] = step_at_x_mm;
  push_line_3d(p, at, to, feed_mm_s, segment_mm);
  to[kX] += ramp_mm;
  to[kZ] -= step_mm;
  push_line_3d(p, at, to, feed_mm_s, segment_mm);
  to[kX] = end_x_mm;
  push_line_3d(p, at, to, feed_mm_s, segment_mm);
  return p;
}

std::optional<StudyPath> parse_study_path(std::string_view name) noexcept {
  if (name == "line") return StudyPath::line;
  if (name == "arc") return StudyPath::arc;
  if (name == "stock-step") return StudyPath::stock_step;
  return std::nullopt;
}

StudyProgram study_program(StudyPath path, const fw::motion::PlanePoint& start_mm, double end_x_mm,
                           double arc_at_x_mm, double feed_mm_s, double segment_mm) {
  StudyProgram p;
  p.start_mm = start_mm;
  fw::motion::PlanePoint at = start_mm;
  if (path == StudyPath::line) {
    push_line(p, at, {end_x_mm, start_mm[1]}, feed_mm_s, segment_mm);
    return p;
  }
  push_line(p, at, {arc_at_x_mm, start_mm[1]}, feed_mm_s, segment_mm);
  // Tangent arc to the left: centre R above the line, end after turning 45 deg.
  const fw::motion::PlanePoint centre{at[0], at[1] + kArcRadiusMm};
  const fw::motion::PlanePoint arc_end{centre[0] + kArcRadiusMm * std::sin(kArcTurnRad),
                                       centre[1] - kArcRadiusMm * std::cos(kArcTurnRad)};
  p.segments.push_back(fw::motion::arc_to(false, arc_end, centre, feed_mm_s,
                                          static_cast<std::uint32_t>(p.segments.size() + 1)));
  p.length_mm += kArcRadiusMm * kArcTurnRad;
  at = arc_end;
  const double run_mm = (end_x_mm - at[0]) / std::cos(kArcTurnRad);
  push_line(p, at, {end_x_mm, at[1] + run_mm * std::sin(kArcTurnRad)}, feed_mm_s, segment_mm);
  return p;
}

}  // namespace tnv::hil
