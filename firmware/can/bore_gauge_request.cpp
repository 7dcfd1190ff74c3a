// BoreGaugeRequest: BORE_GAUGE and its BORE_INFEED reply (bore_gauge_request.hpp).
#include "firmware/can/bore_gauge_request.hpp"

#include <array>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"

namespace tnv::fw::can {

using namespace fields;

namespace {

// The flags of a recorded part (BORE_INFEED.flags; the started bit is the reply's).
std::uint8_t part_flags(const BoringStationAnswer& a) noexcept {
  unsigned flags = 0;
  const auto set = [&flags](bool on, BoreFlag f) noexcept {
    if (on) flags |= f;
  };
  set(a.report.startup, kBoreStartup);
  set(a.report.reset, kBoreReset);
  set(a.out_of_band[kBoringTop], kBoreTopOut);
  set(a.out_of_band[kBoringBottom], kBoreBottomOut);
  set(a.next[kBoringTop].infeed_limited, kBoreTopLimited);
  set(a.next[kBoringBottom].infeed_limited, kBoreBottomLimited);
  set(a.next[kBoringTop].alpha_limited || a.next[kBoringBottom].alpha_limited, kBoreAlphaFloor);
  return static_cast<std::uint8_t>(flags);
}

// A reading as the gauge sent it, raw (sign-extended from 16 bits).
std::int16_t reading_raw(const hal::CanFrame& frame, const FieldDef& f) noexcept {
  return static_cast<std::int16_t>(static_cast<std::uint16_t>(read_raw(frame, f)));
}

}  // namespace

void BoreGaugeRequest::handle(const hal::CanFrame& frame) noexcept {
  const auto op_raw = static_cast<std::uint8_t>(read_raw(frame, kBoreOp));
  if (op_raw >= kBoreOpCount) return reply(ErrorCode::unknown_command, index_of(kBoreGaugeMsg, kBoreOp));
  const auto op = static_cast<BoreOp>(op_raw);
  if (op != BoreOp::query) {
    if (!access_.owns()) return reply(ErrorCode::not_owner, 0);
    // A save or load works on the set (the learned state included) as it was at the request.
    if (storage_.pending()) return reply(ErrorCode::busy, 0);
  }
  if (!params_.settings().bore.enabled) return reply(ErrorCode::not_ready, 0);
  if (op == BoreOp::query) return reply(ErrorCode::ok, 0);
  if (op == BoreOp::restart) {
    const BoringStationState was = params_.bore_state();
    restart(params_.bore_state());
    if (!(params_.bore_state() == was)) storage_.changed();
    return reply(ErrorCode::ok, 0);
  }

  // record: the readings, then the part's number, then the planner.
  const FieldDef* const reading_fields[kBoringStationPositions] = {&kBoreTop, &kBoreBottom};
  std::array<double, kBoringStationPositions> bore_error_mm{};
  for (std::size_t i = 0; i < bore_error_mm.size(); ++i) {
    if (reading_raw(frame, *reading_fields[i]) == kBoreNoReading)
      return reply(ErrorCode::not_finite, index_of(kBoreGaugeMsg, *reading_fields[i]));
    bore_error_mm[i] = read(frame, *reading_fields[i]);
  }
  // The part must be the next one: a repeated frame (its reply lost) or a skipped part is refused.
  const auto expected = static_cast<std::uint32_t>(params_.bore_state().planner.parts + 1) & 0xFFFFu;
  if (read_raw(frame, kBorePart) != expected) return reply(ErrorCode::out_of_range, index_of(kBoreGaugeMsg, kBorePart));

  const BoringStationAnswer a =
      record_bored_part(params_.settings().bore, params_.bore_state(), bore_error_mm, kBoreInfeedTop.scale);
  if (!a.check.ok) {
    // A start-up deflection <= 0 (no logarithm for eq. (10)): the reading is named when known.
    const std::uint8_t detail = a.position >= 0 ? index_of(kBoreGaugeMsg, *reading_fields[a.position]) : 0;
    return reply(ErrorCode::invalid, detail);
  }
  storage_.changed();  // learned, not saved yet
  reply(ErrorCode::ok, 0, part_flags(a));
}

void BoreGaugeRequest::reply(ErrorCode result, std::uint8_t detail, std::uint8_t flags) noexcept {
  hal::CanFrame frame = make_frame(kBoreInfeedMsg, node_id_);
  if (params_.bore_state().planner.started) flags = static_cast<std::uint8_t>(flags | kBoreStarted);
  write_raw(frame, kBoreReplyTag, access_.tag());
  write_raw(frame, kBoreResult, static_cast<std::uint32_t>(result));
  write_raw(frame, kBoreDetail, detail);
  write_raw(frame, kBoreFlags, flags);
  const std::array<double, kBoringStationPositions> infeeds =
      current_infeeds_mm_rev(params_.settings().bore, params_.bore_state(), kBoreInfeedTop.scale);
  write(frame, kBoreInfeedTop, infeeds[kBoringTop]);
  write(frame, kBoreInfeedBottom, infeeds[kBoringBottom]);
  tx_.answer(frame, result);
}

}  // namespace tnv::fw::can
