#pragma once
// The vocabulary of the protocol table (protocol_messages.hpp,
// param_table.hpp): how one field sits in an 8-byte classic CAN payload.
// Little-endian, byte-aligned fields; physical = raw * scale (the DBC
// convention with offset 0). Everything here is constexpr data, read by
// the firmware codec, the host codec and the DBC / Markdown generator.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace tnv::fw::can {

enum class WireType : std::uint8_t { u8, i8, u16, i16, u32, i32, f32, raw32, bytes7, u24, i24 };

constexpr std::size_t wire_size(WireType t) noexcept {
  switch (t) {
    case WireType::u8:
    case WireType::i8: return 1;
    case WireType::u16:
    case WireType::i16: return 2;
    case WireType::u24:
    case WireType::i24: return 3;
    case WireType::u32:
    case WireType::i32:
    case WireType::f32:
    case WireType::raw32: return 4;
    case WireType::bytes7: return 7;
  }
  return 0;
}

constexpr bool is_signed(WireType t) noexcept {
  return t == WireType::i8 || t == WireType::i16 || t == WireType::i24 || t == WireType::i32 || t == WireType::f32;
}

constexpr const char* to_string(WireType t) noexcept {
  switch (t) {
    case WireType::u8: return "u8";
    case WireType::i8: return "i8";
    case WireType::u16: return "u16";
    case WireType::i16: return "i16";
    case WireType::u32: return "u32";
    case WireType::i32: return "i32";
    case WireType::f32: return "f32";
    case WireType::raw32: return "raw32";
    case WireType::bytes7: return "bytes7";
    case WireType::u24: return "u24";
    case WireType::i24: return "i24";
  }
  return "?";
}

struct FieldDef {
  const char* name;          // snake_case; the DBC signal is <MESSAGE>_<name>
  WireType type;
  std::uint8_t byte_offset;  // first byte in the payload
  double scale;              // physical = raw * scale (1 for f32, raw32, bytes7)
  const char* unit;          // "" when dimensionless
  const char* values;        // value table for enumerations, "0=a 1=b ..."; "" otherwise
  const char* doc;
};

enum class Direction : std::uint8_t { to_node, from_node };

struct MessageDef {
  std::uint8_t id;    // 6-bit message id: the identifier's high bits (lower = higher priority)
  const char* name;   // snake_case; the DBC message is its upper-case form
  Direction direction;
  std::uint8_t dlc;   // every message has a fixed length
  std::span<const FieldDef> fields;
  const char* doc;
};

namespace detail {
// Never defined and not constexpr: a consteval lookup that reaches one of
// these is not a constant expression, so a typo fails the build with the
// function's name as the message (a `throw` would do the same, but the
// firmware builds with -fno-exceptions).
void no_such_field_in_this_message();
void no_such_message();
}  // namespace detail

// Compile-time field lookup by name: a typo is a compile error, not a
// silent wrong byte.
consteval const FieldDef& field(const MessageDef& m, std::string_view name) {
  for (const FieldDef& f : m.fields)
    if (name == f.name) return f;
  detail::no_such_field_in_this_message();
  return m.fields[0];
}

}  // namespace tnv::fw::can
