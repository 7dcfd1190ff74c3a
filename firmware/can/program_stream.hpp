#pragma once
// Programs streamed by the command owner over CAN. A SEGMENT is a dwell by
// itself or waits for its SEGMENT_TAIL (same tag, same host); the complete
// element goes to the tick task's motion queue. Every element is answered
// by one COMMAND_ACK whose code is the queue's free slots after it (flow
// control, also in every HEARTBEAT); a refusal names the field at fault and
// leaves the queue as it was. PROGRAM_STATUS carries state, progress and
// underruns (ProgramTracker; docs/motion.md "Streaming"), PROGRAM_TOOL beside
// it the tool in the spindle: a tool_change element's tool once COMMAND
// cycle_start continues it, unknown from start-up and while a change is
// under way (the operator may have taken the old tool out).
//
// Bounded work, no allocation, exceptions, locks or logging: it runs in
// CanNode::service().
#include <array>
#include <cstdint>

#include "firmware/can/command_ack.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/node_transmit.hpp"
#include "firmware/can/program_tracker.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/can/segment_wire.hpp"
#include "firmware/motion/segment_queue.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

// A tool_change element: the program's element number and the tool it puts in.
struct ToolChange {
  std::uint32_t element = 0;
  std::int32_t tool = 0;
};

class ProgramStream {
 public:
  ProgramStream(std::uint8_t node_id, TickTask& task, const HostAccess& access, CommandAck& ack,
                NodeTransmit& tx) noexcept
      : node_id_(node_id), task_(task), access_(access), ack_(ack), tx_(tx) {}
  ProgramStream(const ProgramStream&) = delete;
  ProgramStream& operator=(const ProgramStream&) = delete;

  // SEGMENT / SEGMENT_TAIL of the request being handled, answered here.
  // True when an element was accepted (motion asked for and accepted).
  bool segment(const hal::CanFrame& frame) noexcept;
  bool segment_tail(const hal::CanFrame& frame) noexcept;
  // SEGMENT_Z: Z's end point of the SEGMENT waiting for its tail; answered only when refused.
  bool segment_z(const hal::CanFrame& frame) noexcept;
  // SEGMENT_PLANE: the plane and Z's end point of the arc waiting for its tail; answered only when refused.
  bool segment_plane(const hal::CanFrame& frame) noexcept;
  // COMMAND feed_hold, feed_resume, feed_override, end_program,
  // abort_program, program_status and cycle_start (the caller answers; `detail` = index
  // of the offending field).
  ErrorCode command(CommandCode code, const hal::CanFrame& frame, std::uint8_t& detail) noexcept;

  // A stop of the running program was asked for (stop, host timeout).
  void stopping() noexcept;
  // The owner let go (release, timeout): its half-received element is dropped.
  void drop_pending() noexcept { pending_.active = false; }
  // A new tick: PROGRAM_STATUS when the program's state changed.
  void on_tick() noexcept;
  // A heartbeat went out: PROGRAM_STATUS with it while a program is active.
  void on_heartbeat() noexcept;

  std::uint8_t free_slots() const noexcept;  // the motion queue's, at most 255
  const ProgramTracker& tracker() const noexcept { return program_; }
  bool segment_pending() const noexcept { return pending_.active; }  // a SEGMENT waits for its tail
  // The tool in the spindle as PROGRAM_TOOL reports it; kToolUnknown when the node does not know.
  static constexpr std::int32_t kToolUnknown = -1;
  std::int32_t tool_in_spindle() const noexcept { return tool_; }

 private:
  bool push_element(const SegmentHead& head, const hal::CanFrame* tail, std::uint8_t request) noexcept;
  void refuse_pending() noexcept;  // a SEGMENT whose tail never came: answered not_ready
  void send_status() noexcept;
  void send_probe_result() noexcept;  // PROBE_RESULT, PROBE_RESULT_Z, PROBE_REST of the last probe outcome
  // The tool change accepted as element `element`, or nullptr.
  const ToolChange* tool_change_at(std::uint32_t element) const noexcept;

  struct PendingSegment {
    bool active = false;
    std::uint8_t tag = 0;
    SegmentHead head{};
  };

  std::uint8_t node_id_;
  TickTask& task_;
  const HostAccess& access_;
  CommandAck& ack_;
  NodeTransmit& tx_;
  PendingSegment pending_{};  // the owner's SEGMENT waiting for its SEGMENT_TAIL
  ProgramTracker program_{};
  // This program's tool changes not yet continued: at most the queue's elements and the one paused at.
  std::array<ToolChange, motion::kSegmentQueueCapacity + 1> tool_changes_{};
  std::size_t tool_change_count_ = 0;
  std::int32_t tool_ = kToolUnknown;  // a restart forgets the tool: never guessed
  std::uint32_t probe_sent_count_ = 0;  // the tick task's probe report count last sent
};

}  // namespace tnv::fw::can
