#pragma once
// A machine's probe outcome (firmware/motion/probe_move.hpp, as the tick
// task or PROBE_RESULT reports it) as the interpreter takes it (ProbeRun):
// the errors worded once for every run that probes (tnv-hil path, tnvctl run).
#include <array>

#include "firmware/motion/probe_move.hpp"
#include "tools/gcode/canon_interpreter.hpp"
#include "tools/gcode/gcode_program.hpp"

namespace tnv::gcode {

// `kind` is the probe segment's; positions machine coordinates, mm.
ProbeRun probe_run(fw::motion::ProbeOutcome outcome, fw::motion::ProbeKind kind, const std::array<double, 3>& trip_mm,
                   const std::array<double, 3>& rest_mm);

// A probe that does not trip: it ends at its end (#5070 0), no error. For
// GcodeOptions::run_probe where a program is checked before it runs: read
// as if no probe tripped (what follows a probe is read again as it runs).
ProbeRun untouched_probe(const GcodeProgram& so_far);

}  // namespace tnv::gcode
