// CanNode: EXCITE, the open-loop excitation for identification and the
// sweep / multisine (closed loop) and multisine_open for frequency response
// (TickTask::start_excitation, docs/autotune.md, docs/frequency-response.md).
// Answered by one COMMAND_ACK (detail = index of the offending field); every
// check comes first, a refused request changes nothing. The frame carries
// axis, kind, duration and level; the ramp rate, the settle time and the
// breakaway count are ExcitationSpec's defaults (2 mm/s^2, 0.2 s, 12
// counts), the values of the host's identification sequence
// (tools/hil/tune_sequence.hpp); the band and tone count of a sweep /
// multisine are the excite.* parameters (validated when set), and so is a
// sweep / multisine's carrier (excite.carrier_mm_s), whose travel, carrier x
// duration from where the axis stands, must end inside the soft limits
// (else out_of_range on the duration field).
#include <cmath>

#include "firmware/can/can_node.hpp"
#include "firmware/can/command_result.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;

void CanNode::handle_excite(const hal::CanFrame& frame) noexcept {
  const std::uint32_t axis = read_raw(frame, kExciteAxis);
  const std::uint32_t kind = read_raw(frame, kExciteKind);
  const double duration_s = read(frame, kExciteDuration);
  const double level_mm_s = read(frame, kExciteLevel);
  const std::uint8_t id = kExciteMsg.id;
  if (!access_.owns()) return ack_.send(id, 0, ErrorCode::not_owner, 0);
  if (axis >= hal::kAxisCount) return ack_.send(id, 0, ErrorCode::bad_axis, index_of(kExciteMsg, kExciteAxis));
  if (kind > 4) return ack_.send(id, 0, ErrorCode::out_of_range, index_of(kExciteMsg, kExciteKind));
  const std::uint8_t level = index_of(kExciteMsg, kExciteLevel);
  if (!std::isfinite(level_mm_s)) return ack_.send(id, 0, ErrorCode::not_finite, level);
  if (!(std::fabs(level_mm_s) > 0.0) || std::fabs(level_mm_s) > 100.0)
    return ack_.send(id, 0, ErrorCode::out_of_range, level);
  const std::uint8_t duration = index_of(kExciteMsg, kExciteDuration);
  const auto excitation_kind = static_cast<ExcitationKind>(kind);
  const bool with_band = banded(excitation_kind);
  const double longest_s = with_band ? kExcitationMaxRecordS : 10.0;
  const double shortest_s = with_band ? 0.1 : 0.001;
  if (duration_s < shortest_s || duration_s > longest_s) return ack_.send(id, 0, ErrorCode::out_of_range, duration);
  ExcitationSpec spec;  // rate, settle and breakaway: the defaults (see the top of this file)
  spec.kind = excitation_kind;
  spec.level_mm_s = level_mm_s;
  spec.duration_s = duration_s;
  spec.f_min_hz = params_.settings().excite.f_min_hz;
  spec.f_max_hz = params_.settings().excite.f_max_hz;
  spec.tones = params_.settings().excite.tones;
  spec.carrier_mm_s = closed_loop(excitation_kind) ? params_.settings().excite.carrier_mm_s : 0.0;
  // The band was checked when it was set; what is left is the duration (a multisine's 2 periods).
  if (!validate(spec).ok) return ack_.send(id, 0, ErrorCode::invalid, duration);
  if (!task_.carrier_travel_fits(hal::axis_from_index(axis), spec))
    return ack_.send(id, 0, ErrorCode::out_of_range, duration);
  const CommandStatus st = task_.start_excitation(hal::axis_from_index(axis), spec);
  if (st != CommandStatus::ok) return ack_.send(id, 0, to_error(st), 0);
  motion_accepted();
  // A capture waiting for a motion records the excitation, first tick to last.
  capture_.excitation_started(params_.settings().capture);
  ack_.send(id, 0, ErrorCode::ok, 0);
}

}  // namespace tnv::fw::can
