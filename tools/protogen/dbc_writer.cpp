#include "tools/protogen/dbc_writer.hpp"

#include <bit>
#include <regex>
#include <string>
#include <vector>

#include "firmware/can/can_id.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/protocol_messages.hpp"
#include "hal/axis.hpp"
#include "tools/protogen/text_format.hpp"

namespace tnv::protogen {

namespace {

using fw::can::Direction;
using fw::can::FieldDef;
using fw::can::MessageDef;
using fw::can::WireType;

// DBC wants the identifier escaped for double quotes only. (Not `quoted`:
// std::quoted would win it by argument-dependent lookup where <iomanip> is in.)
std::string dbc_quoted(std::string_view s) {
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
  line += dbc_quoted(f.unit);
  line += ' ';
  line += receiver;
  line += '\n';
  return line;
}

bool is_param_message(const MessageDef& m) {
  return std::string_view(m.name) == "param_request" || std::string_view(m.name) == "param_reply";
}

// "x.sliding.gamma" -> "x_sliding_gamma": DBC names are C identifiers.
std::string param_signal_name(const fw::can::ParamDef& p) {
  std::string name = p.name;
  for (char& c : name)
    if (c == '.') c = '_';
  return name;
}

// PARAM_REQUEST / PARAM_REPLY: `param` multiplexes `value`, one signal per
// parameter with its type, unit and range, so a DBC tool decodes
// x.sliding.gamma = 0.25 as 0.25 (the raw `value` stays for commit/discard,
// whose `param` is a count).
std::string param_signal_lines(const char* receiver) {
  std::string out;
  for (const fw::can::ParamDef& p : fw::can::param_table()) {
    const bool is_signed = p.type == fw::can::ParamType::f32 || p.type == fw::can::ParamType::i32;
    append(out, " SG_ ", param_signal_name(p), " m", std::to_string(p.id), " : 32|32@1", is_signed ? "-" : "+",
           " (1,0) [", number(p.min), "|", number(p.max), "] ", dbc_quoted(p.unit), " ", receiver, "\n");
  }
  return out;
}

// The heartbeat's `errors` word, one 1-bit signal per bit beside it.
std::string heartbeat_bit_lines(const FieldDef& errors) {
  std::string out;
  for (const fw::can::HeartbeatBitDoc& b : fw::can::kHeartbeatBits) {
    int bit = 0;
    while ((b.mask >> bit) != 1u) ++bit;
    append(out, " SG_ ", b.name, " : ", std::to_string(errors.byte_offset * 8 + static_cast<unsigned>(bit)),
           "|1@1+ (1,0) [0|1] \"\" HOST\n");
  }
  return out;
}

// The heartbeat's `axes` byte: homed_<axis> and shaper_<axis>, one 1-bit
// signal per axis of the axis list.
struct AxisBitSignal {
  std::string name;
  unsigned bit;  // within the byte
  std::string doc;
};
std::vector<AxisBitSignal> heartbeat_axis_signals() {
  std::vector<AxisBitSignal> out;
  for (const hal::Axis a : hal::kAxes) {
    const std::string n = hal::axis_label(a);
    out.push_back({"homed_" + n, static_cast<unsigned>(std::countr_zero(fw::can::hb_homed_bit(a))), n + " is homed"});
    out.push_back({"shaper_" + n, static_cast<unsigned>(std::countr_zero(fw::can::hb_shaper_bit(a))),
                   "input shaper on, " + n});
  }
  return out;
}
std::string heartbeat_axis_lines(const FieldDef& axes) {
  std::string out;
  for (const AxisBitSignal& s : heartbeat_axis_signals())
    append(out, " SG_ ", s.name, " : ", std::to_string(axes.byte_offset * 8 + s.bit), "|1@1+ (1,0) [0|1] \"\" HOST\n");
  return out;
}

// A cyclic message says "every tlm.<name>_ms" in its doc: that
// parameter's default is its cycle time.
int default_cycle_ms(const MessageDef& m) {
  static const std::regex period_param(R"(every (tlm\.[a-z_]+_ms))");
  std::cmatch match;
  if (!std::regex_search(m.doc, match, period_param)) return 0;
  const fw::can::ParamDef* p = fw::can::find_param(match[1].str().c_str());
  return p == nullptr ? 0 : static_cast<int>(p->get(fw::can::default_node_settings()));
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
    const char* receiver = to_node ? "TNV_NODE" : "HOST";
    for (const FieldDef& f : m.fields) {
      std::string line = signal_line(f, receiver);
      if (is_param_message(m) && std::string_view(f.name) == "param") line.replace(line.find(" : "), 3, " M : ");
      out += line;
      if (std::string_view(m.name) == "heartbeat" && std::string_view(f.name) == "errors") out += heartbeat_bit_lines(f);
      if (std::string_view(m.name) == "heartbeat" && std::string_view(f.name) == "axes") out += heartbeat_axis_lines(f);
    }
    if (is_param_message(m)) out += param_signal_lines(receiver);
    out += '\n';
  }
  append(out, "CM_ \"TNV-40 controller CAN protocol ", version,
         ", generated from firmware/can/ by tnv-protogen; identifiers for node ", std::to_string(node),
         " (identifier = message id << ", std::to_string(fw::can::kNodeIdBits), " | node id).\";\n");
  for (const MessageDef& m : fw::can::kMessages) {
    const std::string id = std::to_string(fw::can::make_can_id(m.id, node));
    append(out, "CM_ BO_ ", id, " ", dbc_quoted(m.doc), ";\n");
    for (const FieldDef& f : m.fields) append(out, "CM_ SG_ ", id, " ", f.name, " ", dbc_quoted(f.doc), ";\n");
    if (is_param_message(m))
      for (const fw::can::ParamDef& p : fw::can::param_table())
        append(out, "CM_ SG_ ", id, " ", param_signal_name(p), " ", dbc_quoted(std::string(p.name) + ": " + p.doc), ";\n");
    if (std::string_view(m.name) == "heartbeat")
      for (const fw::can::HeartbeatBitDoc& b : fw::can::kHeartbeatBits)
        append(out, "CM_ SG_ ", id, " ", b.name, " ", dbc_quoted(b.doc), ";\n");
    if (std::string_view(m.name) == "heartbeat")
      for (const AxisBitSignal& s : heartbeat_axis_signals())
        append(out, "CM_ SG_ ", id, " ", s.name, " ", dbc_quoted(s.doc), ";\n");
  }
  // Cycle times: the defaults of the tlm.*_ms parameters (0 = sent on request or event).
  out += "BA_DEF_ BO_ \"GenMsgCycleTime\" INT 0 60000;\n";
  out += "BA_DEF_DEF_ \"GenMsgCycleTime\" 0;\n";
  for (const MessageDef& m : fw::can::kMessages)
    if (const int ms = default_cycle_ms(m); ms > 0)
      append(out, "BA_ \"GenMsgCycleTime\" BO_ ", std::to_string(fw::can::make_can_id(m.id, node)), " ",
             std::to_string(ms), ";\n");
  for (const MessageDef& m : fw::can::kMessages) {
    const std::string id = std::to_string(fw::can::make_can_id(m.id, node));
    for (const FieldDef& f : m.fields) {
      if (f.values[0] == '\0') continue;
      append(out, "VAL_ ", id, " ", f.name);
      for (const auto& [value, name] : value_table(f.values)) append(out, " ", std::to_string(value), " ", dbc_quoted(name));
      out += " ;\n";
    }
    if (is_param_message(m))
      for (const fw::can::ParamDef& p : fw::can::param_table()) {
        if (p.values[0] == '\0') continue;
        append(out, "VAL_ ", id, " ", param_signal_name(p));
        for (const auto& [value, name] : value_table(p.values)) append(out, " ", std::to_string(value), " ", dbc_quoted(name));
        out += " ;\n";
      }
  }
  for (const MessageDef& m : fw::can::kMessages) {
    const std::string id = std::to_string(fw::can::make_can_id(m.id, node));
    for (const FieldDef& f : m.fields)
      if (f.type == WireType::f32) append(out, "SIG_VALTYPE_ ", id, " ", f.name, " : 1;\n");
    if (is_param_message(m))
      for (const fw::can::ParamDef& p : fw::can::param_table())
        if (p.type == fw::can::ParamType::f32) append(out, "SIG_VALTYPE_ ", id, " ", param_signal_name(p), " : 1;\n");
  }
  return out;
}

}  // namespace tnv::protogen
