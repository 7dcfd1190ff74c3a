// Fuzz entry: the frame codec alone (firmware/can/frame_codec.hpp), the
// decoder every received frame goes through. Invariants, per frame:
// classify() names a message only for a standard frame whose identifier
// carries that message's id; every field of it reads back to the same
// bytes when written again (raw, physical value and bytes7 alike), so
// decoding loses nothing and encoding touches only the field's own bytes.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "firmware/can/can_id.hpp"
#include "firmware/can/frame_codec.hpp"
#include "tests/fuzz/fuzz_entries.hpp"
#include "tests/fuzz/fuzz_support.hpp"

namespace tnv::fuzz {

namespace can = fw::can;

namespace {

// Bytes [offset, offset + n) of a and b equal, and every byte outside them equal too.
bool only_field_differs(const hal::CanFrame& a, const hal::CanFrame& b, const can::FieldDef& f) {
  const std::size_t n = can::wire_size(f.type);
  for (std::size_t i = 0; i < a.data.size(); ++i) {
    const bool inside = i >= f.byte_offset && i < f.byte_offset + n;
    if (!inside && a.data[i] != b.data[i]) return false;
  }
  return true;
}

bool same_field(const hal::CanFrame& a, const hal::CanFrame& b, const can::FieldDef& f) {
  const std::size_t n = can::wire_size(f.type);
  return std::equal(a.data.begin() + f.byte_offset, a.data.begin() + f.byte_offset + static_cast<std::ptrdiff_t>(n),
                    b.data.begin() + f.byte_offset);
}

const char* check_field(const hal::CanFrame& frame, const can::FieldDef& f) {
  if (f.byte_offset + can::wire_size(f.type) > frame.data.size()) return "a field lies outside the payload";
  hal::CanFrame copy = frame;
  copy.data.fill(0);
  if (f.type == can::WireType::bytes7) {
    std::array<std::uint8_t, 7> bytes{};
    can::read_bytes(frame, f, bytes);
    can::write_bytes(copy, f, bytes);
    if (!same_field(frame, copy, f)) return "bytes7 field does not round-trip";
    if (!only_field_differs(copy, hal::CanFrame{}, f)) return "write_bytes touched bytes outside its field";
    return "";
  }
  const std::uint32_t raw = can::read_raw(frame, f);
  can::write_raw(copy, f, raw);
  if (!same_field(frame, copy, f)) return "raw field does not round-trip";
  if (!only_field_differs(copy, hal::CanFrame{}, f)) return "write_raw touched bytes outside its field";

  const double value = can::read(frame, f);
  hal::CanFrame again = frame;
  if (f.type == can::WireType::f32) {
    if (!can::write(again, f, value)) return "an f32 field refused the value it decoded";
    // float -> double -> float is exact except for a NaN's payload bits
    if (!std::isnan(value) && !same_field(frame, again, f)) return "f32 field does not round-trip";
    if (std::isnan(value) && !std::isnan(can::read(again, f))) return "a NaN did not stay NaN";
  } else if (f.type != can::WireType::raw32) {
    if (!std::isfinite(value)) return "an integer field decoded to a non-finite value";
    if (!can::write(again, f, value)) return "an integer field refused the value it decoded";
    if (!same_field(frame, again, f)) return "integer field does not round-trip through its physical value";
  }
  if (!only_field_differs(frame, again, f)) return "write touched bytes outside its field";
  return "";
}

}  // namespace

std::string frame_codec(const std::uint8_t* data, std::size_t size) {
  for (std::size_t r = 0; r + kFrameRecordBytes <= size; r += kFrameRecordBytes) {
    const std::uint8_t* rec = data + r;
    const std::size_t at = r / kFrameRecordBytes;
    const hal::CanFrame frame = frame_of_record(rec);

    const can::MessageDef* m = can::classify(frame);
    if (m == nullptr) {
      if (!frame.extended && can::find_message(can::message_of(frame.id)) != nullptr)
        return broken("classify() missed a message in the table", at);
      continue;
    }
    if (frame.extended) return broken("classify() accepted an extended frame", at);
    if (m->id != can::message_of(frame.id)) return broken("classify() named another message", at);
    if (can::make_frame(*m, can::node_of(frame.id)).id != frame.id) return broken("make_frame() changed the identifier", at);
    for (const can::FieldDef& f : m->fields)
      if (const char* why = check_field(frame, f); *why != '\0') return broken(why, at);
  }
  return {};
}

}  // namespace tnv::fuzz
