#pragma once
// Streams a program (program_wire.hpp) to a node with flow control, then
// ends it and waits for its end (docs/motion.md "Streaming").
//
// Flow control: the host never has more elements on their way than the
// node's motion queue can take. Its lower bound of the free slots is the
// larger of (a) the free slots in the last element's COMMAND_ACK minus the
// elements sent since, and (b) the queue's capacity minus the elements
// accepted and not yet run (PROGRAM_STATUS.segment is the one running)
// minus those in flight. Both only ever under-estimate: (a) ignores what
// ran since the ack, and an old PROGRAM_STATUS only names an earlier
// element in (b). When neither leaves room and nothing is in flight, the
// host asks for a PROGRAM_STATUS every poll period. At most `window`
// elements are unanswered at once (a tag's 4-bit sequence must not repeat
// among them), so a burst occupies the bus for at most window x 2 frames.
//
// Frames from one host reach the node in the order sent (SocketCAN keeps a
// socket's order; so does the emulated bus): a SEGMENT_TAIL always follows
// its SEGMENT, and end_program follows the last element.
//
// Program pauses (M0, M1, M6: WireElement::pause): when PROGRAM_STATUS
// says paused, on_pause is told once, and the stream waits (still asking
// for PROGRAM_STATUS now and then, which keeps the node's host timeout
// fed) until resume() says go: then COMMAND cycle_start. Without a
// resume() the run ends failed at the first pause, after an abort: a
// program never goes on by itself unless the caller asked for it.
#include <cstdint>
#include <array>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "firmware/motion/probe_move.hpp"
#include "tools/can/node_client.hpp"
#include "tools/can/program_wire.hpp"

namespace tnv::can_host {

struct StreamProgress {
  std::size_t sent = 0;          // elements sent
  std::size_t acknowledged = 0;  // elements the node accepted
  std::size_t total = 0;
  std::uint32_t running = 0;     // element the node runs (1-based)
  int line = 0;                  // its G-code line
  double fraction = 0.0;         // of the program's length run
  std::uint64_t underruns = 0;
  fw::can::ProgramState state = fw::can::ProgramState::none;
  std::optional<ProgramTool> tool;  // the node's PROGRAM_TOOL, once seen during this run
};

// A pause the node rests at.
struct StreamPause {
  std::uint32_t element = 0;  // 1-based
  int line = 0;               // its G-code line
  std::optional<gcode::ProgramPause> why;  // from the program (M0, M1, M6 and the tool)
};

// "line 12: tool change (M6), tool 3"
std::string pause_text(const StreamPause& pause);

struct StreamOptions {
  std::size_t window = 12;           // unanswered elements at most (<= 15)
  std::optional<double> feed_override;  // 0..1.5, sent once the program runs
  double expected_s = 0.0;           // programmed time: the wait for the end is 1.5 x this + 10 s
  Micros poll_period{20'000};        // PROGRAM_STATUS request while the queue is full
  std::function<bool()> interrupted;                  // Ctrl-C: abort on the path
  std::function<void(const StreamProgress&)> progress;  // on every PROGRAM_STATUS
  FrameListener on_frame;                             // every frame from the node (telemetry)
  std::function<void(std::size_t)> before_send;       // called before element k is sent (tests pause here)
  std::function<void(const StreamPause&)> on_pause;   // the node rests at a pause (once per pause)
  // Asked while paused, with the time since the pause was reported: true sends cycle_start.
  std::function<bool(const StreamPause&, Micros paused_for)> resume;
  // The operator's feed hold, asked at every look once the program runs: true brakes on the path and
  // waits there (COMMAND feed_hold), false again goes on (feed_resume). A refusal ends the run failed,
  // after an abort on the path. The wait for the end grows by the time held.
  std::function<bool()> feed_hold;
};

struct StreamResult {
  enum class End { done, interrupted, failed };
  End end = End::failed;
  std::string message;  // why it failed or was interrupted
  std::uint64_t underruns = 0;
  std::size_t sent = 0;
  std::size_t acknowledged = 0;
  std::size_t max_in_flight = 0;
  int min_free_slots = 255;     // lowest free slots an answer reported
  std::size_t queue_capacity = 0;
  double fill_elements_per_s = 0.0;  // elements accepted per second while the queue still had room
  double run_s = 0.0;           // first element sent -> end of the program (bus time), pauses included
  double paused_s = 0.0;        // time the node rested at pauses (bus time)
  double held_s = 0.0;          // time the feed was held by StreamOptions::feed_hold (bus time)
  std::vector<StreamPause> pauses;  // in the order reached
  ProgramStatus final_status{};
  std::optional<ProgramTool> final_tool;  // the node's last PROGRAM_TOOL of the run
  std::optional<Heartbeat> final_heartbeat;
};

// A probe move's outcome from the node: PROBE_RESULT with its
// PROBE_RESULT_Z and PROBE_REST (the same count). Machine coordinates, mm.
struct ProbeResult {
  std::uint8_t count = 0;
  fw::motion::ProbeOutcome outcome = fw::motion::ProbeOutcome::none;
  std::array<double, 3> trip_mm{};  // X Y Z
  std::array<double, 3> rest_mm{};
};

class Streamer;

// A stream that goes on while the program is read (a program that probes:
// what follows a probe is read only after its outcome, docs/gcode.md).
// `program` grows between calls; the elements sent stay as they are.
// Throws as stream_program.
class ProgramStreamer {
 public:
  ProgramStreamer(NodeClient& client, const WireProgram& program, const StreamOptions& options);
  ~ProgramStreamer();
  ProgramStreamer(const ProgramStreamer&) = delete;
  ProgramStreamer& operator=(const ProgramStreamer&) = delete;
  // Sends the elements not yet sent, the last of them a probe move, and
  // waits for its result (within 1.5 x expected_s + 10 s, the program's
  // time so far). nullopt: the run ended (finish() says how).
  std::optional<ProbeResult> run_to_probe(double expected_s);
  // Sends the rest, ends the program and waits for its end, as stream_program.
  StreamResult finish(double expected_s);
  // The program cannot go on (its reading stopped with an error): the run ends failed with `why`, after a
  // controlled stop on the path if the node still runs it.
  StreamResult abandon(const std::string& why);

 private:
  std::unique_ptr<Streamer> impl_;
};

// Throws RequestError / BusError for what stops the conversation itself (no
// node); refusals and lost answers end the run as `failed` after an abort
// on the path.
StreamResult stream_program(NodeClient& client, const WireProgram& program, const StreamOptions& options);

}  // namespace tnv::can_host
