#pragma once
// The host's side of the conversation with one node: parameters by id,
// commands with their acknowledgement checked, heartbeat tracking, and
// the capture download with gap recovery. Every wait is measured on the
// bus clock (HostBus::now), so the same code runs on SocketCAN and on the
// emulated controller. Failures throw RequestError (timeout, refusal,
// protocol) or BusError (transport).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "tools/can/bore_messages.hpp"
#include "tools/can/host_bus.hpp"
#include "tools/can/node_messages.hpp"
#include "tools/can/request_error.hpp"

namespace tnv::can_host {

struct ClientOptions {
  Micros timeout{250'000};           // per request, for its reply
  int upload_retries = 8;            // re-requests of one block without progress before giving up
  std::uint8_t upload_block_frames = 255;
  std::uint8_t host_id = 1;          // request tags carry it (1..15); the node keys staging and ownership on it
  // Before the first request that needs command ownership (commands, motions,
  // set, commit), send take_ownership; release_ownership_if_taken() gives it back.
  bool take_ownership_when_needed = true;
};

// Frames from this node other than the reply being waited for
// (telemetry, heartbeat, fault events, stale replies).
using FrameListener = std::function<void(const hal::CanFrame&, can::MessageId)>;
using UploadProgress = std::function<void(std::uint64_t done_bytes, std::uint64_t total_bytes)>;

class NodeClient {
 public:
  NodeClient(HostBus& bus, std::uint8_t node, ClientOptions options = {});

  // --- parameters: physical values (integers, booleans and enums as numbers)
  double get(const can::ParamDef& p);
  double set(const can::ParamDef& p, double value);    // returns the value read back
  double stage(const can::ParamDef& p, double value);  // returns the staged value read back
  std::uint16_t commit();                              // returns the number of this host's parameters applied
  void discard();

  // --- commands; a refusal throws RequestError(refused) naming the code
  CommandAck command(can::CommandCode code, std::uint8_t axis = 0, std::uint8_t arg = 0, double value = 0.0);
  // Command ownership (COMMAND take_ownership / release_ownership).
  CommandAck take_ownership() { return command(can::CommandCode::take_ownership); }
  CommandAck release_ownership() { return command(can::CommandCode::release_ownership); }
  // Releases ownership this client took (explicitly or when needed); no-op otherwise.
  void release_ownership_if_taken();
  bool holds_ownership() const noexcept { return owned_; }
  CommandAck move(std::uint8_t axis, double distance_mm, double speed_mm_s);
  CommandAck circle(double radius_mm, double feed_mm_s);
  // SPINDLE start / stop / speed (docs/safety.md "Spindle"); needs ownership like the motion commands.
  CommandAck spindle(can::SpindleOp op, fw::SpindleDirection direction = fw::SpindleDirection::forward,
                     double rpm = 0.0);
  CommandAck jog(std::uint8_t axis, double speed_mm_s);  // one axis' stream (JOG names its axis)
  CommandAck shaper(std::uint8_t axis, std::uint8_t type, double freq_hz, double zeta);
  // EXCITE: kind 0 step, 1 ramp (open loop), 2 sweep, 3 multisine (closed loop, band: excite.* parameters).
  CommandAck excite(std::uint8_t axis, std::uint8_t kind, double level_mm_s, double duration_s);
  // Never acknowledged; broadcast = node 0 (every node on the bus).
  void estop(bool broadcast);

  // --- boring on the board (BORE_GAUGE / BORE_INFEED, node_client_bore.cpp)
  // record a part's readings (mm; empty = no reading), query the infeeds or
  // restart the learning; a refusal throws RequestError(refused) naming the
  // result and the field.
  BoreInfeed bore(can::BoreOp op, std::uint16_t part = 0, std::optional<double> top_mm = std::nullopt,
                  std::optional<double> bottom_mm = std::nullopt);

  // --- status
  // The next heartbeat (throws a timeout naming HEARTBEAT).
  Heartbeat wait_heartbeat(Micros timeout);
  // Until a heartbeat shows the motion is over (state not dwell/moving).
  Heartbeat wait_at_rest(Micros timeout);
  // Receives and dispatches frames for `duration`.
  void pump(Micros duration);
  // Receives and dispatches frames until `done()` holds after one (true) or
  // `timeout` passes (false). For pipelined requests (program streaming).
  bool pump_until(const std::function<bool()>& done, Micros timeout);
  // Sends a frame as it is: the caller reads its answer from the listener.
  void send_raw(const hal::CanFrame& frame) { bus_.send(frame); }
  // Refreshes the node's PROGRAM_STATUS (COMMAND program_status, open to every host).
  ProgramStatus program_status();
  const std::optional<ProgramStatus>& last_program_status() const noexcept { return program_status_; }
  // The tool the node knows in the spindle (PROGRAM_TOOL, sent with every PROGRAM_STATUS): asked now.
  ProgramTool program_tool();
  const std::optional<ProgramTool>& last_program_tool() const noexcept { return program_tool_; }
  const std::optional<Heartbeat>& last_heartbeat() const noexcept { return heartbeat_; }
  const std::optional<FaultEvent>& last_fault_event() const noexcept { return fault_event_; }
  void set_listener(FrameListener listener) { listener_ = std::move(listener); }

  // --- capture
  CaptureStatus capture(can::CaptureOp op);  // arm, abort or status
  // Polls status until the recording is done (or idle with samples).
  CaptureStatus wait_capture_done(Micros timeout, Micros poll_period);
  // The whole image (status.image_bytes()), block by block; a block with a
  // gap in its sequence or a silent tail is re-requested from the first
  // missing frame.
  std::vector<std::uint8_t> upload(const CaptureStatus& status, const UploadProgress& progress = {});
  std::uint64_t upload_rerequests() const noexcept { return upload_rerequests_; }
  // Replies of the awaited kind whose tag was not the request's (stale, or
  // another host's): discarded, never taken for the answer.
  std::uint64_t replies_discarded() const noexcept { return replies_discarded_; }
  std::uint8_t host_id() const noexcept { return options_.host_id; }
  // The tag of the next request (and advances the host's 4-bit sequence).
  std::uint8_t next_tag();

  HostBus& bus() noexcept { return bus_; }
  std::uint8_t node() const noexcept { return node_; }
  const ClientOptions& options() const noexcept { return options_; }

 private:
  // Sends `request`, then receives until `match` accepts a frame of
  // message `reply` from this node; every other frame is dispatched.
  using Match = std::function<bool(const hal::CanFrame&, can::MessageId)>;
  // The reply must carry `tag` (the request's); others of its kind are counted and discarded.
  hal::CanFrame transact(const hal::CanFrame& request, std::uint8_t tag, can::MessageId reply, const Match& match,
                         const std::string& what);
  // Receives (dispatching everything from this node) until `match` accepts
  // a frame; nullopt at the deadline.
  std::optional<hal::CanFrame> wait_for(const Match& match, Micros deadline);
  void dispatch(const hal::CanFrame& frame, can::MessageId id);
  std::optional<can::MessageId> ours(const hal::CanFrame& frame) const;
  ParamReply param_op(can::ParamOp op, const can::ParamDef* p, std::uint32_t raw, const std::string& what);
  CommandAck checked(const hal::CanFrame& request, std::uint8_t tag, std::uint8_t code, const std::string& what);
  std::string timeout_text(const std::string& what, can::MessageId reply, Micros waited) const;

  HostBus& bus_;
  std::uint8_t node_;
  ClientOptions options_;
  std::optional<Heartbeat> heartbeat_;
  std::optional<FaultEvent> fault_event_;
  std::optional<ProgramStatus> program_status_;
  std::optional<ProgramTool> program_tool_;
  FrameListener listener_;
  std::uint64_t upload_rerequests_ = 0;
  std::uint64_t replies_discarded_ = 0;
  std::uint8_t sequence_ = 0;
  bool owned_ = false;  // this client's last take_ownership succeeded and was not released since
  void need_ownership();
};

}  // namespace tnv::can_host
