#pragma once
// THE protocol table, part 2: every parameter. Id, name, type, unit,
// range, access and when a change may apply; defaults are read from
// default_node_settings() (the papers' values), so they cannot drift.
// Axis parameters repeat per axis: x at 0x01xx, y at 0x02xx, same low byte.
#include <cstddef>
#include <cstdint>
#include <span>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "hal/axis.hpp"

namespace tnv::fw::can {

// Each axis of TNV_AXES has one block of parameter ids, (index + 1) << 8
// (x 0x01nn, y 0x02nn), its rows named "<axis>." (param_table.cpp).
constexpr std::uint16_t axis_param_base(hal::Axis axis) noexcept {
  return static_cast<std::uint16_t>((hal::index(axis) + 1) << 8);
}
// The id of axis `axis`' parameter at `offset` in its block (TNV_AXIS_PARAMS).
constexpr std::uint16_t axis_param_id(std::size_t axis, std::uint16_t offset) noexcept {
  return static_cast<std::uint16_t>(axis_param_base(hal::axis_from_index(axis)) + offset);
}

enum class ParamType : std::uint8_t { f32, u32, i32, boolean, enumeration };
enum class Access : std::uint8_t { read_only, read_write };
// When a written value takes effect.
enum class Apply : std::uint8_t {
  live,     // at once, between two ticks, also while moving
  idle,     // only at rest (disabled or holding): refused with "busy" while moving
  restart,  // stored at once, used from the next start (node id, bit rate)
};
// Who may change a parameter. A safety parameter is one whose wrong value
// defeats a safety function (a supervisor limit, the missed-tick limit,
// the host timeout, the jog dead man, the encoder and DAC scales): it
// changes only in commissioning mode (docs/safety.md "Commissioning").
enum class Guard : std::uint8_t {
  open,           // any write the access and apply rules allow
  commissioning,  // a change outside commissioning mode is refused (commissioning_required)
};

constexpr const char* to_string(ParamType t) noexcept {
  switch (t) {
    case ParamType::f32: return "f32";
    case ParamType::u32: return "u32";
    case ParamType::i32: return "i32";
    case ParamType::boolean: return "bool";
    case ParamType::enumeration: return "enum";
  }
  return "?";
}
constexpr const char* to_string(Access a) noexcept { return a == Access::read_only ? "ro" : "rw"; }
constexpr const char* to_string(Guard g) noexcept { return g == Guard::commissioning ? "commissioning" : "open"; }
constexpr const char* to_string(Apply a) noexcept {
  switch (a) {
    case Apply::live: return "live";
    case Apply::idle: return "idle";
    case Apply::restart: return "restart";
  }
  return "?";
}

struct ParamDef {
  std::uint16_t id;
  const char* name;  // dotted, e.g. "x.sliding.gamma"
  ParamType type;
  const char* unit;
  double min;  // inclusive range of the physical value
  double max;
  const char* values;  // enumeration / boolean names "0=pid 1=dvsc 2=rdvsc"; "" otherwise
  Access access;
  Apply apply;
  Guard guard;
  double (*get)(const NodeSettings&) noexcept;
  void (*set)(NodeSettings&, double) noexcept;  // nullptr for read-only
  bool (*allowed)(double) noexcept;             // extra membership test (e.g. bit rates); nullptr = none
  // The member the parameter is, in the given settings (nullptr for a
  // computed one): a validation error naming a member names its parameter.
  const void* (*member)(const NodeSettings&) noexcept;
  const char* doc;
};

// Sorted by id, ids unique (tested).
std::span<const ParamDef> param_table() noexcept;
const ParamDef* find_param(std::uint16_t id) noexcept;
const ParamDef* find_param(const char* name) noexcept;

// A safety parameter (Guard::commissioning).
constexpr bool safety_param(const ParamDef& p) noexcept { return p.guard == Guard::commissioning; }

// The first safety parameter whose value differs between `live` and
// `next` (compared as the wire carries it, so a value read back and
// written again is no change); 0 if none.
std::uint16_t first_safety_change(const NodeSettings& live, const NodeSettings& next) noexcept;
// Copies every safety parameter of `from` into `to`.
void keep_safety_params(const NodeSettings& from, NodeSettings& to) noexcept;
// Read-write parameters whose values differ between `a` and `b`, counted up
// to `stop_at` (1: whether they differ at all, ending at the first).
std::size_t differing_params(const NodeSettings& a, const NodeSettings& b,
                             std::size_t stop_at = static_cast<std::size_t>(-1)) noexcept;

// Range / type check of one value for one parameter: ok, not_finite,
// out_of_range (also for a non-integer value of an integer type) or
// read_only.
ErrorCode check_value(const ParamDef& p, double value) noexcept;

// The 4 wire bytes of a value (f32 bits, or the integer) and back.
std::uint32_t to_wire(const ParamDef& p, double value) noexcept;
double from_wire(const ParamDef& p, std::uint32_t raw) noexcept;

// The whole set, cross-field (firmware validate(), shaper designs, motion
// defaults, capture). On failure: the parameter to blame (0 if none
// fits), a section and a reason, static text.
struct SettingsCheck {
  bool ok = true;
  std::uint16_t param = 0;
  const char* section = "";
  const char* reason = "";
};
SettingsCheck validate(const NodeSettings& settings) noexcept;
// The same, skipping the parts byte for byte those of `valid_base`, a set
// that passed validate() (a change checks what it changes; the parameter
// ranges are always checked).
SettingsCheck validate(const NodeSettings& settings, const NodeSettings& valid_base) noexcept;

// Maximum capture image, in 32-bit words (the firmware's fixed buffer).
inline constexpr std::uint32_t kCaptureCapacityWords = 131072;

}  // namespace tnv::fw::can
