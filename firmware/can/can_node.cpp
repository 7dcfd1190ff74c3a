// CanNode: construction, the service() loop, receive routing and the
// dispatch of each request to the part that handles it (can_node.hpp
// "Parts"); the worker's finished jobs are collected here too: a deferred
// request is dispatched again.
#include "firmware/can/can_node.hpp"

#include <array>

#include "firmware/adaptive/boring/boring_station.hpp"

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/request_tag.hpp"

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
      telemetry_(node_id_, task, can, tx_, access_, commissioning_, storage_, params_, programs_, capture_),
      motion_(commissioning_, telemetry_),
      storage_requests_(task, access_, ack_, storage_, params_),
      commands_(task, access_, ack_, commissioning_, programs_, params_, design_, storage_requests_, motion_),
      motions_(task, access_, ack_, params_, motion_),
      tuning_(task, access_, ack_, params_, design_, capture_, motion_),
      spindle_(task, access_, ack_, programs_, motion_),
      bore_(node_id_, access_, tx_, storage_, params_),
      capture_(node_id_, task, access_, tx_) {
  last_tick_ = task_.last_record().tick;
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
ChannelMask CanNode::capture_channel_mask() const noexcept { return capture_.recorder().channel_mask(); }
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
std::uint16_t CanNode::heartbeat_errors() const noexcept { return telemetry_.heartbeat_errors(); }
std::uint8_t CanNode::heartbeat_axes() const noexcept { return telemetry_.heartbeat_axes(); }

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
  telemetry_.check_fault();
  commissioning_.refresh();
  telemetry_.send(due);
  tx_.flush();
  capture_.send_upload();
}

// The planner's infeeds for the part being cut (as BORE_INFEED tells them) at
// its gauge overhangs: what a feed per revolution along the depth follows.
static InfeedAlongOverhang depth_infeed(const NodeParameters& params) noexcept {
  const BoringStationSettings& bore = params.settings().bore;
  const std::array<double, kBoringStationPositions> s =
      current_infeeds_mm_rev(bore, params.settings().bore_state, kBoreInfeedTop.scale);
  return {bore.top_overhang_mm, s[kBoringTop], bore.bottom_overhang_mm, s[kBoringBottom]};
}

std::uint32_t CanNode::on_new_tick(std::uint64_t ticks) noexcept {
  capture_.on_tick(params_.settings());
  task_.set_depth_infeed(depth_infeed(params_));
  telemetry_.check_fault();
  programs_.on_tick();
  // Host timeout: no valid frame from the owner for can.host_timeout_ms -> it loses command
  // ownership, and motion (which only the owner may have started) comes to a controlled stop.
  if (access_.owner_timed_out(ticks, params_.settings().can.host_timeout_ms)) {
    task_.set_host_lost(true);  // the spindle stops (host_timeout) and stays off until a host starts it again
    programs_.drop_pending();
    if (task_.moving() && !task_.stopping()) {
      programs_.stopping();
      task_.stop();
      telemetry_.host_timed_out();
    }
  }
  return telemetry_.on_tick(ticks);
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
      case MessageId::bore_gauge: bore_.reply(e, 0); return;
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
    case MessageId::command: commands_.handle(frame); return;
    case MessageId::jog: motions_.jog(frame); return;
    case MessageId::move: motions_.move(frame); return;
    case MessageId::circle: motions_.circle(frame); return;
    case MessageId::shaper: tuning_.shaper(frame); return;
    case MessageId::excite: tuning_.excite(frame); return;
    case MessageId::param_request: params_.handle(frame); return;
    case MessageId::capture_control: capture_.control(frame, params_.settings().capture); return;
    case MessageId::bore_gauge: bore_.handle(frame); return;
    case MessageId::spindle: spindle_.handle(frame); return;
    case MessageId::segment:
      if (programs_.segment(frame)) motion_.accepted();
      return;
    case MessageId::segment_tail:
      if (programs_.segment_tail(frame)) motion_.accepted();
      return;
    case MessageId::segment_z: programs_.segment_z(frame); return;
    case MessageId::segment_plane: programs_.segment_plane(frame); return;
    default: ++counters_.rx_ignored; return;  // a to_node message this node does not know (none today)
  }
}

// --- the worker's jobs: a finished save / load is answered (StorageRequests);
// a request deferred for its shaper designs is dispatched again.

void CanNode::collect_worker() noexcept {
  // One job at a time (NodeParameters::worker_busy() refuses a second): the one done is the one pending.
  if (storage_.pending()) {
    if (storage_.job_done()) storage_requests_.finish();
    return;
  }
  if (design_.job_done()) finish_design();
}

void CanNode::finish_design() noexcept {
  const ShaperDesignDeferral::Replay replay = design_.finish(params_.designs());
  // The request as it came: its tag names the host (ownership is checked again).
  access_.begin_request(replay.frame.data[0], false);
  dispatch(replay.frame, replay.id);
  // Handled again it finds its designs; should it defer once more (a host
  // changed its staged set meanwhile), it is answered after that job.
}

}  // namespace tnv::fw::can
