// TuningRequests: SHAPER and EXCITE (tuning_requests.hpp).
#include "firmware/can/tuning_requests.hpp"

#include <array>
#include <cmath>
#include <utility>

#include "firmware/can/command_result.hpp"
#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/param_table.hpp"

namespace tnv::fw::can {

using namespace fields;

// Same as staging x|y.shaper.type/freq_hz/zeta and committing.
void TuningRequests::shaper(const hal::CanFrame& frame) noexcept {
  if (!access_.owns()) return ack_.send(kShaperMsg.id, 0, ErrorCode::not_owner, 0);
  const std::uint32_t axis = read_raw(frame, kShaperAxis);
  const std::uint32_t type = read_raw(frame, kShaperType);
  const double zeta = read(frame, kShaperZeta);
  const double freq_hz = read(frame, kShaperFreq);
  if (axis >= hal::kAxisCount) return ack_.send(kShaperMsg.id, 0, ErrorCode::bad_axis, index_of(kShaperMsg, kShaperAxis));
  const std::array<std::pair<const FieldDef*, std::uint16_t>, 3> checks{
      {{&kShaperType, axis_param_id(axis, 0x40)}, {&kShaperZeta, axis_param_id(axis, 0x42)}, {&kShaperFreq, axis_param_id(axis, 0x41)}}};
  const std::array<double, 3> values{static_cast<double>(type), zeta, freq_hz};
  NodeSettings next = params_.settings();
  for (std::size_t k = 0; k < checks.size(); ++k) {
    const ParamDef* p = find_param(checks[k].second);
    const std::uint8_t detail = index_of(kShaperMsg, *checks[k].first);
    if (p == nullptr) return ack_.send(kShaperMsg.id, 0, ErrorCode::unknown_id, detail);
    if (const ErrorCode e = check_value(*p, values[k]); e != ErrorCode::ok) return ack_.send(kShaperMsg.id, 0, e, detail);
    p->set(next, values[k]);
  }
  const ErrorCode e = params_.apply(next, false);
  if (design_.deferred()) return;  // handled again, and answered, when the design is made
  ack_.send(kShaperMsg.id, 0, e, 0);
}

void TuningRequests::excite(const hal::CanFrame& frame) noexcept {
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
  ExcitationSpec spec;  // rate, settle and breakaway: the defaults (tuning_requests.hpp)
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
  motion_.accepted();
  // A capture waiting for a motion records the excitation, first tick to last.
  capture_.excitation_started(params_.settings().capture);
  ack_.send(id, 0, ErrorCode::ok, 0);
}

}  // namespace tnv::fw::can
