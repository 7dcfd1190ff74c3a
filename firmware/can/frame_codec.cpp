#include "firmware/can/frame_codec.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace tnv::fw::can {

hal::CanFrame make_frame(const MessageDef& m, std::uint8_t node) noexcept {
  hal::CanFrame frame;
  frame.id = make_can_id(m.id, node);
  frame.dlc = m.dlc;
  return frame;
}

std::uint32_t read_raw(const hal::CanFrame& frame, const FieldDef& f) noexcept {
  const std::size_t n = wire_size(f.type);
  if (f.type == WireType::bytes7 || f.byte_offset + n > frame.data.size()) return 0;
  std::uint32_t raw = 0;
  for (std::size_t i = 0; i < n; ++i) raw |= static_cast<std::uint32_t>(frame.data[f.byte_offset + i]) << (8 * i);
  return raw;
}

void write_raw(hal::CanFrame& frame, const FieldDef& f, std::uint32_t raw) noexcept {
  const std::size_t n = wire_size(f.type);
  if (f.type == WireType::bytes7 || f.byte_offset + n > frame.data.size()) return;
  for (std::size_t i = 0; i < n; ++i) frame.data[f.byte_offset + i] = static_cast<std::uint8_t>(raw >> (8 * i));
}

std::uint32_t float_bits(float v) noexcept { return std::bit_cast<std::uint32_t>(v); }
float bits_float(std::uint32_t raw) noexcept { return std::bit_cast<float>(raw); }

double read(const hal::CanFrame& frame, const FieldDef& f) noexcept {
  const std::uint32_t raw = read_raw(frame, f);
  switch (f.type) {
    case WireType::u8:
    case WireType::u16:
    case WireType::u24:
    case WireType::u32:
    case WireType::raw32: return static_cast<double>(raw) * f.scale;
    case WireType::i8: return static_cast<double>(static_cast<std::int8_t>(raw)) * f.scale;
    case WireType::i16: return static_cast<double>(static_cast<std::int16_t>(raw)) * f.scale;
    case WireType::i24:  // sign-extend bit 23
      return static_cast<double>(static_cast<std::int32_t>(raw << 8) >> 8) * f.scale;
    case WireType::i32: return static_cast<double>(static_cast<std::int32_t>(raw)) * f.scale;
    case WireType::f32: return static_cast<double>(bits_float(raw));
    case WireType::bytes7: return 0.0;
  }
  return 0.0;
}

namespace {

bool fits(double raw, double lo, double hi) noexcept { return std::isfinite(raw) && raw >= lo && raw <= hi; }

// The raw range of an integer field; false for f32 and bytes7.
bool raw_range(WireType t, double& lo, double& hi) noexcept {
  lo = 0.0;
  switch (t) {
    case WireType::u8: hi = 255.0; return true;
    case WireType::u16: hi = 65535.0; return true;
    case WireType::u24: hi = 16777215.0; return true;
    case WireType::u32:
    case WireType::raw32: hi = 4294967295.0; return true;
    case WireType::i8: lo = -128.0; hi = 127.0; return true;
    case WireType::i16: lo = -32768.0; hi = 32767.0; return true;
    case WireType::i24: lo = -8388608.0; hi = 8388607.0; return true;
    case WireType::i32: lo = -2147483648.0; hi = 2147483647.0; return true;
    default: return false;
  }
}

}  // namespace

bool write_saturated(hal::CanFrame& frame, const FieldDef& f, double physical) noexcept {
  double lo = 0.0, hi = 0.0;
  if (f.type == WireType::f32 || !raw_range(f.type, lo, hi)) return write(frame, f, physical);
  const double raw = std::isnan(physical) ? 0.0 : std::clamp(std::round(physical / f.scale), lo, hi);
  return write(frame, f, raw * f.scale);
}

bool write(hal::CanFrame& frame, const FieldDef& f, double physical) noexcept {
  if (f.type == WireType::f32) {
    write_raw(frame, f, float_bits(static_cast<float>(physical)));
    return true;
  }
  if (f.type == WireType::bytes7) return false;
  const double raw = std::round(physical / f.scale);
  double lo = 0.0;
  double hi = 0.0;
  if (!raw_range(f.type, lo, hi)) return false;
  if (!fits(raw, lo, hi)) return false;
  const std::uint32_t bits = raw < 0.0 ? static_cast<std::uint32_t>(static_cast<std::int32_t>(raw))
                                       : static_cast<std::uint32_t>(raw);
  write_raw(frame, f, bits);
  return true;
}

void read_bytes(const hal::CanFrame& frame, const FieldDef& f, std::span<std::uint8_t> out) noexcept {
  for (std::size_t i = 0; i < out.size() && i < wire_size(f.type) && f.byte_offset + i < frame.data.size(); ++i)
    out[i] = frame.data[f.byte_offset + i];
}

void write_bytes(hal::CanFrame& frame, const FieldDef& f, std::span<const std::uint8_t> in) noexcept {
  for (std::size_t i = 0; i < in.size() && i < wire_size(f.type) && f.byte_offset + i < frame.data.size(); ++i)
    frame.data[f.byte_offset + i] = in[i];
}

const MessageDef* classify(const hal::CanFrame& frame) noexcept {
  if (frame.extended || frame.id > 0x7FFu) return nullptr;
  return find_message(message_of(frame.id));
}

}  // namespace tnv::fw::can
