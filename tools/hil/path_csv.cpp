#include "tools/hil/path_csv.hpp"

#include <cstdio>

#include "tools/gcode/path_distance.hpp"

namespace tnv::hil {

std::string path_csv(const gcode::GcodeProgram& program, const PathRunResult& run) {
  const gcode::ProgrammedPath path(program.geometry);
  std::string out = "t_s,x_ref_mm,y_ref_mm,x_mm,y_mm,contour_um,path_speed_mm_s\n";
  char line[256];
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    const PathSample& s = run.samples[k];
    const double speed = k > 0 && k - 1 < run.path_speed_mm_s.size() ? run.path_speed_mm_s[k - 1] : 0.0;
    std::snprintf(line, sizeof line, "%.3f,%.9f,%.9f,%.9f,%.9f,%.5f,%.6f\n", static_cast<double>(k) * 1e-3,
                  s.reference_mm[0], s.reference_mm[1], s.position_mm[0], s.position_mm[1],
                  path.distance_mm(s.position_mm) * 1e3, speed);
    out += line;
  }
  return out;
}

}  // namespace tnv::hil
