#include "tools/protogen/dbc_writer.hpp"

#include "firmware/can/can_id.hpp"
#include "firmware/can/protocol_messages.hpp"
#include "tools/protogen/text_format.hpp"

namespace tnv::protogen {

namespace {

using fw::can::Direction;
using fw::can::FieldDef;
using fw::can::MessageDef;
using fw::can::WireType;

// DBC wants the identifier escaped for double quotes only.
std::string quoted(std::string_view s) {
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '\\';
    out += c;
  }
  out += '"';
  return out;
}

void raw_range(const FieldDef& f, double& lo, double& hi) {
  switch (f.type) {
    case WireType::u8: lo = 0; hi = 255; break;
    case WireType::i8: lo = -128; hi = 127; break;
    case WireType::u16: lo = 0; hi = 65535; break;
    case WireType::u24: lo = 0; hi = 16777215.0; break;
    case WireType::i16: lo = -32768; hi = 32767; break;
    case WireType::i24: lo = -8388608.0; hi = 8388607.0; break;
    case WireType::u32:
    case WireType::raw32: lo = 0; hi = 4294967295.0; break;
    case WireType::i32: lo = -2147483648.0; hi = 2147483647.0; break;
    case WireType::f32:
    case WireType::bytes7: lo = 0; hi = 0; break;  // 0|0: no range stated
  }
}

std::string signal_line(const FieldDef& f, const char* receiver) {
  double lo = 0;
  double hi = 0;
  raw_range(f, lo, hi);
  std::string line = " SG_ ";
  line += f.name;
  line += " : ";
  line += std::to_string(f.byte_offset * 8);
  line += '|';
  line += std::to_string(8 * fw::can::wire_size(f.type));
  line += "@1";
  line += fw::can::is_signed(f.type) ? '-' : '+';
  line += " (";
  line += number(f.scale);
  line += ",0) [";
  line += number(lo * f.scale);
  line += '|';
  line += number(hi * f.scale);
  line += "] ";
  line += quoted(f.unit);
  line += ' ';
  line += receiver;
  line += '\n';
  return line;
}

}  // namespace

std::string write_dbc(std::uint8_t node) {
  std::string out;
  const std::string version = std::to_string(fw::can::kProtocolVersion);
  append(out, "VERSION \"tnv40-can-protocol-", version, "\"\n\n");
  out += "NS_ :\n    CM_\n    BA_DEF_\n    BA_\n    VAL_\n    SIG_VALTYPE_\n\n";
  out += "BS_:\n\n";
  out += "BU_: HOST TNV_NODE\n\n";
  for (const MessageDef& m : fw::can::kMessages) {
    const std::uint32_t id = fw::can::make_can_id(m.id, node);
    const bool to_node = m.direction == Direction::to_node;
    append(out, "BO_ ", std::to_string(id), " ", upper(m.name), ": ", std::to_string(m.dlc), " ",
           to_node ? "HOST" : "TNV_NODE", "\n");
    for (const FieldDef& f : m.fields) out += signal_line(f, to_node ? "TNV_NODE" : "HOST");
    out += '\n';
  }
  append(out, "CM_ \"TNV-40 controller CAN protocol ", version,
         ", generated from firmware/can/ by tnv-protogen; identifiers for node ", std::to_string(node),
         " (identifier = message id << 6 | node id).\";\n");
  for (const MessageDef& m : fw::can::kMessages) {
    const std::string id = std::to_string(fw::can::make_can_id(m.id, node));
    append(out, "CM_ BO_ ", id, " ", quoted(m.doc), ";\n");
    for (const FieldDef& f : m.fields) append(out, "CM_ SG_ ", id, " ", f.name, " ", quoted(f.doc), ";\n");
  }
  for (const MessageDef& m : fw::can::kMessages) {
    const std::string id = std::to_string(fw::can::make_can_id(m.id, node));
    for (const FieldDef& f : m.fields) {
      if (f.values[0] == '\0') continue;
      append(out, "VAL_ ", id, " ", f.name);
      for (const auto& [value, name] : value_table(f.values)) append(out, " ", std::to_string(value), " ", quoted(name));
      out += " ;\n";
    }
  }
  for (const MessageDef& m : fw::can::kMessages) {
    const std::string id = std::to_string(fw::can::make_can_id(m.id, node));
    for (const FieldDef& f : m.fields)
      if (f.type == WireType::f32) append(out, "SIG_VALTYPE_ ", id, " ", f.name, " : 1;\n");
  }
  return out;
}

}  // namespace tnv::protogen
