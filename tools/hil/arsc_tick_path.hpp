#pragma once
// The programs `tnv-hil arsc tick` cuts: planner segments pushed through
// fw::TickTask::push_segment as a host (G-code, a CAN stream) would. The
// emulated milling force acts on the X feed only (emulator/milling_force.hpp,
// K delta max(v_x, 0)), so a path whose direction has an X share c sees a
// cutting gain of K delta c per mm/s of path feed: the arc changes that
// gain under the force loop, which knows nothing about the path.
//   line: along +X, in 10 mm segments;
//   arc:  the same line, a tangent counter-clockwise arc of 20 mm radius
//         turning 45 deg, then a straight line at 45 deg (c = 0.707).
//   stock-step: the line along +X cut where the tool is (emulator [stock],
//         the spindle turning; issue 27), stepping down in Z at one point by
//         a short 45 deg ramp, so the depth of cut steps (2:1 by default).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "firmware/motion/segment.hpp"

namespace tnv::hil {

enum class StudyPath : std::uint8_t { line = 0, arc = 1, stock_step = 2 };

constexpr const char* to_string(StudyPath p) noexcept {
  return p == StudyPath::arc ? "arc" : p == StudyPath::stock_step ? "stock-step" : "line";
}
std::optional<StudyPath> parse_study_path(std::string_view name) noexcept;

struct StudyProgram {
  std::vector<fw::motion::Segment> segments;
  fw::motion::PlanePoint start_mm{};
  double length_mm = 0.0;
};

// Starts at start_mm; the last point is at X = end_x_mm. The arc starts
// arc_at_x_mm along X (line path: ignored).
StudyProgram study_program(StudyPath path, const fw::motion::PlanePoint& start_mm, double end_x_mm,
                           double arc_at_x_mm, double feed_mm_s, double segment_mm);

// stock-step: along +X from start_mm at its Z; at X = step_at_x_mm down
// step_mm in Z over ramp_mm of X, then on along +X to end_x_mm.
StudyProgram stock_step_program(const fw::motion::PlanePoint& start_mm, double step_at_x_mm, double step_mm,
                                double ramp_mm, double end_x_mm, double feed_mm_s, double segment_mm);

}  // namespace tnv::hil
