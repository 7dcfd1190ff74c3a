// NodeTelemetry: HEARTBEAT, the cyclic telemetry and FAULT_EVENT.
#include "firmware/can/node_telemetry.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/tick_signals.hpp"

namespace tnv::fw::can {

using namespace fields;

NodeTelemetry::NodeTelemetry(std::uint8_t node_id, const TickTask& task, const hal::CanPort& can, NodeTransmit& tx,
                             const HostAccess& access, const CommissioningMode& commissioning,
                             const NodeStorage& storage, const NodeParameters& params, ProgramStream& programs,
                             const NodeCapture& capture) noexcept
    : node_id_(node_id),
      task_(task),
      can_(can),
      tx_(tx),
      access_(access),
      commissioning_(commissioning),
      storage_(storage),
      params_(params),
      programs_(programs),
      capture_(capture),
      deadman_stops_seen_(task.jog_deadman_stops()),
      bus_errors_at_heartbeat_(task.counters().bus_errors),
      can_errors_at_heartbeat_(can.error_frames()),
      late_ticks_at_heartbeat_(task.counters().late_ticks) {}

std::uint32_t NodeTelemetry::on_tick(std::uint64_t ticks) noexcept {
  if (const std::uint32_t stops = task_.jog_deadman_stops(); stops != deadman_stops_seen_) {
    deadman_stops_seen_ = stops;
    jog_deadman_ = true;
  }
  return telemetry_.advance(params_.settings().telemetry, ticks);
}

void NodeTelemetry::check_fault() noexcept {
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

std::uint16_t NodeTelemetry::heartbeat_errors() const noexcept {
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
  set(host_timeout_, kHbHostTimeout);
  set(can_.error_frames() != can_errors_at_heartbeat_, kHbCanErrors);
  set(commissioning_.active(), kHbCommissioning);
  return bits;
}

std::uint8_t NodeTelemetry::heartbeat_axes() const noexcept {
  std::uint8_t bits = 0;
  for (const hal::Axis a : hal::kAxes) {
    if (task_.homed(a)) bits = static_cast<std::uint8_t>(bits | hb_homed_bit(a));
    if (task_.shaper_active(a)) bits = static_cast<std::uint8_t>(bits | hb_shaper_bit(a));
  }
  return bits;
}

void NodeTelemetry::send_heartbeat() noexcept {
  hal::CanFrame f = make_frame(kHeartbeatMsg, node_id_);
  const TickCounters& c = task_.counters();
  write_raw(f, kHbState, static_cast<std::uint32_t>(task_.state()));
  write_raw(f, kHbFault, static_cast<std::uint32_t>(task_.fault().reason));
  write_raw(f, kHbErrors, heartbeat_errors());
  write_raw(f, kHbOverruns, static_cast<std::uint32_t>(std::min<std::uint64_t>(c.missed_ticks + c.late_ticks, 0xFFu)));
  write_raw(f, kHbFreeSlots, programs_.free_slots());
  write_raw(f, kHbOwner, access_.owner());
  write_raw(f, kHbAxes, heartbeat_axes());
  tx_.heartbeat_sent();
  bus_errors_at_heartbeat_ = c.bus_errors;
  late_ticks_at_heartbeat_ = c.late_ticks;
  can_errors_at_heartbeat_ = can_.error_frames();
  tx_.queue(f, false);  // never dropped for telemetry's sake
  programs_.on_heartbeat();
}

void NodeTelemetry::send(std::uint32_t due) noexcept {
  if (due == 0) return;
  const TickRecord& r = task_.last_record();
  const auto emit = [this](const hal::CanFrame& frame) noexcept { tx_.queue(frame, true); };
  if ((due & cyclic_bit(Cyclic::heartbeat)) != 0) send_heartbeat();
  const auto i32_mm = [](hal::CanFrame& f, const FieldDef& field, double mm) noexcept {
    // Saturate rather than send nothing: a reading beyond +-2.1 m is off the table anyway.
    const double lim_mm = 2147483647.0 * field.scale;
    write(f, field, std::clamp(std::isfinite(mm) ? mm : 0.0, -lim_mm, lim_mm));
  };
  // One frame per axis and kind, axis by axis.
  if ((due & cyclic_bit(Cyclic::position)) != 0) {
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      hal::CanFrame f = make_frame(*kPositionMsgs[i], node_id_);
      i32_mm(f, kPosition, r.axis[i].position_mm);
      i32_mm(f, kFollowing, r.axis[i].reference_mm - r.axis[i].position_mm);
      emit(f);
    }
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
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      hal::CanFrame f = make_frame(*kDacMsgs[i], node_id_);
      write_raw(f, kDacCode, r.axis[i].dac_code);
      emit(f);
    }
    hal::CanFrame f = make_frame(kOutputMsg, node_id_);
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
  if ((due & cyclic_bit(Cyclic::spindle)) != 0) {
    hal::CanFrame f = make_frame(kTlmSpindleMsg, node_id_);
    const SpindleControl& sp = task_.spindle();
    write_saturated(f, kTlmSpindleTarget, r.spindle.target_rpm);
    write_saturated(f, kTlmSpindleCommand, r.spindle.command_rpm);
    write_saturated(f, kTlmSpindleMeasured, r.spindle.measured_rpm);
    std::uint32_t flags = 0;
    if (sp.commanded_on()) flags |= kSpindleOn;
    if (r.spindle.enabled) flags |= kSpindleEnabled;
    if (r.spindle.reverse) flags |= kSpindleReverse;
    if (r.spindle.at_speed) flags |= kSpindleAtSpeed;
    if (r.spindle.feed_gate_waiting) flags |= kSpindleFeedWaiting;
    if (sp.inhibited()) flags |= kSpindleInhibited;
    write_raw(f, kTlmSpindleFlags, flags);
    write_raw(f, kTlmSpindleStopCause, static_cast<std::uint32_t>(sp.last_stop_cause()));
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
