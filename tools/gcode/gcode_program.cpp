#include "tools/gcode/gcode_program.hpp"

#include <cstdio>
#include <string>
#include <string_view>

#include "tools/gcode/canon_segments.hpp"

namespace tnv::gcode {

namespace {

CanonSetup machine_setup(const GcodeOptions& options) {
  CanonSetup setup = options.canon;
  setup.start_machine_mm[0] = options.start_mm[0];
  setup.start_machine_mm[1] = options.start_mm[1];
  setup.start_machine_mm[2] = options.start_mm[2];
  setup.end_of_file_ends = true;
  // A run from line N approaches its start from where the machine is.
  if (setup.from_line) setup.from_line->machine_position_mm = setup.start_machine_mm;
  return setup;
}

}  // namespace

double GcodeProgram::programmed_length_mm() const noexcept {
  double sum = 0.0;
  for (const auto& g : geometry) sum += g.length_mm;
  return sum;
}

double GcodeProgram::programmed_time_s() const noexcept {
  double sum = 0.0;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    if (segments[k].kind == fw::motion::SegmentKind::dwell) sum += segments[k].dwell_s;
    else sum += geometry[k].length_mm / segments[k].feed_mm_s;
  }
  return sum;
}

namespace {

std::string count_of(std::size_t n, const char* what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

}  // namespace

const char* to_string(PauseReason reason) noexcept {
  switch (reason) {
    case PauseReason::program_stop: return "program stop (M0)";
    case PauseReason::optional_stop: return "optional stop (M1)";
    case PauseReason::tool_change: return "tool change (M6)";
    case PauseReason::pallet_change: return "pallet change (M60)";
  }
  return "?";
}

std::string to_string(const ProgramPause& pause) {
  std::string out = to_string(pause.reason);
  if (pause.reason == PauseReason::tool_change) out += ", tool " + std::to_string(pause.tool);
  return out;
}

std::string summary_text(const GcodeProgram& p) {
  char time[64];
  std::snprintf(time, sizeof time, "%.3f s", p.programmed_time_s());
  std::string s = count_of(p.lines_run, "line") + " run, " + count_of(p.segments.size(), "segment") + ", " +
                  count_of(p.tool_changes, "tool change") + ", programmed cycle time " + time;
  if (!p.pauses.empty()) s += ", " + count_of(p.pauses.size(), "pause");
  if (p.optional_stops_skipped > 0) s += ", " + count_of(p.optional_stops_skipped, "optional stop") + " skipped (switch off)";
  if (p.spindle_changes > 0) s += ", " + count_of(p.spindle_changes, "spindle command");
  if (p.probes > 0) s += ", " + count_of(p.probes, "probe move");
  if (p.coolant_starts > 0)
    s += "; not sent (this table has no coolant): " + count_of(p.coolant_starts, "coolant start");
  return s;
}

namespace {

// With a probe input: each probe runs the segments so far on the machine and
// the rest of the program goes on from where it rests. After a refusal
// nothing more runs (the result is the refusal).
void connect_probe(CanonSetup& setup, CanonSegmentSink& sink, const GcodeOptions& options) {
  if (!options.run_probe) return;
  setup.probe_input = [&sink, &options](const CanonCall& call) {
    if (sink.refused()) {
      ProbeRun idle;
      idle.rest_mm = call.motion.end_mm;
      return idle;
    }
    ProbeRun run = options.run_probe(sink.so_far());
    if (run.error.empty()) sink.rest_at(run.rest_mm);
    return run;
  };
}

}  // namespace

// The calls become segments as they are made: none is held.
GcodeResult parse_gcode(std::string_view text, const GcodeOptions& options) {
  CanonSetup setup = machine_setup(options);
  CanonSegmentSink sink(setup.start_machine_mm, options);
  connect_probe(setup, sink, options);
  const CanonRun run = interpret_canon_to(text, setup, [&sink](const CanonCall& call) { sink(call); });
  return sink.finish(run);
}

GcodeResult parse_gcode_file(const std::string& path, const GcodeOptions& options) {
  CanonSetup setup = machine_setup(options);
  CanonSegmentSink sink(setup.start_machine_mm, options);
  connect_probe(setup, sink, options);
  const CanonRun run = interpret_canon_file_to(path, setup, [&sink](const CanonCall& call) { sink(call); });
  return sink.finish(run);
}

}  // namespace tnv::gcode
