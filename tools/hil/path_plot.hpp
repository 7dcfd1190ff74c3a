#pragma once
// tnv-hil path --plot: the programmed path with where its contour error is
// largest, the contour error against time, and the planner's path speed.
#include <string>

#include "tools/gcode/gcode_program.hpp"
#include "tools/hil/path_run.hpp"
#include "tools/hil/svg_writer.hpp"

namespace tnv::hil {

// `run` must hold its samples (PathRunOptions::keep_samples).
SvgWriter path_figure(const std::string& title, const gcode::GcodeProgram& program, const PathRunResult& run);

// The same run as CSV, one row per tick from the program's start:
// t_s, x_ref_mm, y_ref_mm, x_mm, y_mm, contour_um, path_speed_mm_s.
std::string path_csv(const gcode::GcodeProgram& program, const PathRunResult& run);

}  // namespace tnv::hil
