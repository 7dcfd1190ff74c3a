#pragma once
// The canonical calls of a program (canon_interpreter.hpp) as the machine's
// motion queue takes them: rapids and feeds become lines in XYZ, arcs arcs
// in their plane (G17 XY, G18 ZX, G19 YZ; with an end off the plane on the
// third axis: a helix, that axis moving with the angle; P turns share it
// by angle), dwells dwell segments, each checked against the firmware's
// limits (fw::motion::prepare) as the queue will check it. Refused, with
// the line: rigid tapping, a G5.1 spline and a probe move unless the run
// has a probe input (GcodeOptions::run_probe: a probe segment, and the
// program goes on from where the machine rests). Program pauses (Segment::pause,
// GcodeProgram::pauses): M0, M1 while the optional stop switch is on
// (CanonSetup::optional_stop), and M6 (a manual tool change; the tool's
// length applies to Z from the next move). Spindle commands (S, M3, M4, M5, and the stops of M6 and the
// program's end) become spindle elements (Segment::spindle) in program
// order. Counted and not sent: coolant (the table has none).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "tools/gcode/canon_interpreter.hpp"
#include "tools/gcode/gcode_program.hpp"

namespace tnv::gcode {

// Converts the calls as the interpreter makes them (a CanonSink:
// interpret_canon_to), so no call is held, only the segments. After the
// first refusal later calls are ignored.
class CanonSegmentSink {
 public:
  // The interpreter runs from `start_machine_mm` (CanonSetup::start_machine_mm).
  CanonSegmentSink(const std::array<double, 3>& start_machine_mm, const GcodeOptions& options)
      : at_{start_machine_mm[0], start_machine_mm[1], start_machine_mm[2]}, options_(options) {}
  void operator()(const CanonCall& call);
  // The run's error if it has one, else the first refusal (its file named
  // from run.files), else the program.
  GcodeResult finish(const CanonRun& run);
  // The segments so far (a probe move last while the machine runs it).
  const GcodeProgram& so_far() const { return program_; }
  bool refused() const { return refused_.has_value(); }
  // After a probe: the next segment starts where the machine rests.
  void rest_at(const std::array<double, 3>& machine_mm) { at_ = {machine_mm[0], machine_mm[1], machine_mm[2]}; }

 private:
  void convert(const CanonCall& call);  // throws the refusal (canon_segments.cpp)
  // A machine position as the motion core's point: X, Y and Z (Z within rounding of the current one is it).
  PlanePoint point(const std::array<double, 3>& machine_mm) const;
  void add(const fw::motion::Segment& segment);
  void add_pause(std::uint32_t tag, PauseReason reason, int tool);
  void add_spindle(std::uint32_t tag);

  struct Refused {
    int line = 0;
    std::uint32_t file = 0;
    std::string message;
  };
  PlanePoint at_;  // machine coordinates, mm (X, Y, Z)
  const GcodeOptions& options_;
  double feed_mm_min_ = 0.0;
  int spindle_direction_ = 0;  // 1 M3, -1 M4, 0 stopped (M5, M6, the program's end)
  double spindle_rpm_ = 0.0;   // the last S
  // The last spindle command sent; none yet: the first is sent whatever it is (the
  // spindle may turn from before the program).
  std::optional<std::pair<fw::motion::SpindleChange, double>> sent_spindle_;
  GcodeProgram program_;
  std::optional<Refused> refused_;
};

// `canon` ran from `start_machine_mm` (CanonSetup::start_machine_mm); its
// error, if any, is the result's. Uses the options' rapid feed and limits.
GcodeResult canon_segments(const CanonResult& canon, const std::array<double, 3>& start_machine_mm,
                           const GcodeOptions& options);

}  // namespace tnv::gcode
