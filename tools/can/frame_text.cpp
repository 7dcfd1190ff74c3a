#include "tools/can/frame_text.hpp"

#include <cstdio>
#include <string_view>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "hal/axis.hpp"
#include "tools/can/param_text.hpp"
#include "tools/protogen/text_format.hpp"

namespace tnv::can_host {

namespace {

namespace can = fw::can;

std::string hex_bytes(const hal::CanFrame& frame) {
  std::string out;
  char buf[4];
  for (std::size_t i = 0; i < frame.dlc && i < frame.data.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%02X", frame.data[i]);
    out += buf;
  }
  return out;
}

// The name of `raw` in a "0=a 1=b" table, or "" when it has none.
std::string value_name(const char* values, long raw) {
  for (const auto& [value, name] : protogen::value_table(values))
    if (value == raw) return name;
  return "";
}

std::string field_text(const hal::CanFrame& frame, const can::FieldDef& f) {
  if (f.type == can::WireType::bytes7) return hex_bytes(frame).substr(2);
  const double v = can::read(frame, f);
  if (f.values[0] != '\0')
    if (std::string name = value_name(f.values, static_cast<long>(v)); !name.empty()) return name;
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  std::string out = buf;
  if (f.unit[0] != '\0') out.append(" ").append(f.unit);
  return out;
}

std::string heartbeat_bits(std::uint32_t errors) {
  std::string out = "[";
  for (const can::HeartbeatBitDoc& b : can::kHeartbeatBits)
    if ((errors & b.mask) != 0) out.append(out.size() > 1 ? " " : "").append(b.name);
  return out + "]";
}

// HEARTBEAT.axes: homed_<axis> and shaper_<axis>, named from the axis list.
std::string heartbeat_axis_bits(std::uint32_t axes) {
  std::string out = "[";
  for (const hal::Axis a : hal::kAxes) {
    if ((axes & can::hb_homed_bit(a)) != 0) out.append(out.size() > 1 ? " " : "").append("homed_").append(hal::axis_label(a));
    if ((axes & can::hb_shaper_bit(a)) != 0) out.append(out.size() > 1 ? " " : "").append("shaper_").append(hal::axis_label(a));
  }
  return out + "]";
}

}  // namespace

std::string frame_text(const hal::CanFrame& frame) {
  const can::MessageDef* m = can::classify(frame);
  char head[64];
  if (m == nullptr) {
    std::snprintf(head, sizeof head, "%s 0x%X", frame.extended ? "extended" : "unknown", static_cast<unsigned>(frame.id));
    return std::string(head) + " [" + std::to_string(frame.dlc) + "] " + hex_bytes(frame) + " (not this protocol)";
  }
  std::string out;
  for (const char c : std::string_view(m->name)) out += static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
  out.append(" node ").append(std::to_string(can::node_of(frame.id)));
  if (frame.dlc < m->dlc) return out + " [" + std::to_string(frame.dlc) + "] " + hex_bytes(frame) + " (short frame)";
  const bool param_message = std::string_view(m->name) == "param_request" || std::string_view(m->name) == "param_reply";
  const can::ParamDef* param = nullptr;
  for (const can::FieldDef& f : m->fields) {
    const std::string_view name(f.name);
    out.append("  ").append(f.name).append("=");
    if (name == "tag") {
      char buf[8];
      std::snprintf(buf, sizeof buf, "0x%02X", static_cast<unsigned>(can::read_raw(frame, f)));
      out += buf;
    } else if (param_message && name == "param") {
      const std::uint32_t id = can::read_raw(frame, f);
      param = can::find_param(static_cast<std::uint16_t>(id));
      char buf[16];
      std::snprintf(buf, sizeof buf, "0x%04X", id);
      out += buf;
      if (param != nullptr) out.append(" (").append(param->name).append(")");
    } else if (param_message && name == "value" && param != nullptr) {
      const double v = can::from_wire(*param, can::read_raw(frame, f));
      out += format_param_value(*param, v);
      if (param->unit[0] != '\0') out.append(" ").append(param->unit);
    } else if (std::string_view(m->name) == "heartbeat" && name == "errors") {
      out += heartbeat_bits(can::read_raw(frame, f));
    } else if (std::string_view(m->name) == "heartbeat" && name == "axes") {
      out += heartbeat_axis_bits(can::read_raw(frame, f));
    } else {
      out += field_text(frame, f);
    }
  }
  return out;
}

}  // namespace tnv::can_host
