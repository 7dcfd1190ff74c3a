// ProgramStream: SEGMENT / SEGMENT_TAIL into the motion queue, the program
// commands and PROGRAM_STATUS.
#include "firmware/can/program_stream.hpp"

#include <algorithm>

#include "firmware/can/command_result.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;

namespace {

constexpr std::uint32_t kMaxOverridePercent = 150;

struct Refusal {
  ErrorCode code = ErrorCode::ok;
  const MessageDef* message = nullptr;  // the message holding the field at fault
  const FieldDef* field = nullptr;
};

// The queue's reason as a code a host can show, and the field it concerns.
Refusal refusal(motion::SegmentRefusal why) noexcept {
  using motion::SegmentRefusal;
  switch (why) {
    case SegmentRefusal::queue_full: return {ErrorCode::queue_full, &kSegmentTailMsg, nullptr};
    case SegmentRefusal::not_finite: return {ErrorCode::not_finite, &kSegmentMsg, &kSegmentX};
    case SegmentRefusal::bad_kind: return {ErrorCode::out_of_range, &kSegmentMsg, &kSegmentKind};
    case SegmentRefusal::zero_length: return {ErrorCode::zero_length, &kSegmentMsg, &kSegmentX};
    case SegmentRefusal::arc_radius_mismatch:
    case SegmentRefusal::arc_radius_too_small: return {ErrorCode::bad_arc, &kSegmentTailMsg, &kTailCentreNormal};
    case SegmentRefusal::feed_not_positive: return {ErrorCode::out_of_range, &kSegmentTailMsg, &kTailFeed};
    case SegmentRefusal::feed_above_limit: return {ErrorCode::feed_above_limit, &kSegmentTailMsg, &kTailFeed};
    case SegmentRefusal::outside_workspace: return {ErrorCode::outside_workspace, &kSegmentMsg, &kSegmentX};
    case SegmentRefusal::bad_dwell:
    case SegmentRefusal::bad_spindle: return {ErrorCode::out_of_range, &kSegmentMsg, &kSegmentX};
    case SegmentRefusal::probe_pending: return {ErrorCode::probe_pending, &kSegmentMsg, nullptr};
    case SegmentRefusal::bad_ramp:
    case SegmentRefusal::none: break;
  }
  return {ErrorCode::invalid, &kSegmentMsg, nullptr};
}

}  // namespace

std::uint8_t ProgramStream::free_slots() const noexcept {
  return static_cast<std::uint8_t>(std::min<std::size_t>(task_.motion().free_slots(), 255));
}

void ProgramStream::refuse_pending() noexcept {
  if (!pending_.active) return;
  pending_.active = false;
  ack_.send_tagged(pending_.tag, kSegmentMsg.id, free_slots(), ErrorCode::not_ready, 0);
}

bool ProgramStream::segment(const hal::CanFrame& frame) noexcept {
  if (!access_.owns()) {
    ack_.send(kSegmentMsg.id, free_slots(), ErrorCode::not_owner, 0);
    return false;
  }
  refuse_pending();  // the owner moved on without sending the last one's tail
  SegmentHead head;
  if (!decode_head(frame, head)) {
    ack_.send(kSegmentMsg.id, free_slots(), ErrorCode::out_of_range, index_of(kSegmentMsg, kSegmentKind));
    return false;
  }
  if (!wire_kind_has_tail(head.kind)) return push_element(head, nullptr, kSegmentMsg.id);
  pending_ = {true, access_.tag(), head};  // answered when the tail comes
  return false;
}

bool ProgramStream::segment_tail(const hal::CanFrame& frame) noexcept {
  if (!access_.owns()) {
    ack_.send(kSegmentTailMsg.id, free_slots(), ErrorCode::not_owner, 0);
    return false;
  }
  if (!pending_.active || pending_.tag != access_.tag()) {
    refuse_pending();  // its tail was lost, or this one belongs to a lost head: both are answered
    ack_.send(kSegmentTailMsg.id, free_slots(), ErrorCode::not_ready, index_of(kSegmentTailMsg, kTailTag));
    return false;
  }
  pending_.active = false;
  return push_element(pending_.head, &frame, kSegmentTailMsg.id);
}

bool ProgramStream::segment_z(const hal::CanFrame& frame) noexcept {
  if (!access_.owns()) {
    ack_.send(kSegmentZMsg.id, free_slots(), ErrorCode::not_owner, 0);
    return false;
  }
  // Only between its SEGMENT and SEGMENT_TAIL, once: else the element is refused whole (its tail will find nothing
  // waiting and is refused too), so nothing half-described is queued.
  if (!pending_.active || pending_.tag != access_.tag()) {
    refuse_pending();  // a lost head's element is answered too
    ack_.send(kSegmentZMsg.id, free_slots(), ErrorCode::not_ready, index_of(kSegmentZMsg, kSegmentZTag));
    return false;
  }
  if (!decode_z(frame, pending_.head)) {  // a second one: the element is refused, answered once
    pending_.active = false;
    ack_.send(kSegmentZMsg.id, free_slots(), ErrorCode::not_ready, index_of(kSegmentZMsg, kSegmentZTag));
  }
  return false;
}

bool ProgramStream::segment_plane(const hal::CanFrame& frame) noexcept {
  if (!access_.owns()) {
    ack_.send(kSegmentPlaneMsg.id, free_slots(), ErrorCode::not_owner, 0);
    return false;
  }
  // As SEGMENT_Z: a refusal refuses the element whole (its tail then finds nothing waiting).
  if (!pending_.active || pending_.tag != access_.tag()) {
    refuse_pending();
    ack_.send(kSegmentPlaneMsg.id, free_slots(), ErrorCode::not_ready, index_of(kSegmentPlaneMsg, kPlaneTag));
    return false;
  }
  if (const ErrorCode e = decode_plane(frame, pending_.head); e != ErrorCode::ok) {
    pending_.active = false;
    const FieldDef& f = e == ErrorCode::out_of_range ? kPlaneField : kPlaneTag;
    ack_.send(kSegmentPlaneMsg.id, free_slots(), e, index_of(kSegmentPlaneMsg, f));
  }
  return false;
}

bool ProgramStream::push_element(const SegmentHead& head, const hal::CanFrame* tail, std::uint8_t request) noexcept {
  const bool starting = !task_.program_running();
  if (starting) tool_change_count_ = 0;  // an earlier program's changes never continued
  if (head.kind == WireKind::tool_change && (head.tool < 0 || tool_change_count_ == tool_changes_.size())) {
    ack_.send(kSegmentMsg.id, free_slots(), head.tool < 0 ? ErrorCode::out_of_range : ErrorCode::queue_full,
              index_of(kSegmentMsg, kSegmentX));
    return false;
  }
  motion::Segment segment;
  if (!decode_segment(head, tail, task_.next_segment_start_mm(), segment)) {
    ack_.send(kSegmentTailMsg.id, free_slots(), ErrorCode::bad_arc, index_of(kSegmentTailMsg, kTailCentreNormal));
    return false;
  }
  segment.tag = starting ? 1 : program_.next_element();
  motion::SegmentRefusal why = motion::SegmentRefusal::none;
  const CommandStatus st = task_.push_segment(segment, why);
  if (st == CommandStatus::ok) {
    if (starting) program_.started(task_);
    program_.accepted();
    if (head.kind == WireKind::tool_change) tool_changes_[tool_change_count_++] = {segment.tag, head.tool};
    ack_.send(request, free_slots(), ErrorCode::ok, 0);
    if (program_.update(task_) || starting) send_status();
    return true;
  }
  if (st != CommandStatus::invalid) {
    ack_.send(request, free_slots(), to_error(st), 0);
    return false;
  }
  // The answer names the frame holding the field at fault (SEGMENT: kind, end point, dwell;
  // SEGMENT_TAIL: feed, centre), or the frame just handled when no field is (queue_full).
  const Refusal r = refusal(why);
  const bool in_tail = r.message == &kSegmentTailMsg && tail != nullptr;
  const bool in_head = r.message == &kSegmentMsg;
  if (r.field == nullptr || (!in_tail && !in_head)) {
    ack_.send(request, free_slots(), r.code, 0);
    return false;
  }
  const MessageDef& m = in_tail ? kSegmentTailMsg : kSegmentMsg;
  ack_.send(m.id, free_slots(), r.code, index_of(m, *r.field));
  return false;
}

void ProgramStream::stopping() noexcept {
  program_.aborting();
  pending_.active = false;
}

void ProgramStream::on_tick() noexcept {
  if (task_.probe_report().count != probe_sent_count_) send_probe_result();
  bool news = program_.update(task_);
  // At a tool change the operator takes the old tool out: unknown until cycle_start says the new one is in.
  // Looked at on every paused tick, not only when the state changes: one pause may follow another at once.
  if (program_.state() == ProgramState::paused && tool_ != kToolUnknown &&
      tool_change_at(program_.element(task_)) != nullptr) {
    tool_ = kToolUnknown;
    news = true;
  }
  if (news) send_status();
}

const ToolChange* ProgramStream::tool_change_at(std::uint32_t element) const noexcept {
  for (std::size_t i = 0; i < tool_change_count_; ++i)
    if (tool_changes_[i].element == element) return &tool_changes_[i];
  return nullptr;
}

void ProgramStream::on_heartbeat() noexcept {
  if (active(program_.state())) send_status();
}

ErrorCode ProgramStream::command(CommandCode code, const hal::CanFrame& frame, std::uint8_t& detail) noexcept {
  switch (code) {
    case CommandCode::feed_hold: return to_error(task_.feed_hold(true));
    case CommandCode::feed_resume: return to_error(task_.feed_hold(false));
    case CommandCode::feed_override: {
      const std::uint32_t percent = read_raw(frame, kCommandArg);
      if (percent > kMaxOverridePercent) {
        detail = index_of(kCommandMsg, kCommandArg);
        return ErrorCode::out_of_range;
      }
      return to_error(task_.set_feed_override(static_cast<double>(percent) / 100.0));
    }
    case CommandCode::end_program: {
      const ErrorCode e = to_error(task_.end_program());
      if (e == ErrorCode::ok) program_.ended();
      return e;
    }
    case CommandCode::abort_program:
      if (!task_.program_running()) {
        pending_.active = false;
        return task_.moving() ? ErrorCode::busy : ErrorCode::ok;  // another motion is not ours to abort
      }
      stopping();
      return to_error(task_.stop());
    case CommandCode::program_status:
      send_status();
      if (probe_sent_count_ != 0) send_probe_result();
      return ErrorCode::ok;
    case CommandCode::cycle_start: {
      const std::uint32_t at = program_.element(task_);  // the pause it rests at
      const ErrorCode e = to_error(task_.cycle_start());
      const ToolChange* change = e == ErrorCode::ok ? tool_change_at(at) : nullptr;
      if (change != nullptr) {
        tool_ = change->tool;
        const std::size_t i = static_cast<std::size_t>(change - tool_changes_.data());
        tool_changes_[i] = tool_changes_[--tool_change_count_];  // order does not matter
        send_status();
      }
      return e;
    }
    default: break;
  }
  return ErrorCode::unknown_command;
}

// Before the PROGRAM_STATUS of the same tick: a host that sees the program
// starved after a probe has its result already.
void ProgramStream::send_probe_result() noexcept {
  const ProbeReport& p = task_.probe_report();
  probe_sent_count_ = p.count;
  const std::uint32_t count = p.count & 0xFFu;
  const std::size_t x = hal::index(hal::Axis::x), y = hal::index(hal::Axis::y), z = hal::index(hal::Axis::z);
  hal::CanFrame r = make_frame(kProbeResultMsg, node_id_);
  write_raw(r, kProbeCount, count);
  write_raw(r, kProbeOutcome, static_cast<std::uint32_t>(p.outcome));
  write_saturated(r, kProbeTripX, p.trip_mm[x]);
  write_saturated(r, kProbeTripY, p.trip_mm[y]);
  hal::CanFrame rz = make_frame(kProbeResultZMsg, node_id_);
  write_raw(rz, kProbeZCount, count);
  write_saturated(rz, kProbeTripZ, p.trip_mm[z]);
  write_saturated(rz, kProbeRestZ, p.rest_mm[z]);
  hal::CanFrame rest = make_frame(kProbeRestMsg, node_id_);
  write_raw(rest, kProbeRestCount, count);
  write_saturated(rest, kProbeRestX, p.rest_mm[x]);
  write_saturated(rest, kProbeRestY, p.rest_mm[y]);
  for (const hal::CanFrame& f : {r, rz, rest}) tx_.queue(f, false);  // never dropped: the host waits for it
}

void ProgramStream::send_status() noexcept {
  hal::CanFrame f = make_frame(kProgramStatusMsg, node_id_);
  write_raw(f, kProgramState, static_cast<std::uint32_t>(program_.state()));
  write_raw(f, kProgramFreeSlots, free_slots());
  write_raw(f, kProgramUnderruns, static_cast<std::uint32_t>(std::min<std::uint64_t>(program_.underruns(task_), 0xFFFFu)));
  write_raw(f, kProgramSegment, std::min<std::uint32_t>(program_.element(task_), 0xFFFFFFu));
  write_raw(f, kProgramOverride,
            static_cast<std::uint32_t>(std::clamp(task_.motion().feed_override() * 100.0 + 0.5, 0.0, 255.0)));
  tx_.queue(f, false);  // status the host paces its stream by: never dropped for telemetry's sake
  hal::CanFrame t = make_frame(kProgramToolMsg, node_id_);
  write(t, kProgramToolNumber, static_cast<double>(tool_));
  tx_.queue(t, false);
}

}  // namespace tnv::fw::can
