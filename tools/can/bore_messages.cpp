#include "tools/can/bore_messages.hpp"

#include "firmware/can/node_fields.hpp"
#include "tools/score/boring_node_resolution.hpp"

namespace tnv::can_host {

namespace {

using namespace can::fields;

void write_reading(hal::CanFrame& frame, const can::FieldDef& f, std::optional<double> mm) {
  if (!mm || !can::write(frame, f, *mm))
    can::write_raw(frame, f, static_cast<std::uint16_t>(can::kBoreNoReading));
}

}  // namespace

hal::CanFrame bore_gauge_request(std::uint8_t node, std::uint8_t tag, can::BoreOp op, std::uint16_t part,
                                 std::optional<double> top_mm, std::optional<double> bottom_mm) {
  hal::CanFrame f = can::make_frame(kBoreGaugeMsg, node);
  can::write_raw(f, can::field(kBoreGaugeMsg, "tag"), tag);
  can::write_raw(f, kBoreOp, static_cast<std::uint32_t>(op));
  can::write_raw(f, kBorePart, part);
  if (op == can::BoreOp::record) {
    write_reading(f, kBoreTop, top_mm);
    write_reading(f, kBoreBottom, bottom_mm);
  }
  return f;
}

BoreInfeed read_bore_infeed(const hal::CanFrame& frame) {
  BoreInfeed r;
  r.tag = static_cast<std::uint8_t>(can::read_raw(frame, kBoreReplyTag));
  r.result = static_cast<can::ErrorCode>(can::read_raw(frame, kBoreResult));
  r.detail = static_cast<std::uint8_t>(can::read_raw(frame, kBoreDetail));
  r.flags = static_cast<std::uint8_t>(can::read_raw(frame, kBoreFlags));
  r.infeed_top_mm_rev = can::read(frame, kBoreInfeedTop);
  r.infeed_bottom_mm_rev = can::read(frame, kBoreInfeedBottom);
  return r;
}

bool bore_reading_fits(double bore_error_mm) { return hil::gauge_on_wire_mm(bore_error_mm).has_value(); }

std::string bore_gauge_field_name(std::uint8_t index) {
  return index < kBoreGaugeMsg.fields.size() ? kBoreGaugeMsg.fields[index].name : "?";
}

}  // namespace tnv::can_host
