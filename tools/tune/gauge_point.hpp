#pragma once
// One stop of a lead-error measurement: where the machine's own encoder put
// the axis, the direction it came from, and what the reference (a laser
// interferometer or a gauge against the table) read. The file format is
// tools/hil/gauge_file.hpp; the fit is screw_fit.hpp.

namespace tnv::tune {

struct GaugePoint {
  double position_mm = 0.0;  // the axis' position as the control reads it (motor encoder)
  int direction = 1;         // +1 or -1: the direction the axis came from
  double table_mm = 0.0;     // the reference's reading of the table (any zero)
};

}  // namespace tnv::tune
