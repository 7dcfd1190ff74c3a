#include "tools/protogen/protocol_doc_writer.hpp"

#include <bit>
#include <cmath>
#include <string>

#include "firmware/can/can_id.hpp"
#include "firmware/can/capture_channels.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/can/protocol_messages.hpp"
#include "hal/axis.hpp"
#include "tools/protogen/bus_load.hpp"
#include "tools/protogen/text_format.hpp"

namespace tnv::protogen {

namespace {

using namespace fw::can;

std::string hex(unsigned v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%0*X", digits, v);
  return buf;
}

std::string percent(double fraction) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f %%", 100.0 * fraction);
  return buf;
}

// Table cells: a '|' would split the cell.
std::string cell(std::string_view s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

void framing(std::string& out, const NodeSettings& d) {
  append(out, "## Framing\n\n",
         "- Classic CAN (2.0A), 11-bit identifiers, default bit rate ", std::to_string(d.can.bitrate_kbit),
         " kbit/s (parameter `can.bitrate_kbit`). Every message has a fixed length (the DLC column below).\n",
         "- Identifier = message id << ", std::to_string(kNodeIdBits), " | node id. The message id (",
         std::to_string(11 - kNodeIdBits), " bits) is in the high bits, so arbitration ",
         "orders by message: an ESTOP to any node wins over every other frame on the bus; commands rank above ",
         "telemetry (BORE_GAUGE, which waits between parts, ranks among it), the capture upload last. Node ids are 1..",
         std::to_string(kMaxNodeId), " (parameter `can.node_id`, default ", std::to_string(d.can.node_id),
         "); node 0 is broadcast and carries only ESTOP and COMMAND `stop`.\n",
         "- Requests go host -> node with the node's id; the node answers with its own id.\n",
         "- Fields are little-endian and byte-aligned; physical value = raw x scale. `f32` is an IEEE-754 ",
         "single; `raw32` holds a parameter value: the f32 bits, or the integer, by the parameter's type.\n",
         "- CAN FD is not used; the payloads fit classic frames.\n",
         "- Per-axis messages (TLM_POSITION_<AXIS>, TLM_SLIDING_<AXIS>, TLM_DAC_<AXIS>) come in ",
         "blocks of ", std::to_string(kAxisBlock), " ids: block base + axis index, one message per axis of the ",
         "axis list (hal/axis.hpp), so an axis is a line in that list. JOG names the axis it jogs.\n\n");
}

void message_summary(std::string& out) {
  append(out, "## Messages\n\n| id | identifier, node 1 | message | direction | DLC | what it is |\n",
         "|---|---|---|---|---|---|\n");
  for (const MessageDef& m : kMessages)
    append(out, "| ", hex(m.id, 2), " | ", hex(make_can_id(m.id, 1), 3), " | ", upper(m.name), " | ",
           m.direction == Direction::to_node ? "host -> node" : "node -> host", " | ", std::to_string(m.dlc), " | ",
           cell(m.doc), " |\n");
  out += '\n';
}

void message_layouts(std::string& out) {
  for (const MessageDef& m : kMessages) {
    if (m.fields.empty()) continue;
    append(out, "### ", upper(m.name), " (", hex(m.id, 2), ")\n\n| bytes | field | type | scale | unit | values | meaning |\n",
           "|---|---|---|---|---|---|---|\n");
    for (const FieldDef& f : m.fields) {
      const std::size_t last = f.byte_offset + wire_size(f.type) - 1;
      const std::string bytes =
          last == f.byte_offset ? std::to_string(f.byte_offset) : std::to_string(f.byte_offset) + "-" + std::to_string(last);
      append(out, "| ", bytes, " | ", f.name, " | ", to_string(f.type), " | ", number(f.scale), " | ", f.unit, " | ",
             cell(f.values), " | ", cell(f.doc), " |\n");
    }
    out += '\n';
  }
}

void codes(std::string& out) {
  out += "## Result codes\n\nCOMMAND_ACK.result, PARAM_REPLY.result, CAPTURE_STATUS.result and BORE_INFEED.result. A refused request changes nothing.\n\n| code | name |\n|---|---|\n";
  for (std::uint8_t i = 0; i < kErrorCodeCount; ++i)
    append(out, "| ", std::to_string(i), " | ", to_string(static_cast<ErrorCode>(i)), " |\n");
  out += "\n## Commands (COMMAND.code)\n\n| code | name |\n|---|---|\n";
  for (std::uint8_t i = 0; i < kCommandCodeCount; ++i)
    append(out, "| ", std::to_string(i), " | ", to_string(static_cast<CommandCode>(i)), " |\n");
  out += "\nzero, select_controller, load_params and restore_defaults need the machine at rest (else busy); save_params too.\n";
  out += "save_params and load_params are answered when the node's worker has done the I/O (milliseconds later); so is "
         "a parameter change (PARAM_REQUEST set or commit, SHAPER, shaper_enable) that needs an input-shaper design the "
         "node does not hold yet: the design is made off the real-time loop and the request is then handled as if it "
         "arrived at that moment (every check again, one answer with its tag). Meanwhile other parameter changes and "
         "storage commands answer busy (docs/safety.md \"Real-time budget\").\n";
  out += "enter_commissioning needs the servo disabled (else busy) and no fault latched (else faulted), and on tnv-fw "
         "the config's [safety] allow_commissioning (else not_permitted); the mode ends at leave_commissioning, enable, "
         "any accepted motion or a fault (docs/safety.md \"Commissioning\"). 10 and 11 are reserved (unknown_command).\n";
  out += "feed_hold, feed_resume, feed_override (arg: percent of the programmed feeds, 0..150) and end_program act on "
         "the running program (busy when none runs); abort_program stops it on the path and drops the rest (ok when "
         "nothing runs, busy when another motion does); program_status answers and sends a PROGRAM_STATUS, to any "
         "host.\n";
  out += "\n## Heartbeat error bits (HEARTBEAT.errors)\n\n| bit | name | meaning |\n|---|---|---|\n";
  for (const HeartbeatBitDoc& b : kHeartbeatBits) {
    int bit = 0;
    while ((1u << bit) != b.mask) ++bit;
    append(out, "| ", std::to_string(bit), " | ", b.name, " | ", b.doc, " |\n");
  }
  out += "\n## Heartbeat axis bits (HEARTBEAT.axes)\n\nOne pair per axis of the axis list (hal/axis.hpp), by axis "
         "index; room for four axes.\n\n| bit | name | meaning |\n|---|---|---|\n";
  for (const hal::Axis a : hal::kAxes) {
    const std::string n = hal::axis_label(a);
    append(out, "| ", std::to_string(std::countr_zero(hb_homed_bit(a))), " | homed_", n, " | ", n,
           " is homed: its frame is the home switch's index (docs/safety.md \"Homing\") |\n");
  }
  for (const hal::Axis a : hal::kAxes) {
    const std::string n = hal::axis_label(a);
    append(out, "| ", std::to_string(std::countr_zero(hb_shaper_bit(a))), " | shaper_", n, " | input shaper on, ", n,
           " |\n");
  }
  out += '\n';
}

void parameters(std::string& out, const NodeSettings& d) {
  append(out, "## Parameters\n\n",
         "PARAM_REQUEST `get` reads, `set` writes one parameter and applies it, `stage` collects writes that ",
         "`commit` applies together between two ticks (or refuses together), `discard` drops them. Apply: ",
         "`live` any time, also while moving; `idle` only at rest (refused with busy while a motion runs); ",
         "`restart` stored now, used from the next start. Access `rw commissioning`: a safety parameter, changed only in ",
         "commissioning mode (COMMAND enter_commissioning while disabled; outside it a change is refused with ",
         "commissioning_required, docs/safety.md \"Commissioning\"). Defaults are the papers' values (S1 Tables 1/2, ",
         "eq. 31; the boring planner's S4 Table 1) and the PID tuned by the stated rule. ", std::to_string(param_table().size()), " parameters.\n\n",
         "| id | name | type | unit | range | default | access | apply | meaning |\n",
         "|---|---|---|---|---|---|---|---|---|\n");
  for (const ParamDef& p : param_table()) {
    std::string range = p.access == Access::read_only ? std::string("-") : number(p.min) + " .. " + number(p.max);
    if (p.values[0] != '\0') range = p.values;
    // The build id is the commit being built: the document states what it is, not one build's value.
    const bool per_build = std::string_view(p.name) == "sys.build_id";
    append(out, "| ", hex(p.id, 4), " | `", p.name, "` | ", to_string(p.type), " | ", p.unit, " | ", cell(range), " | ",
           per_build ? std::string("this build's") : number(p.get(d)), " | ", safety_param(p) ? "rw commissioning" : to_string(p.access), " | ", to_string(p.apply), " | ", cell(p.doc), " |\n");
  }
  out += '\n';
}

void capture(std::string& out, const NodeSettings& d) {
  append(out, "## Capture channels\n\n",
         "Bit n of the 64-bit channel mask records channel n (`capture.channels` holds bits 0-31, ",
         "`capture.channels_high` bits 32-63; an arm with no channel is refused `out_of_range`), one 32-bit ",
         "little-endian value per tick (or every ",
         "`capture.decimation` ticks). The image is sample-major with the selected channels in bit order; the ",
         "buffer holds ", std::to_string(kCaptureCapacityWords), " values. Upload: CAPTURE_CONTROL upload (offset, ",
         "frames) -> that many CAPTURE_DATA frames, sequence 0.., 7 image bytes each; a gap in the sequence means ",
         "re-request the block. At ", std::to_string(d.can.bitrate_kbit), " kbit/s an upload moves about ",
         number(capture_upload_bytes_per_s(d.can.bitrate_kbit) / 1000.0), " kB/s.\n\n",
         "| bit | channel | type | scale | unit | meaning |\n|---|---|---|---|---|---|\n");
  for (const ChannelDef& c : kCaptureChannels)
    append(out, "| ", std::to_string(c.bit), " | ", c.name, " | ", to_string(c.type), " | ", number(c.scale), " | ",
           c.unit, " | ", cell(c.doc), " |\n");
  out += "\nDefault channels:";
  for (const ChannelDef& c : kCaptureChannels)
    if ((kDefaultCaptureChannels >> c.bit) & 1u) append(out, " ", c.name);
  out += ".\n\n";
}

void malformed(std::string& out) {
  out += R"(## Malformed and foreign frames

| frame | what the node does |
|---|---|
| extended (29-bit) identifier | ignored |
| another node's id | ignored |
| a node -> host message id (another node's reply or telemetry) | ignored |
| unused message id | ignored (counted) |
| known request with the wrong DLC | the request's reply with `bad_length`; nothing changes |
| ESTOP with any DLC | acted on (safety first) |
| COMMAND with an unknown code | COMMAND_ACK `unknown_command` |
| COMMAND / JOG / MOVE / SHAPER / EXCITE with a bad axis byte | COMMAND_ACK `bad_axis`; no axis changes |
| PARAM_REQUEST with an unknown op | PARAM_REPLY `unknown_command` |
| PARAM_REQUEST for an unknown id | PARAM_REPLY `unknown_id`, value 0 |
| set / stage of a read-only parameter | `read_only` |
| NaN or infinity (any f32 field) | `not_finite` |
| value outside the range, or not one of the allowed values | `out_of_range` |
| a set that breaks a cross-parameter rule | `invalid`; PARAM_REPLY.value is the unchanged value |
| idle-only parameter or command while moving | `busy` |
| CAPTURE_CONTROL with an unknown op | CAPTURE_STATUS `unknown_command` |
| upload past the end of the image, or with no capture | CAPTURE_STATUS `not_ready` |
| BORE_GAUGE with an unknown op | BORE_INFEED `unknown_command`, detail 1 |
| BORE_GAUGE record / restart from a host without command ownership | BORE_INFEED `not_owner` |
| BORE_GAUGE while `bore.enable` is off | BORE_INFEED `not_ready` |
| BORE_GAUGE record / restart while a save or load runs | BORE_INFEED `busy` |
| BORE_GAUGE record with a reading of -32768 (no reading) | BORE_INFEED `not_finite`, detail 3 (top) or 4 (bottom) |
| BORE_GAUGE record of a part other than `bore.parts` + 1 (a repeat, a skip) | BORE_INFEED `out_of_range`, detail 2 |
| BORE_GAUGE record of a start-up part whose deflection (eq. (11)) is <= 0 | BORE_INFEED `invalid`, detail 3 or 4 |
| broadcast (node 0) other than ESTOP / COMMAND stop | ignored |
| SEGMENT with an unknown kind | COMMAND_ACK `out_of_range`, detail = `kind` |
| SEGMENT_TAIL without its SEGMENT (none pending, or another tag) | COMMAND_ACK `not_ready`; a pending SEGMENT of another tag is answered `not_ready` too |
| a SEGMENT while the previous one still waits for its tail | the waiting one is answered `not_ready`, the new one waits |
| SEGMENT / SEGMENT_TAIL from a host without command ownership | COMMAND_ACK `not_owner`; the owner's waiting SEGMENT is kept |

)";
}

void bus_load(std::string& out, const NodeSettings& d) {
  const BusLoad load = telemetry_load(d);
  append(out, "## Bus load\n\n",
         "A classic 8-byte frame with an 11-bit identifier takes ", std::to_string(frame_bits_nominal(8)),
         " bit times including the interframe space, and up to ", std::to_string(frame_bits_worst(8)),
         " with worst-case bit stuffing. The default cyclic set (HEARTBEAT every ", std::to_string(d.telemetry.heartbeat_ms),
         " ms, TLM_POSITION_<AXIS>, an 8-byte frame per axis with position and following error, every ",
         std::to_string(d.telemetry.position_ms), " ms) is ", number(load.frames_per_s), " frames/s: ",
         percent(load.load_nominal), " to ", percent(load.load_worst), " of ", std::to_string(d.can.bitrate_kbit),
         " kbit/s. Streaming two 8-byte frames per 1 ms tick would take ",
         percent(2000.0 * frame_bits_nominal(8) / (1000.0 * d.can.bitrate_kbit)), " to ",
         percent(2000.0 * frame_bits_worst(8) / (1000.0 * d.can.bitrate_kbit)),
         ": full-rate traces of long runs are captured on the node and uploaded afterwards, and `tnvctl run` takes this ",
         "load only while a program runs, to score it (telemetry loses arbitration to every control frame).\n\n",
         "A streamed program costs three 8-byte frames per line or arc (SEGMENT, SEGMENT_TAIL and the COMMAND_ACK; a ",
         "dwell two): ", std::to_string(3 * frame_bits_nominal(8)), " bit times, so the bus carries at most ",
         number(std::floor(1000.0 * d.can.bitrate_kbit / (3.0 * frame_bits_nominal(8)))),
         " elements/s with nothing else on it (docs/motion.md \"Streaming\" has the measured rates).\n");
}

}  // namespace

std::string write_protocol_doc() {
  const NodeSettings d = default_node_settings();
  std::string out;
  append(out, "# TNV-40 CAN protocol, version ", std::to_string(kProtocolVersion), "\n\n",
         "Generated by `tnv-protogen` from the protocol table in `firmware/can/` (protocol_messages.hpp, ",
         "param_table.cpp, capture_channels.hpp, protocol_enums.hpp). Do not edit: change the table and run ",
         "`cmake --build build/release --target update-protocol-docs`. A test fails when this file or ",
         "`docs/tnv.dbc` differs from what the table generates. The same table drives the firmware and the host ",
         "codec.\n\n",
         "In `docs/tnv.dbc`, PARAM_REQUEST and PARAM_REPLY multiplex their value on `param`: one signal per ",
         "parameter (`x_sliding_gamma`, its id as the multiplexer value) with its type (float or integer), unit, ",
         "range and value names, so a DBC tool decodes x.sliding.gamma = 0.25 as 0.25; the raw `value` stays for ",
         "commit and discard, whose `param` is a count. HEARTBEAT has each `errors` bit as a 1-bit signal beside the ",
         "word, and the cyclic messages carry `GenMsgCycleTime` (the defaults of their `tlm.*_ms` parameters). ",
         "A test decodes a session `tnvctl --trace` recorded with Debian's python3-canmatrix ",
         "(`tests/protocol/dbc_decode_check.py`).\n\n");
  framing(out, d);
  message_summary(out);
  message_layouts(out);
  codes(out);
  parameters(out, d);
  capture(out, d);
  malformed(out);
  bus_load(out, d);
  return out;
}

}  // namespace tnv::protogen
