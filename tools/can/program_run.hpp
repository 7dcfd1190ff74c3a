#pragma once
// `tnvctl run`'s work, for any transport: read the node's planner limits and
// where the table stands, parse the program from there with those limits,
// turn telemetry on at 1 ms (TLM_POSITION_<AXIS>), enable the
// servo, stream the program (program_stream.hpp), restore the telemetry
// periods and score the run (tools/score/path_score.hpp).
//
// Telemetry rate: 1 ms, an 8-byte frame per axis and tick (two axes: 22 %
// of 1 Mbit/s, 27 % with worst-case stuffing). The identifiers (0x401,
// 0x421, ... for node 1) lose arbitration to every control frame (FAULT_EVENT, replies,
// HEARTBEAT and the host's SEGMENT frames), and the node drops telemetry
// first when its transmit queue fills. The score needs every tick: the
// jerk and acceleration ratios are finite differences of the 1 ms
// reference. `telemetry_ms = 0` leaves telemetry as it is and scores
// nothing (for a bus with other traffic to protect).
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

#include "tools/can/node_client.hpp"
#include "tools/can/program_stream.hpp"
#include "tools/gcode/gcode_program.hpp"
#include "tools/score/path_score.hpp"

namespace tnv::can_host {

// The program cannot run from where the table stands with the node's limits:
// the message names the G-code line and column. Nothing on the node was
// changed (the telemetry periods are back as they were).
class ProgramInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ProgramRunOptions {
  double rapid_feed_mm_s = 50.0;        // G0
  gcode::CanonSetup canon{};            // tool table, parameters, subroutine path (gcode_program.hpp)
  // With canon.from_line: the tool in the spindle is the node's PROGRAM_TOOL when the node knows it
  // (asked before the parse); when it does not, canon.from_line->tool_in_spindle stands.
  bool tool_from_node = false;
  std::optional<double> feed_override;  // 0..1.5
  int telemetry_ms = 1;                 // 1: sample every tick and score; 0: no score
  std::size_t window = 12;
  std::function<bool()> interrupted;
  std::function<void(const StreamProgress&)> progress;
  std::function<void(std::size_t)> before_send;  // tests: called before element k is sent
  // Program pauses (M0, M1, M6): StreamOptions::on_pause and resume. No resume: the run stops at the first pause.
  std::function<void(const StreamPause&)> on_pause;
  std::function<bool(const StreamPause&, Micros paused_for)> resume;
  std::function<bool()> feed_hold;  // StreamOptions::feed_hold: the operator's feed hold switch
  FrameListener on_frame;  // every frame from the node too, besides the run's own telemetry (a live page's scope)
  // Changes the parsed program before it is put on the wire (a program without probes): the boring
  // pass gives its feed lines their feed per revolution (Segment::feed_mm_rev; the G-code reader has no G95).
  std::function<void(gcode::GcodeProgram&)> before_wire;
  // > 0: how long the program takes at most (s), for the wait for its end, instead of its programmed time
  // (the boring pass along the depth: the node slows its line below the programmed F).
  double expected_s = 0.0;
};

struct ProgramRunResult {
  gcode::GcodeProgram program;  // parsed from start_mm with the node's limits
  WireProgram wire;
  fw::motion::MotionLimits limits;
  fw::motion::PlanePoint start_mm{};
  StreamResult stream;
  std::vector<hil::PathSample> samples;
  // Every tick sampled: no frame dropped by the node, at most the last tick's position still
  // waiting for its following error.
  bool telemetry_complete = false;
  std::optional<hil::PathScore> score;  // when sampled (telemetry_ms 1) and the program ran to its end
};

// What run_gcode would run now, changing nothing on the node: the node's
// limits, where the table stands (from its telemetry, which must be on) and
// the program parsed from there (a refusal in parsed.error, or, for a
// program the wire cannot carry, in wire_error).
struct ProgramPlan {
  gcode::GcodeResult parsed;
  std::string wire_error;
  fw::motion::MotionLimits limits;
  fw::motion::PlanePoint start_mm{};
};

// The options with the tool in the spindle a run from line starts with:
// with tool_from_node, the node's PROGRAM_TOOL when the node knows it (asked
// now, once: tool_from_node is cleared in the result), else
// canon.from_line->tool_in_spindle as given (0, none, by default: a tool the
// start needs is then changed, a pause the operator confirms). A check
// before sending and the run itself use the same answer.
ProgramRunOptions with_node_tool(NodeClient& client, const ProgramRunOptions& options);

// Throws RequestError when the node sends no TLM_POSITION_X / _Y pair within 500 ms.
ProgramPlan plan_gcode(NodeClient& client, const std::string& gcode_text, const ProgramRunOptions& options);

// The planner's limits the node runs with (x/y.path.*, path.tolerance_mm, the soft travel limits).
fw::motion::MotionLimits node_motion_limits(NodeClient& client);

// Throws ProgramInputError (parse or wire error), RequestError / BusError
// (the node), RunFailed-like std::runtime_error for a node that is not ready
// (faulted, moving). A stream that was refused, interrupted or faulted is in
// result.stream (end != done), not thrown.
ProgramRunResult run_gcode(NodeClient& client, const std::string& gcode_text, const ProgramRunOptions& options);

}  // namespace tnv::can_host
