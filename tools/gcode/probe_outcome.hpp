#pragma once
// A machine's probe outcome (firmware/motion/probe_move.hpp, as the tick
// task or PROBE_RESULT reports it) as the interpreter takes it (ProbeRun):
// the errors worded once for every run that probes (tnv-hil path, tnvctl run).
#include <array>

#include "firmware/motion/probe_move.hpp"
#include "tools/gcode/canon_interpreter.hpp"

namespace tnv::gcode {

// `kind` is the probe segment's; positions machine coordinates, mm.
ProbeRun probe_run(fw::motion::ProbeOutcome outcome, fw::motion::ProbeKind kind, const std::array<double, 3>& trip_mm,
                   const std::array<double, 3>& rest_mm);

}  // namespace tnv::gcode
