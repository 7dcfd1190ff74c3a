#include "tools/hil/path_csv.hpp"

#include <cstdio>

#include "hal/axis.hpp"
#include "tools/gcode/path_distance.hpp"

namespace tnv::hil {

namespace {

constexpr bool in_plane(hal::Axis axis) noexcept { return axis == hal::kPlaneFirst || axis == hal::kPlaneSecond; }

void cell(std::string& row, double value, const char* format) {
  char buf[48];
  std::snprintf(buf, sizeof buf, format, value);
  row.append(",").append(buf);
}

}  // namespace

std::string path_csv_header() {
  std::string out = "t_s,x_ref_mm,y_ref_mm,x_mm,y_mm,contour_um,path_speed_mm_s";
  for (const hal::Axis axis : hal::kAxes) {
    if (in_plane(axis)) continue;
    const std::string n = hal::axis_label(axis);
    out.append(",").append(n).append("_ref_mm,").append(n).append("_mm");
  }
  return out;
}

std::string path_csv(const gcode::GcodeProgram& program, const PathRunResult& run) {
  constexpr std::size_t kP = hal::index(hal::kPlaneFirst);
  constexpr std::size_t kQ = hal::index(hal::kPlaneSecond);
  const gcode::ProgrammedPath path(program.geometry);
  std::string out = path_csv_header();
  out += '\n';
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    const PathSample& s = run.samples[k];
    const double speed = k > 0 && k - 1 < run.path_speed_mm_s.size() ? run.path_speed_mm_s[k - 1] : 0.0;
    char head[32];
    std::snprintf(head, sizeof head, "%.3f", static_cast<double>(k) * 1e-3);
    std::string row = head;
    cell(row, s.reference_mm[kP], "%.9f");
    cell(row, s.reference_mm[kQ], "%.9f");
    cell(row, s.position_mm[kP], "%.9f");
    cell(row, s.position_mm[kQ], "%.9f");
    cell(row, path.distance_mm(s.position_mm) * 1e3, "%.5f");
    cell(row, speed, "%.6f");
    for (const hal::Axis axis : hal::kAxes) {
      if (in_plane(axis)) continue;
      cell(row, s.reference_mm[hal::index(axis)], "%.9f");
      cell(row, s.position_mm[hal::index(axis)], "%.9f");
    }
    out.append(row).append("\n");
  }
  return out;
}

}  // namespace tnv::hil
