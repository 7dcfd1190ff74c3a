// CanNode: construction, the service() loop, receive routing, heartbeat
// and telemetry. Requests are handled in can_node_commands.cpp,
// can_node_excite.cpp, can_node_boring.cpp and by the parts
// (NodeParameters, ProgramStream, NodeCapture).
#include "firmware/can/can_node.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/request_tag.hpp"
#include "firmware/can/tick_signals.hpp"

namespace tnv::fw::can {

using namespace fields;

CanNode::CanNode(TickTask& task, hal::CanPort& can, hal::ParamStorage& storage, const NodeSettings& settings,
                 bool storage_fault, hal::ParamStorage* previous_storage,
                 hal::StorageWorker* storage_worker) noexcept
    : task_(task),
      can_(can),
      node_id_(static_cast<std::uint8_t>(settings.can.node_id)),
      commissioning_(task),
      tx_(can),
      ack_(node_id_, task, access_, tx_),
      programs_(node_id_, task, access_, ack_, tx_),
      storage_(storage, previous_storage, storage_worker, storage_fault),
      design_(storage_worker),
      params_(node_id_, task, access_, commissioning_, tx_, storage_, design_, capture_, settings),
      capture_(node_id_, task, access_, tx_) {
  last_tick_ = task_.last_record().tick;
  deadman_stops_seen_ = task_.jog_deadman_stops();
  bus_errors_at_heartbeat_ = task_.counters().bus_errors;
  late_ticks_at_heartbeat_ = task_.counters().late_ticks;
  can_errors_at_heartbeat_ = can_.error_frames();
}

const NodeSettings& CanNode::settings() const noexcept { return params_.settings(); }
std::uint8_t CanNode::node_id() const noexcept { return node_id_; }
NodeCounters CanNode::counters() const noexcept {
  NodeCounters c = counters_;
  const TxCounters& t = tx_.counters();
  c.rx_malformed += t.unknown_commands;  // answered unknown_command: malformed too
  c.tx_frames = t.tx_frames;
  c.tx_dropped = t.tx_dropped;
  c.telemetry_dropped = t.telemetry_dropped;
  c.requests_refused = t.requests_refused;
  return c;
}
CaptureState CanNode::capture_state() const noexcept { return capture_.recorder().state(); }
std::uint32_t CanNode::capture_samples() const noexcept { return capture_.recorder().samples(); }
std::uint32_t CanNode::capture_channel_mask() const noexcept { return capture_.recorder().channel_mask(); }
std::span<const std::uint32_t> CanNode::capture_words() const noexcept { return capture_.recorder().words(); }
std::size_t CanNode::staged_count() const noexcept { return params_.staged_count(); }
std::size_t CanNode::staged_count(std::uint8_t host) const noexcept { return params_.staged_count(host); }
std::uint8_t CanNode::owner() const noexcept { return access_.owner(); }
void CanNode::allow_commissioning(bool allowed) noexcept { commissioning_.allow(allowed); }
bool CanNode::commissioning() const noexcept { return commissioning_.active(); }
std::size_t CanNode::tx_pending() const noexcept { return tx_.pending(); }
bool CanNode::storage_fault() const noexcept { return storage_.fault(); }
bool CanNode::params_unsaved() const noexcept { return storage_.unsaved(); }
bool CanNode::storage_in_flight() const noexcept { return storage_.pending(); }
std::uint16_t CanNode::reply_sequence() const noexcept { return tx_.sequence(); }

bool CanNode::moving() const noexcept { return task_.moving(); }

void CanNode::service() noexcept {
  tx_.begin_service();
  std::uint32_t due = 0;
  const std::uint64_t tick = task_.last_record().tick;
  if (tick != last_tick_) {
    const std::uint64_t ticks = tick - last_tick_;
    last_tick_ = tick;
    due = on_new_tick(ticks);
  }
  tx_.flush();
  commissioning_.refresh();
  collect_worker();
  receive();
  check_fault();
  commissioning_.refresh();
  send_telemetry(due);
  tx_.flush();
  capture_.send_upload();
}

std::uint32_t CanNode::on_new_tick(std::uint64_t ticks) noexcept {
  capture_.on_tick(params_.settings());
  check_fault();
  programs_.on_tick();
  if (const std::uint32_t stops = task_.jog_deadman_stops(); stops != deadman_stops_seen_) {
    deadman_stops_seen_ = stops;
    jog_deadman_ = true;
  }
  // Host timeout: no valid frame from the owner for can.host_timeout_ms -> it loses command
  // ownership, and motion (which only the owner may have started) comes to a controlled stop.
  if (access_.owner_timed_out(ticks, params_.settings().can.host_timeout_ms)) {
    programs_.drop_pending();
    if (task_.moving() && !task_.stopping()) {
      programs_.stopping();
      task_.stop();
      host_timeout_ = true;
    }
  }
  return telemetry_.advance(params_.settings().telemetry, ticks);
}

void CanNode::check_fault() noexcept {
  const FaultRecord& f = task_.fault();
  if (!f.active()) {
    fault_reported_ = false;
    return;
  }
  if (fault_reported_) return;
  fault_reported_ = true;
  hal::CanFrame frame = make_frame(kFaultEventMsg, node_id_);
  write_raw(frame, kFaultReason, static_cast<std::uint32_t>(f.reason));
  write(frame, kFaultAxis, f.axis);
  write_raw(frame, kFaultTick, static_cast<std::uint32_t>(f.tick & 0xFFFFu));
  write(frame, kFaultValue, f.value);
  tx_.queue(frame, false);
}

// --- receive

void CanNode::receive() noexcept {
  for (int n = 0; n < kMaxRxPerService; ++n) {
    hal::CanFrame frame;
    if (!can_.try_receive(frame)) return;
    const MessageDef* m = classify(frame);  // nullptr: extended, remote or no such message
    const std::uint8_t node = node_of(frame.id);
    const bool broadcast = node == kBroadcastNode;
    if (m == nullptr || m->direction != Direction::to_node || (!broadcast && node != node_id_)) {
      ++counters_.rx_ignored;
      continue;
    }
    if (broadcast) {
      // Only e-stop and a well-formed stop command are accepted on node 0.
      const bool stop = m->id == kCommandMsg.id && frame.dlc == kCommandMsg.dlc &&
                        read_raw(frame, kCommandCode) == static_cast<std::uint32_t>(CommandCode::stop);
      if (m->id != static_cast<std::uint8_t>(MessageId::estop) && !stop) {
        ++counters_.rx_ignored;
        continue;
      }
    }
    handle(frame, *m);
  }
}

void CanNode::handle(const hal::CanFrame& frame, const MessageDef& m) noexcept {
  ++counters_.rx_frames;
  const auto id = static_cast<MessageId>(m.id);
  if (id == MessageId::estop) {  // whatever its length, from anyone
    task_.estop();
    return;
  }
  // Every other to-node message starts with its tag (byte 0); a frame too
  // short to hold one is answered with tag 0.
  access_.begin_request(frame.dlc > 0 ? frame.data[0] : 0, node_of(frame.id) == kBroadcastNode);
  const auto refuse = [&](ErrorCode e) noexcept {
    switch (id) {
      case MessageId::param_request: params_.reply(e, 0, 0); return;
      case MessageId::capture_control: capture_.reply(e); return;
      case MessageId::bore_gauge: reply_bore(e, 0); return;
      default: ack_.send(m.id, 0, e, 0); return;
    }
  };
  if (frame.dlc != m.dlc) {
    ++counters_.rx_malformed;
    return refuse(ErrorCode::bad_length);
  }
  const std::uint8_t host = access_.host();
  // Host 0 is anonymous: only the broadcast stop (checked in receive()) may come from it.
  if (host == kAnonymousHost && !access_.broadcast()) {
    ++counters_.rx_malformed;
    return refuse(ErrorCode::no_host);
  }
  access_.heard_from(host);  // a valid frame: from the owner, its silence ends
  dispatch(frame, id);
}

void CanNode::dispatch(const hal::CanFrame& frame, MessageId id) noexcept {
  design_.begin_request(frame, id);
  switch (id) {
    case MessageId::command: handle_command(frame); return;
    case MessageId::jog: handle_jog(frame); return;
    case MessageId::move: handle_move(frame); return;
    case MessageId::circle: handle_circle(frame); return;
    case MessageId::shaper: handle_shaper(frame); return;
    case MessageId::excite: handle_excite(frame); return;
    case MessageId::param_request: params_.handle(frame); return;
    case MessageId::capture_control: capture_.control(frame, params_.settings().capture); return;
    case MessageId::bore_gauge: handle_bore(frame); return;
    case MessageId::segment:
      if (programs_.segment(frame)) motion_accepted();
      return;
    case MessageId::segment_tail:
      if (programs_.segment_tail(frame)) motion_accepted();
      return;
    default: ++counters_.rx_ignored; return;  // a to_node message this node does not know (none today)
  }
}

// --- heartbeat and telemetry

std::uint16_t CanNode::heartbeat_errors() const noexcept {
  std::uint16_t bits = 0;
  const auto set = [&bits](bool on, HeartbeatBit b) noexcept {
    if (on) bits = static_cast<std::uint16_t>(bits | b);
  };
  const TickCounters& c = task_.counters();
  set(storage_.fault(), kHbStorageFault);
  set(storage_.unsaved(), kHbParamsUnsaved);
  set(tx_.dropped_since_heartbeat(), kHbTxDropped);
  set(jog_deadman_, kHbJogDeadman);
  const CaptureState capture = capture_.recorder().state();
  set(capture == CaptureState::recording, kHbCaptureRecording);
  set(capture == CaptureState::done, kHbCaptureDone);
  set(c.bus_errors != bus_errors_at_heartbeat_, kHbBoardBusErrors);
  set(c.late_ticks != late_ticks_at_heartbeat_, kHbLateTicks);
  set(params_.staged_count() != 0, kHbParamsStaged);
  for (const hal::Axis a : hal::kAxes) set(task_.shaper_active(a), static_cast<HeartbeatBit>(kHbShaperBits[hal::index(a)]));
  set(host_timeout_, kHbHostTimeout);
  set(can_.error_frames() != can_errors_at_heartbeat_, kHbCanErrors);
  set(commissioning(), kHbCommissioning);
  for (const hal::Axis a : hal::kAxes) set(task_.homed(a), static_cast<HeartbeatBit>(kHbHomedBits[hal::index(a)]));
  return bits;
}

void CanNode::send_telemetry(std::uint32_t due) noexcept {
  if (due == 0) return;
  const TickRecord& r = task_.last_record();
  const auto emit = [this](const hal::CanFrame& frame) noexcept { tx_.queue(frame, true); };
  if ((due & cyclic_bit(Cyclic::heartbeat)) != 0) {
    hal::CanFrame f = make_frame(kHeartbeatMsg, node_id_);
    const TickCounters& c = task_.counters();
    write_raw(f, kHbState, static_cast<std::uint32_t>(task_.state()));
    write_raw(f, kHbFault, static_cast<std::uint32_t>(task_.fault().reason));
    write_raw(f, kHbErrors, heartbeat_errors());
    write_raw(f, kHbOverruns, static_cast<std::uint32_t>(std::min<std::uint64_t>(c.missed_ticks + c.late_ticks, 0xFFu)));
    write_raw(f, kHbFreeSlots, programs_.free_slots());
    write_raw(f, kHbOwner, access_.owner());
    write_raw(f, kHbTick, static_cast<std::uint32_t>(r.tick & 0xFFu));
    tx_.heartbeat_sent();
    bus_errors_at_heartbeat_ = c.bus_errors;
    late_ticks_at_heartbeat_ = c.late_ticks;
    can_errors_at_heartbeat_ = can_.error_frames();
    tx_.queue(f, false);  // never dropped for telemetry's sake
    programs_.on_heartbeat();
  }
  const auto i32_mm = [](hal::CanFrame& f, const FieldDef& field, double mm) noexcept {
    // Saturate rather than send nothing: a reading beyond +-2.1 m is off the table anyway.
    const double lim_mm = 2147483647.0 * field.scale;
    write(f, field, std::clamp(std::isfinite(mm) ? mm : 0.0, -lim_mm, lim_mm));
  };
  if ((due & cyclic_bit(Cyclic::position)) != 0) {
    hal::CanFrame f = make_frame(kPositionMsg, node_id_);
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) i32_mm(f, *kPositionFields[i], r.axis[i].position_mm);
    emit(f);
  }
  if ((due & cyclic_bit(Cyclic::following)) != 0) {
    hal::CanFrame f = make_frame(kFollowingMsg, node_id_);
    for (std::size_t i = 0; i < hal::kAxisCount; ++i)
      i32_mm(f, *kFollowingFields[i], r.axis[i].reference_mm - r.axis[i].position_mm);
    emit(f);
  }
  if ((due & cyclic_bit(Cyclic::sliding)) != 0) {
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      hal::CanFrame f = make_frame(*kSlidingMsgs[i], node_id_);
      const bool pid = task_.controller(hal::axis_from_index(i)) == ControllerKind::pid;
      write(f, kSlidingS, pid ? 0.0 : r.axis[i].s);
      write(f, kSlidingDHat, pid ? 0.0 : r.axis[i].d_hat_mm_s);
      emit(f);
    }
  }
  if ((due & cyclic_bit(Cyclic::output)) != 0) {
    hal::CanFrame f = make_frame(kOutputMsg, node_id_);
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) write_raw(f, *kOutputDacs[i], r.axis[i].dac_code);
    write(f, kOutputForce, force_n(r, params_.settings()));
    emit(f);
  }
  if ((due & cyclic_bit(Cyclic::arsc)) != 0) {
    hal::CanFrame f = make_frame(kArscMsg, node_id_);
    write_saturated(f, kArscForce, force_n(r, params_.settings()));
    write_saturated(f, kArscForceRef, r.arsc_force_ref_n);
    write_saturated(f, kArscOverride, r.feed_override);
    write_saturated(f, kArscGain, r.arsc_cutting_gain_n_per_mm_s);
    emit(f);
  }
  if ((due & cyclic_bit(Cyclic::contour)) != 0) {
    hal::CanFrame f = make_frame(kContourMsg, node_id_);
    write(f, kContour, contour_um(task_, r));
    write(f, kContourTick, static_cast<double>(std::clamp<std::int64_t>(r.motion_tick, -1, 2147483647)));
    emit(f);
  }
}

}  // namespace tnv::fw::can
