#pragma once
// tnv-hil path --csv (and the data of its --plot): one row per tick from
// the program's start: t_s, x_ref_mm, y_ref_mm, x_mm, y_mm, contour_um,
// path_speed_mm_s, then each axis beyond the XY plane from the axis list
// (hal/axis.hpp): z_ref_mm, z_mm. The plane's columns keep their place, so
// a reader of the columns before Z reads them as it did. contour_um is the
// distance to the programmed path over every axis.
#include <string>

#include "tools/gcode/gcode_program.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {

// The header line, without its newline.
std::string path_csv_header();

// `run` must hold its samples (PathRunOptions::keep_samples).
std::string path_csv(const gcode::GcodeProgram& program, const PathRunResult& run);

}  // namespace tnv::hil
