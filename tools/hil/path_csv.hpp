#pragma once
// tnv-hil path --csv (and the data of its --plot): one row per tick from
// the program's start: t_s, x_ref_mm, y_ref_mm, x_mm, y_mm, contour_um,
// path_speed_mm_s.
#include <string>

#include "tools/gcode/gcode_program.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {

// `run` must hold its samples (PathRunOptions::keep_samples).
std::string path_csv(const gcode::GcodeProgram& program, const PathRunResult& run);

}  // namespace tnv::hil
