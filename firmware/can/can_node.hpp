#pragma once
// The node's CAN service: parameters, commands, heartbeat, telemetry and
// on-target capture over the protocol of protocol_messages.hpp.
//
// Threading and timing: service() runs once after every tick(), in the
// same thread, never inside it. Everything it applies (a committed
// parameter set, a command) therefore lands between two ticks, whole; a
// tick never sees half of it. service() does bounded work (at most
// kMaxRxPerService received frames, kMaxTxPerService sent frames), does not
// allocate, throw, lock or log. Storage (save/load) is posted to a
// hal::StorageWorker that does the I/O off the real-time thread; the
// COMMAND_ACK goes out in the service() that sees the job done. Without a
// worker (unit tests) the job runs inside service(), as before.
//
// Per new tick (TickTask::last_record().tick advanced since the last call)
// service() records the capture sample, counts the telemetry periods and
// the host timeout, and notices a newly latched fault (FAULT_EVENT, once).
// Calling service() more than once per tick only handles more frames.
//
// Hosts: every answered request carries a tag (request_tag.hpp) naming its
// host (1..15); the reply echoes it. Each host has its own staged
// parameter set (host_staged_sets.hpp). Commands that move or change the
// machine need command ownership, taken and released explicitly
// (COMMAND take_ownership / release_ownership) and lost when its host is
// silent for can.host_timeout_ms; reads are open to every host (HostAccess).
//
// Transmit order: every frame goes through a priority queue
// (NodeTransmit, tx_priority_queue.hpp) and leaves in CAN-id order; telemetry is dropped
// first when it is full, a capture upload only goes out when nothing else
// waits.
//
// Programs: the command owner streams elements (SEGMENT, SEGMENT_TAIL) into
// the tick task's motion queue; each complete or refused element is
// answered with the queue's free slots (flow control, also in every
// HEARTBEAT); PROGRAM_STATUS reports progress and underruns
// (ProgramStream, program_stream.hpp; docs/motion.md "Streaming").
//
// Parts (docs/architecture.md "CAN node"): CanNode is the dispatcher.
// It reads and routes the frames and owns the parts, each a class with its
// own state that gets what it uses from the others as references:
// NodeTransmit (every frame out), HostAccess (tag, host, ownership),
// CommissioningMode, CommandAck, NodeStorage (save / load),
// ShaperDesignDeferral, NodeParameters (the live set, its one path of
// change, PARAM_REQUEST), NodeTelemetry (heartbeat, telemetry,
// FAULT_EVENT), ProgramStream (programs) and NodeCapture; and the request
// handlers: CommandRequest (COMMAND), MotionRequests (JOG, MOVE, CIRCLE),
// TuningRequests (SHAPER, EXCITE), SpindleRequest (SPINDLE),
// BoreGaugeRequest (BORE_GAUGE), StorageRequests (save / load answered)
// and MotionAcceptance (what every accepted motion request clears).
// Every rule above holds for every part.
//
// Size: the node holds the capture buffer (NodeCapture's recorder,
// kCaptureCapacityWords 32-bit words, 512 KiB), its last member: give the
// node static storage or build it on the heap.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "firmware/can/bore_gauge_request.hpp"
#include "firmware/can/capture_channels.hpp"
#include "firmware/can/command_ack.hpp"
#include "firmware/can/command_request.hpp"
#include "firmware/can/commissioning_mode.hpp"
#include "firmware/can/host_access.hpp"
#include "firmware/can/motion_acceptance.hpp"
#include "firmware/can/motion_requests.hpp"
#include "firmware/can/node_capture.hpp"
#include "firmware/can/node_parameters.hpp"
#include "firmware/can/node_settings.hpp"
#include "firmware/can/node_storage.hpp"
#include "firmware/can/node_telemetry.hpp"
#include "firmware/can/node_transmit.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/program_stream.hpp"
#include "firmware/can/protocol_messages.hpp"
#include "firmware/can/staged_params.hpp"
#include "firmware/can/shaper_design_cache.hpp"
#include "firmware/can/shaper_design_deferral.hpp"
#include "firmware/can/spindle_request.hpp"
#include "firmware/can/storage_jobs.hpp"
#include "firmware/can/storage_requests.hpp"
#include "firmware/can/host_staged_sets.hpp"
#include "firmware/can/telemetry_scheduler.hpp"
#include "firmware/can/tuning_requests.hpp"
#include "firmware/tick/tick_task.hpp"
#include "hal/can_port.hpp"
#include "hal/param_storage.hpp"
#include "hal/storage_worker.hpp"

namespace tnv::fw::can {

// A saturated 1 Mbit/s wire delivers up to 21 frames per ms (47-bit frames):
// reading more than that per tick keeps the receive FIFO from overflowing
// (an e-stop could be among the frames lost; docs/safety.md "Bus flood").
inline constexpr int kMaxRxPerService = 24;
// kMaxTxPerService: node_transmit.hpp.

struct NodeCounters {
  std::uint64_t rx_frames = 0;       // frames addressed to this node (or broadcast) and handled
  std::uint64_t rx_ignored = 0;      // frames for other nodes, from other nodes, or not ours
  std::uint64_t rx_malformed = 0;    // answered with an error code (bad length, unknown op, ...)
  // The transmit side's (NodeTransmit::counters()):
  std::uint64_t tx_frames = 0;
  std::uint64_t tx_dropped = 0;      // the transmit queue was full (telemetry_dropped included)
  std::uint64_t telemetry_dropped = 0;  // telemetry frames dropped to make room (or for want of it)
  std::uint64_t requests_refused = 0;
};

class CanNode {
 public:
  // `task` must have been built from settings.firmware; settings must pass
  // validate(). storage_fault: the start-up load failed (shown in the
  // heartbeat until a save or load succeeds). The constructor brings the
  // task in line with `settings` (controller per axis, enabled shapers);
  // the task must be at rest (it is, right after construction).
  // `previous_storage`: the generation saved before the current one (see
  // param_fallback.hpp), read by load_params when the current image fails.
  // `storage_worker`: runs save/load off the real-time thread (nullptr: in
  // service()). The first node built computes the defaults restore_defaults
  // copies (the PID tuning takes milliseconds: never in service()).
  CanNode(TickTask& task, hal::CanPort& can, hal::ParamStorage& storage, const NodeSettings& settings,
          bool storage_fault = false, hal::ParamStorage* previous_storage = nullptr,
          hal::StorageWorker* storage_worker = nullptr) noexcept;
  CanNode(const CanNode&) = delete;
  CanNode& operator=(const CanNode&) = delete;

  void service() noexcept;

  // Local permission for COMMAND enter_commissioning (docs/safety.md
  // "Commissioning"): without it the node answers not_permitted. Allowed
  // unless the integration says otherwise (tnv-fw: [safety] allow_commissioning).
  void allow_commissioning(bool allowed) noexcept;
  // In commissioning mode: safety parameters may change.
  bool commissioning() const noexcept;

  // The live parameter set (what PARAM_REQUEST get reads back).
  const NodeSettings& settings() const noexcept;
  // The id this node answers to: settings().can.node_id at construction
  // (a changed node id applies at the next start).
  std::uint8_t node_id() const noexcept;
  NodeCounters counters() const noexcept;  // the receive side's and the transmit side's

  // --- inspection (tests and the in-process emulated controller)
  std::uint16_t heartbeat_errors() const noexcept;  // HEARTBEAT.errors if one were sent now
  std::uint8_t heartbeat_axes() const noexcept;     // HEARTBEAT.axes if one were sent now
  CaptureState capture_state() const noexcept;
  std::uint32_t capture_samples() const noexcept;
  ChannelMask capture_channel_mask() const noexcept;  // channels of the current / last capture
  // The capture image as 32-bit words: samples x channels, sample-major,
  // channels in bit order (CAPTURE_DATA carries these little-endian).
  std::span<const std::uint32_t> capture_words() const noexcept;
  std::size_t staged_count() const noexcept;  // parameters waiting for commit, all hosts
  std::size_t staged_count(std::uint8_t host) const noexcept;  // the host's own pending set
  std::uint8_t owner() const noexcept;  // host id holding command ownership, 0 none
  std::size_t tx_pending() const noexcept;  // frames waiting in the priority queue
  bool storage_fault() const noexcept;
  bool params_unsaved() const noexcept;
  bool storage_in_flight() const noexcept;  // a save or load posted to the worker, not answered yet
  bool design_in_flight() const noexcept { return design_.pending(); }  // a request waits for shaper designs
  std::uint16_t reply_sequence() const noexcept;  // requests answered (mod 65536)
  const ProgramTracker& program() const noexcept { return programs_.tracker(); }
  // The tool in the spindle as PROGRAM_TOOL reports it (ProgramStream::kToolUnknown: not known).
  std::int32_t tool_in_spindle() const noexcept { return programs_.tool_in_spindle(); }
  bool segment_pending() const noexcept { return programs_.segment_pending(); }  // a SEGMENT waits for its tail

 private:
  // service() steps
  std::uint32_t on_new_tick(std::uint64_t ticks) noexcept;  // returns the telemetry due
  void receive() noexcept;
  // one frame addressed to this node (or an accepted broadcast)
  void handle(const hal::CanFrame& frame, const MessageDef& m) noexcept;
  void dispatch(const hal::CanFrame& frame, MessageId id) noexcept;  // to the handler of its message
  void collect_worker() noexcept;  // service() step: finishes a job the worker has finished
  // A request deferred for its shaper designs (ShaperDesignDeferral), dispatched again now they are made.
  void finish_design() noexcept;

  TickTask& task_;
  hal::CanPort& can_;
  std::uint8_t node_id_;                // settings.can.node_id at construction
  HostAccess access_{};                 // the request's tag and host, command ownership
  CommissioningMode commissioning_;     // safety parameters writable
  NodeTransmit tx_;                     // the priority queue, the budget, the answers' count
  CommandAck ack_;                      // COMMAND_ACK, the answer of most requests
  ProgramStream programs_;              // SEGMENT streaming and PROGRAM_STATUS
  NodeStorage storage_;                 // save / load on the worker, storage fault, unsaved
  ShaperDesignDeferral design_;         // a request waiting for the shaper designs made on the worker
  NodeParameters params_;               // the live set, its one path of change, PARAM_REQUEST
  NodeTelemetry telemetry_;             // HEARTBEAT, the cyclic telemetry, FAULT_EVENT
  MotionAcceptance motion_;             // leaves commissioning, clears the sticky heartbeat bits
  StorageRequests storage_requests_;    // COMMAND save_params / load_params, answered when done
  CommandRequest commands_;             // COMMAND
  MotionRequests motions_;              // JOG, MOVE, CIRCLE
  TuningRequests tuning_;               // SHAPER, EXCITE
  SpindleRequest spindle_;              // SPINDLE
  BoreGaugeRequest bore_;               // BORE_GAUGE, BORE_INFEED
  NodeCounters counters_{};             // the receive side's (the tx_ fields are tx_'s)
  std::uint64_t last_tick_ = 0;
  NodeCapture capture_;                 // last: it holds the big buffer
};

}  // namespace tnv::fw::can
