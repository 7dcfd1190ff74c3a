#include "tools/gcode/probe_outcome.hpp"

#include <string>

namespace tnv::gcode {

namespace {

const char* g_code(fw::motion::ProbeKind kind) {
  using fw::motion::ProbeKind;
  switch (kind) {
    case ProbeKind::toward_or_error: return "G38.2";
    case ProbeKind::toward: return "G38.3";
    case ProbeKind::away_or_error: return "G38.4";
    case ProbeKind::away: return "G38.5";
    case ProbeKind::none: break;
  }
  return "G38.x";
}

}  // namespace

ProbeRun probe_run(fw::motion::ProbeOutcome outcome, fw::motion::ProbeKind kind, const std::array<double, 3>& trip_mm,
                   const std::array<double, 3>& rest_mm) {
  using fw::motion::ProbeOutcome;
  ProbeRun run;
  run.tripped = outcome == ProbeOutcome::tripped;
  run.trip_mm = trip_mm;
  run.rest_mm = rest_mm;
  const bool toward = kind == fw::motion::ProbeKind::toward_or_error || kind == fw::motion::ProbeKind::toward;
  switch (outcome) {
    case ProbeOutcome::tripped:
    case ProbeOutcome::not_tripped: break;
    case ProbeOutcome::failed:
      run.error = std::string(g_code(kind)) + " reached its end " +
                  (toward ? "without the probe touching" : "with the probe still touching") +
                  "; the program stops here";
      break;
    case ProbeOutcome::already_tripped:
      run.error = std::string(g_code(kind)) + " refused: the probe " + (toward ? "already touches" : "does not touch") +
                  " at the start of the move; the program stops here";
      break;
    case ProbeOutcome::none: run.error = std::string(g_code(kind)) + ": the machine reported no outcome"; break;
  }
  return run;
}

ProbeRun untouched_probe(const GcodeProgram& so_far) {
  ProbeRun run;
  run.rest_mm = so_far.segments.back().end_mm;
  run.trip_mm = run.rest_mm;
  return run;
}

}  // namespace tnv::gcode
