#pragma once
// Table-driven codec for one frame: the same functions encode and decode
// on the firmware and on the host, driven by protocol_messages.hpp. No
// allocation, no exceptions: safe in the firmware's CAN service.
#include <cstdint>
#include <span>

#include "firmware/can/can_id.hpp"
#include "firmware/can/protocol_messages.hpp"
#include "hal/can_port.hpp"

namespace tnv::fw::can {

// An empty frame of message m addressed to / sent by node.
hal::CanFrame make_frame(const MessageDef& m, std::uint8_t node) noexcept;

// The raw bits of a field (zero-extended; bytes7 fields: not available, use read_bytes).
std::uint32_t read_raw(const hal::CanFrame& frame, const FieldDef& f) noexcept;
void write_raw(hal::CanFrame& frame, const FieldDef& f, std::uint32_t raw) noexcept;

// Physical value: raw * scale (sign-extended for signed types; f32 as is).
// raw32 fields read as the unsigned bits.
double read(const hal::CanFrame& frame, const FieldDef& f) noexcept;

// Writes round(physical / scale). Returns false, writing nothing, when the
// value is not finite (for integer types) or does not fit the type's range.
// f32 fields take any value, NaN and infinities included (the receiver
// checks), narrowed to float.
bool write(hal::CanFrame& frame, const FieldDef& f, double physical) noexcept;
// As write(), but a value beyond the type's range is written as the nearest
// end of it (infinities too) and NaN as 0: telemetry sends a saturated
// reading rather than none, a host request arrives at the nearest end for
// the node to range-check. false only for bytes7.
bool write_saturated(hal::CanFrame& frame, const FieldDef& f, double physical) noexcept;

void read_bytes(const hal::CanFrame& frame, const FieldDef& f, std::span<std::uint8_t> out) noexcept;
void write_bytes(hal::CanFrame& frame, const FieldDef& f, std::span<const std::uint8_t> in) noexcept;

// f32 <-> raw bits, for raw32 fields (parameter values).
std::uint32_t float_bits(float v) noexcept;
float bits_float(std::uint32_t raw) noexcept;

// The message a frame is, from its identifier alone (nullptr: no such
// message or an extended / remote frame).
const MessageDef* classify(const hal::CanFrame& frame) noexcept;

}  // namespace tnv::fw::can
