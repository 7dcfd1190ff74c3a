#pragma once
// THE protocol table, part 1: every CAN message. The firmware codec, the
// host codec, docs/tnv.dbc and docs/can-protocol.md all come from here
// (tools/protogen writes the two documents; a test compares them with the
// checked-in copies). Identifier = (id << 6) | node (can_id.hpp).
// Parameters are in param_table.hpp, capture channels in capture_channels.hpp.
#include <array>

#include "firmware/can/can_id.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/can/value_list.hpp"
#include "firmware/can/wire.hpp"
#include "firmware/compensation/excitation.hpp"
#include "firmware/motion/segment.hpp"
#include "firmware/shaper/shaper_type.hpp"
#include "firmware/spindle/spindle_control.hpp"
#include "firmware/supervisor/fault.hpp"
#include "firmware/tick/tick_record.hpp"
#include "hal/axis.hpp"

namespace tnv::fw::can {

// Per-axis messages come in blocks of kAxisBlock ids, one id per axis of
// TNV_AXES (block base + axis index): a new axis is a line in the axis list,
// up to kAxisBlock axes.
inline constexpr std::uint8_t kAxisBlock = 4;
static_assert(hal::kAxisCount <= kAxisBlock, "per-axis CAN messages: an axis beyond kAxisBlock needs wider id blocks");

// Lower id = higher priority: commands and their answers (0x00-0x13), then
// the node-wide telemetry, then the per-axis telemetry blocks, the capture
// upload last; BORE_GAUGE and BORE_INFEED, which wait between parts, rank
// among the telemetry. 0x1E-0x1F, 0x24-0x27 and 0x30-0x3D are free.
enum class MessageId : std::uint8_t {
  estop = 0x00,
  fault_event = 0x01,
  command = 0x02,
  command_ack = 0x03,
  jog = 0x04,
  move = 0x05,
  circle = 0x06,
  shaper = 0x07,
  param_request = 0x08,
  param_reply = 0x09,
  capture_control = 0x0A,
  capture_status = 0x0B,
  heartbeat = 0x0C,
  excite = 0x0D,
  segment = 0x0E,
  segment_tail = 0x0F,
  spindle = 0x10,
  segment_z = 0x11,
  segment_plane = 0x12,
  probe_result = 0x13,
  tlm_output = 0x14,
  tlm_contour = 0x15,
  tlm_arsc = 0x16,
  program_status = 0x17,
  program_tool = 0x18,
  probe_result_z = 0x19,
  bore_gauge = 0x1A,
  bore_infeed = 0x1B,
  tlm_spindle = 0x1C,
  probe_rest = 0x1D,
// The per-axis blocks: TLM_POSITION_<AXIS> from 0x20, TLM_SLIDING_<AXIS>
// from 0x28, TLM_DAC_<AXIS> from 0x2C (0x24-0x27 free).
#define TNV_AXIS_MESSAGE_IDS(name, ...)                                      \
  tlm_position_##name = 0x20 + static_cast<std::uint8_t>(hal::Axis::name),  \
  tlm_sliding_##name = 0x28 + static_cast<std::uint8_t>(hal::Axis::name),   \
  tlm_dac_##name = 0x2C + static_cast<std::uint8_t>(hal::Axis::name),
  TNV_AXES(TNV_AXIS_MESSAGE_IDS)
#undef TNV_AXIS_MESSAGE_IDS
  capture_data = 0x3E,
  // 0x3F is never used: its identifiers for nodes 16-31 (0x7F0-0x7FF) are
  // the ones CAN 2.0A forbids (the seven most significant bits recessive).
};

namespace detail {

// a + b, at compile time, in a buffer of N (a longer text fails the build).
template <std::size_t N>
constexpr std::array<char, N> joined_text(const char* a, const char* b) {
  std::array<char, N> out{};
  std::size_t at = 0;
  for (const char* s : {a, b})
    for (; *s != '\0'; ++s) out[at++] = *s;
  out[at] = '\0';
  return out;
}

// The enums' value lists, from their own name lists (value_list.hpp).
inline constexpr const char* kStateValues = kValueList<kMotionStateNames>;
inline constexpr const char* kFaultValues = kValueList<kFaultReasonNames>;
inline constexpr const char* kErrorValues = kValueList<kErrorCodeNames>;
// The axis fields' value lists, from the axis list (hal/axis.hpp).
inline constexpr const char* kAxisIndexValues = kValueList<hal::kAxisNames>;
inline constexpr auto kAxisValuesText = joined_text<64>(kAxisIndexValues, " 255=all");
inline constexpr auto kAxisOrNoneText = joined_text<64>("-1=none ", kAxisIndexValues);
inline constexpr const char* kAxisValues = kAxisValuesText.data();
inline constexpr const char* kTagDoc =
    "request tag: host id (high nibble, 1..15; 0 is refused) and the host's own sequence (low nibble); the reply "
    "echoes it";
inline constexpr const char* kReplyTagDoc = "the tag of the request answered (host id << 4 | its sequence)";

inline constexpr FieldDef kFaultEvent[] = {
    {"reason", WireType::u8, 0, 1, "", kFaultValues, "the latched fault"},
    {"axis", WireType::i8, 1, 1, "", kAxisOrNoneText.data(), "axis it concerns"},
    {"tick_low", WireType::u16, 2, 1, "tick", "", "low 16 bits of the tick count when it latched"},
    {"value", WireType::f32, 4, 1, "", "", "the offending value (mm, mm/s or ticks, by reason)"},
};
inline constexpr FieldDef kCommand[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"code", WireType::u8, 1, 1, "",
     kValueList<kCommandCodeNames>,
     "what to do"},
    {"axis", WireType::u8, 2, 1, "", kAxisValues, "axis for zero, select_controller, shaper_enable, home"},
    {"arg", WireType::u8, 3, 1, "", "",
     "select_controller: 0 pid, 1 dvsc, 2 rdvsc; shaper_enable: 0 off, 1 on; feed_override: percent, 0..150"},
    {"value", WireType::f32, 4, 1, "mm", "", "zero: the position to assign"},
};
inline constexpr FieldDef kCommandAck[] = {
    {"tag", WireType::u8, 0, 1, "", "", kReplyTagDoc},
    {"request", WireType::u8, 1, 1, "", "", "message id of the request acknowledged"},
    {"code", WireType::u8, 2, 1, "", "",
     "the request's command code (COMMAND); SEGMENT, SEGMENT_TAIL: free motion-queue slots after the request; else 0"},
    {"result", WireType::u8, 3, 1, "", kErrorValues, "0 ok, else why it was refused (nothing changed)"},
    {"state", WireType::u8, 4, 1, "", kStateValues, "motion state after the request"},
    {"fault", WireType::u8, 5, 1, "", kFaultValues, "latched fault after the request"},
    {"detail", WireType::u8, 6, 1, "", "",
     "request-specific: index of the offending field (in the message named by request), or 0"},
    {"owner", WireType::u8, 7, 1, "", "", "host id holding command ownership after the request, 0 none"},
};
inline constexpr FieldDef kJog[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"axis", WireType::u8, 1, 1, "", kAxisIndexValues, "the axis this frame jogs; the others keep their own streams"},
    {"speed", WireType::i16, 2, 0.01, "mm/s", "", "target speed of that axis (repeat within its jog.deadman_s)"},
};
inline constexpr FieldDef kMove[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"axis", WireType::u8, 1, 1, "", kAxisIndexValues, "axis to move; the others hold"},
    {"speed", WireType::u16, 2, 0.01, "mm/s", "", "cruise speed"},
    {"distance", WireType::f32, 4, 1, "mm", "", "signed distance from where the axis stands"},
};
inline constexpr FieldDef kCircle[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"reserved", WireType::u8, 1, 1, "", "", "0"},
    {"feed", WireType::u16, 2, 0.01, "mm/s", "", "path speed"},
    {"radius", WireType::f32, 4, 1, "mm", "", "radius; the table stands on the circle at (+r, 0) from its centre"},
};
inline constexpr FieldDef kShaper[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"axis", WireType::u8, 1, 1, "", kAxisIndexValues, "axis"},
    {"type", WireType::u8, 2, 1, "", kValueList<kShaperTypeNames>, "shaper family"},
    {"reserved", WireType::u8, 3, 1, "", "", "0"},
    {"zeta", WireType::u16, 4, 0.0001, "", "", "damping ratio of the mode"},
    {"freq", WireType::u16, 6, 0.01, "Hz", "", "mode frequency"},
};
inline constexpr FieldDef kExcite[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"axis", WireType::u8, 1, 1, "", kAxisIndexValues, "axis to excite; the others hold"},
    {"kind", WireType::u8, 2, 1, "", kValueList<kExcitationKindNames>,
     "step: u = level for duration; ramp: u = +-2 mm/s^2 t up to |level|; sweep / multisine: added to the holding "
     "controller's command, the reference moving at excite.carrier_mm_s meanwhile; multisine_open: the command "
     "itself; band excite.f_min_hz .. f_max_hz (docs/frequency-response.md)"},
    {"reserved", WireType::u8, 3, 1, "", "", "0"},
    {"duration", WireType::u16, 4, 0.001, "s", "",
     "step length / longest ramp (0.001 .. 10 s); sweep / multisine record (0.1 .. 40 s, multisine >= 2 periods of "
     "1 / f_min; on a carrier, carrier x duration must end inside the soft limits, else out_of_range)"},
    {"level", WireType::i16, 6, 0.01, "mm/s", "",
     "step level, the ramp's sign and largest |u|, the sweep's amplitude, the multisine's RMS x sqrt(2) (0 < |level| <= 100)"},
};
inline constexpr FieldDef kParamRequest[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"op", WireType::u8, 1, 1, "", kValueList<kParamOpNames>, "operation"},
    {"param", WireType::u16, 2, 1, "", "", "parameter id (param_table)"},
    {"value", WireType::raw32, 4, 1, "", "", "set/stage: the value, f32 or u32/i32 by the parameter's type"},
};
inline constexpr FieldDef kParamReply[] = {
    {"tag", WireType::u8, 0, 1, "", "", kReplyTagDoc},
    {"result", WireType::u8, 1, 1, "", kErrorValues, "0 ok, else why it was refused (nothing changed)"},
    {"param", WireType::u16, 2, 1, "", "",
     "parameter id; commit/discard: number of the host's staged parameters applied / dropped"},
    {"value", WireType::raw32, 4, 1, "", "",
     "value read back after the request (for a refused set: the unchanged value; unknown id: 0)"},
};
inline constexpr FieldDef kCaptureControl[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"op", WireType::u8, 1, 1, "", kValueList<kCaptureOpNames>, "operation"},
    {"frames", WireType::u8, 2, 1, "", "", "upload: number of CAPTURE_DATA frames to send (1..255)"},
    {"reserved", WireType::u8, 3, 1, "", "", "0"},
    {"offset", WireType::u32, 4, 1, "byte", "", "upload: first byte of the capture image to send"},
};
inline constexpr FieldDef kCaptureStatus[] = {
    {"tag", WireType::u8, 0, 1, "", "", kReplyTagDoc},
    {"state", WireType::u8, 1, 1, "", kValueList<kCaptureStateNames>, "capture state"},
    {"result", WireType::u8, 2, 1, "", kErrorValues, "result of the request that caused this reply"},
    {"channels", WireType::u8, 3, 1, "", "", "number of channels per sample"},
    {"decimation", WireType::u8, 4, 1, "tick", "", "ticks per sample"},
    {"samples", WireType::u24, 5, 1, "", "", "samples recorded; the image is samples x channels x 4 bytes"},
};
inline constexpr FieldDef kCaptureData[] = {
    {"sequence", WireType::u8, 0, 1, "", "", "frame index within the upload block, from 0"},
    {"data", WireType::bytes7, 1, 1, "", "", "7 bytes of the capture image (little-endian 32-bit values, "
                                              "sample-major, channels in bit order)"},
};
inline constexpr FieldDef kHeartbeat[] = {
    {"state", WireType::u8, 0, 1, "", kStateValues, "motion state"},
    {"fault", WireType::u8, 1, 1, "", kFaultValues, "latched fault reason"},
    {"errors", WireType::u16, 2, 1, "", "", "sub-system bits (protocol_enums.hpp HeartbeatBit)"},
    {"overruns", WireType::u8, 4, 1, "tick", "", "missed + late ticks since start (saturates at 255)"},
    {"free_slots", WireType::u8, 5, 1, "", "", "free slots in the motion queue (flow control for SEGMENT)"},
    {"owner", WireType::u8, 6, 1, "", "", "host id holding command ownership, 0 none"},
    {"axes", WireType::u8, 7, 1, "", "",
     "per-axis bits by axis index: bit i axis i is homed (its frame is the home switch's index, docs/safety.md "
     "\"Homing\"), bit 4 + i its input shaper is on"},
};
inline constexpr FieldDef kSegment[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"kind", WireType::u8, 1, 1, "",
     "0=line 1=arc_cw 2=arc_ccw 3=dwell 4=line_exact_stop 5=arc_cw_exact_stop 6=arc_ccw_exact_stop 7=rapid "
     "8=rapid_exact_stop 9=pause 10=spindle_forward 11=spindle_reverse 12=spindle_stop 13=tool_change "
     "14=probe_toward_or_error 15=probe_toward 16=probe_away_or_error 17=probe_away 18=line_per_rev "
     "19=line_per_rev_exact_stop 20=line_per_rev_depth 21=line_per_rev_depth_exact_stop",
     "element; the _exact_stop kinds end at rest before the next element starts; a rapid (G0) is a line that does "
     "not wait for the spindle, every other line and arc is a feed move that starts only with the spindle off or at "
     "speed; a pause (M0, M1, M6) is reached at rest and holds (PROGRAM_STATUS paused) until COMMAND cycle_start, "
     "the spindle left as it is; a tool_change (M6) is a pause whose cycle_start puts its tool in the spindle "
     "(PROGRAM_TOOL); the spindle kinds (S, M3, M4, M5) are reached at rest and carried out there in "
     "program order (a start while turning is a new speed or direction); dwell, pause, tool_change and the spindle "
     "kinds have no SEGMENT_TAIL; the probe kinds (G38.2, G38.3, G38.4, G38.5) are lines at their feed that end "
     "when the touch probe input changes (PROBE_RESULT), nothing may follow one until its PROBE_RESULT "
     "(probe_pending); the line_per_rev kinds (G95) are feed lines whose path speed is their feed per revolution "
     "(SEGMENT_TAIL centre_normal) times the spindle's measured speed, tick by tick through the feed override, "
     "and 0 (at rest on the path) while the spindle is not at speed; the line_per_rev_depth kinds are such lines "
     "along a boring pass's depth, their feed per revolution the boring planner's infeeds for the part (BORE_INFEED) "
     "along the bar's overhang (SEGMENT_TAIL centre_normal) at the path point, every tick"},
    {"x", WireType::i24, 2, 1e-4, "mm", "",
     "end point x (line, arc); for a dwell the dwell time in s (same scale, 0.1 ms per unit); for spindle_forward "
     "and spindle_reverse the speed in rpm / 1000 (0.1 rpm per unit); for tool_change the tool number / 10000 (one "
     "tool per unit, 0 = no tool); 0 for a pause and spindle_stop"},
    {"y", WireType::i24, 5, 1e-4, "mm", "", "end point y (line, arc); 0 for the other kinds"},
};
inline constexpr FieldDef kSegmentTail[] = {
    {"tag", WireType::u8, 0, 1, "", "", "the tag of the SEGMENT frame this completes (a reply echoes it)"},
    {"feed", WireType::u16, 1, 0.01, "mm/s", "", "path speed of the element"},
    {"centre_normal", WireType::i24, 3, 1e-4, "mm", "",
     "arc: the centre's offset from the chord's midpoint along the chord's left normal (start -> end); 0 for a "
     "line; for the line_per_rev kinds 100 times the feed per revolution in mm/rev (1e-6 mm/rev per unit), and feed is "
     "then the path speed at the programmed spindle speed (what the look-ahead plans with); for the "
     "line_per_rev_depth kinds the bar's overhang (mm) at the end point, > 0 (at the path point: this + the end's Z - "
     "its Z), and feed the path speed of the line's largest infeed at the programmed spindle speed"},
    {"centre_along", WireType::i16, 6, 1e-4, "mm", "",
     "arc: the centre's offset from the chord's midpoint along the chord (start -> end); 0 for a line"},
};
inline constexpr FieldDef kSegmentZ[] = {
    {"tag", WireType::u8, 0, 1, "", "", "the tag of the SEGMENT frame whose end point this completes"},
    {"z", WireType::i24, 1, 1e-4, "mm", "", "end point z (line, arc: a helix); without this frame Z stays where the element starts"},
};
inline constexpr FieldDef kSegmentPlane[] = {
    {"tag", WireType::u8, 0, 1, "", "", "the tag of the SEGMENT frame (an arc) whose plane and end point this completes"},
    {"plane", WireType::u8, 1, 1, "", kValueList<motion::kArcPlaneNames>,
     "the arc's plane, counter-clockwise from its first axis towards its second: xy (G17), zx (G18), yz (G19); "
     "the axis beyond it moves linearly with the angle (a helix)"},
    {"z", WireType::i24, 2, 1e-4, "mm", "", "end point z of the arc (always sent)"},
};
inline constexpr FieldDef kProgramStatus[] = {
    {"state", WireType::u8, 0, 1, "", kValueList<kProgramStateNames>,
     "program state: holding = feed hold; starved = underrun, at rest on the path until segments arrive; aborted = "
     "stopped (abort, stop, fault, host timeout) before its end; paused = at rest at a pause element (segment names "
     "it) until COMMAND cycle_start"},
    {"free_slots", WireType::u8, 1, 1, "", "", "free slots in the motion queue"},
    {"underruns", WireType::u16, 2, 1, "", "", "times this program's queue ran dry before its end (saturates)"},
    {"segment", WireType::u24, 4, 1, "", "",
     "number of the program's element being run, from 1 in the order accepted; 0 before the first"},
    {"feed_override", WireType::u8, 7, 1, "%", "", "feed override in percent of the programmed feeds"},
};
inline constexpr FieldDef kProgramTool[] = {
    {"tool", WireType::i32, 0, 1, "", "-1=unknown",
     "the tool in the spindle as far as the node knows: the tool of the last tool_change element continued by "
     "COMMAND cycle_start; -1 (unknown) from start-up and while a tool change is under way or was left unconfirmed "
     "(aborted at its pause)"},
};
// A probe move's outcome in three frames with the same count: the trip
// position (x, y; z in PROBE_RESULT_Z) and where the motion rests.
inline constexpr FieldDef kProbeResult[] = {
    {"count", WireType::u8, 0, 1, "", "", "probe outcomes since start-up, modulo 256: a new value is a new result"},
    {"outcome", WireType::u8, 1, 1, "",
     "1=tripped 2=not_tripped 3=failed 4=already_tripped",
     "tripped: the input changed, the axes braked to rest; not_tripped: G38.3/G38.5 reached the end, the program "
     "goes on; failed: G38.2/G38.4 reached the end without a change, already_tripped: the input was in the "
     "tripping state at the start: both errors, the program is stopped"},
    {"x", WireType::i24, 2, 1e-4, "mm", "",
     "tripped: x measured in the tick whose snapshot first showed the change (at most one tick's travel past the "
     "contact); otherwise where the motion rests"},
    {"y", WireType::i24, 5, 1e-4, "mm", "", "the same for y"},
};
inline constexpr FieldDef kProbeResultZ[] = {
    {"count", WireType::u8, 0, 1, "", "", "the PROBE_RESULT this completes"},
    {"z", WireType::i24, 1, 1e-4, "mm", "", "the same for z"},
    {"rest_z", WireType::i24, 4, 1e-4, "mm", "", "z where the motion rests after it: the next element starts there"},
};
inline constexpr FieldDef kProbeRest[] = {
    {"count", WireType::u8, 0, 1, "", "", "the PROBE_RESULT this completes"},
    {"x", WireType::i24, 1, 1e-4, "mm", "", "x where the motion rests after it: the next element starts there"},
    {"y", WireType::i24, 4, 1e-4, "mm", "", "the same for y"},
};
// The per-axis telemetry frames: one message per axis, the same fields.
// Position and following error share a frame: one 8-byte frame per axis
// and tick costs less bus time than two 4-byte ones (a program streamed at
// full rate keeps its 1 ms telemetry).
inline constexpr FieldDef kTlmPosition[] = {
    {"position", WireType::i32, 0, 1e-6, "mm", "", "encoder position"},
    {"following", WireType::i32, 4, 1e-6, "mm", "", "reference - position, the same tick"},
};
inline constexpr FieldDef kTlmSliding[] = {
    {"s", WireType::f32, 0, 1, "mm/s", "", "sliding variable s_k (S1 eq. 5)"},
    {"d_hat", WireType::f32, 4, 1, "mm/s", "", "disturbance estimate d^_k (S1 eq. 7)"},
};
inline constexpr FieldDef kTlmDac[] = {
    {"code", WireType::u16, 0, 1, "", "", "DAC code (offset binary)"},
};
inline constexpr FieldDef kTlmOutput[] = {
    {"force", WireType::f32, 0, 1, "N", "", "force sensor (force.n_per_volt x ADC volts)"},
};
inline constexpr FieldDef kTlmContour[] = {
    {"contour", WireType::f32, 0, 1, "um", "", "contour error of the running circle (S1 eq. 33), 0 otherwise"},
    {"motion_tick", WireType::i32, 4, 1, "tick", "", "ticks since the start of motion, -1 outside motion"},
};

inline constexpr FieldDef kTlmArsc[] = {
    {"force", WireType::i16, 0, 0.1, "N", "", "force sensor this tick (force.n_per_volt x ADC volts), saturated"},
    {"force_ref", WireType::u16, 2, 0.1, "N", "",
     "the force loop's reference now (arsc.force_ref_n after the soft start); 0 when it does not run"},
    {"feed_override", WireType::u16, 4, 0.0001, "", "",
     "feed override of the motion core this tick (the force loop's, or the host's when the loop is off)"},
    {"cutting_gain", WireType::u16, 6, 0.001, "N*s/mm", "",
     "the loop's cutting-gain estimate (force per mm/s of path feed), saturated; 0 when it does not run"},
};
inline constexpr FieldDef kSpindle[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"op", WireType::u8, 1, 1, "", kValueList<kSpindleOpNames>, "what to do"},
    {"direction", WireType::u8, 2, 1, "", kValueList<kSpindleDirectionNames>, "start: the direction; else 0"},
    {"reserved", WireType::u8, 3, 1, "", "", "0"},
    {"rpm", WireType::f32, 4, 1, "rpm", "",
     "start, speed: the speed, 0 < rpm <= spindle.max_rpm (out_of_range otherwise); stop: 0"},
};
inline constexpr FieldDef kTlmSpindle[] = {
    {"target", WireType::i16, 0, 1, "rpm", "", "speed asked for (signed: negative is reverse); 0 when commanded off"},
    {"command", WireType::i16, 2, 1, "rpm", "", "the ramped command written to the spindle DAC (signed)"},
    {"measured", WireType::i16, 4, 1, "rpm", "", "speed from the spindle encoder (signed, M-method over the tick)"},
    {"flags", WireType::u8, 6, 1, "", "",
     "bit 0 commanded on, bit 1 enable output, bit 2 direction output reverse, bit 3 at speed, bit 4 a feed move "
     "waits for it, bit 5 inhibited (fault, e-stop or a lost host)"},
    {"stop_cause", WireType::u8, 7, 1, "", kValueList<kSpindleStopCauseNames>, "why it was last stopped"},
};
inline constexpr FieldDef kBoreGauge[] = {
    {"tag", WireType::u8, 0, 1, "", "", kTagDoc},
    {"op", WireType::u8, 1, 1, "", kValueList<kBoreOpNames>,
     "record: a finished part's readings (needs command ownership); query: the current infeeds, nothing changes; "
     "restart: learning starts again, the next part is cut at bore.s0_mm_rev (needs command ownership)"},
    {"part", WireType::u16, 2, 1, "", "",
     "record: the number of the part measured, bore.parts + 1 (mod 65536): a repeated or skipped part is refused "
     "(out_of_range); query, restart: 0"},
    {"top", WireType::i16, 4, 0.0001, "mm", "",
     "record: diametral bore error at overhang bore.l1_mm (nominal minus measured diameter, + = undersize); "
     "-32768 = no reading (not_finite)"},
    {"bottom", WireType::i16, 6, 0.0001, "mm", "", "record: the same at overhang bore.l2_mm"},
};
inline constexpr FieldDef kBoreInfeed[] = {
    {"tag", WireType::u8, 0, 1, "", "", kReplyTagDoc},
    {"result", WireType::u8, 1, 1, "", kErrorValues, "0 ok, else why it was refused (nothing changed)"},
    {"detail", WireType::u8, 2, 1, "", "", "refused: index of the offending BORE_GAUGE field, else 0"},
    {"flags", WireType::u8, 3, 1, "", "",
     "bit 0 started (infeeds follow S4 eq. (3); 0: the next part is the start-up part, cut at S0); for a recorded "
     "part: bit 1 it was the start-up part (eq. (10)), bit 2 the variance perturbation reset P, bits 3/4 the "
     "top/bottom reading was out of d0 +- 3 sigma_d, bits 5/6 the top/bottom infeed is clamped to 0.005..1 mm/rev, "
     "bit 7 alpha^ < 0.05 (0.05 used)"},
    {"infeed_top", WireType::u16, 4, 0.00002, "mm/rev", "",
     "infeed to cut with at bore.l1_mm: after record, the next part's; else the part being cut now"},
    {"infeed_bottom", WireType::u16, 6, 0.00002, "mm/rev", "", "the same at bore.l2_mm"},
};

}  // namespace detail

inline constexpr std::array<MessageDef, 31 + 3 * hal::kAxisCount> kMessages{{
    {0x00, "estop", Direction::to_node, 0, {},
     "Emergency stop: outputs safe at the next tick, fault latched (reason estop). Acted on whatever its "
     "length, also on node 0 (broadcast); never acknowledged (the FAULT_EVENT and HEARTBEAT show it)."},
    {0x01, "fault_event", Direction::from_node, 8, detail::kFaultEvent,
     "Sent once when a fault latches."},
    {0x02, "command", Direction::to_node, 8, detail::kCommand,
     "Commands without a motion profile. Answered by COMMAND_ACK. Every code but take_ownership, "
     "release_ownership and program_status needs command ownership (not_owner otherwise); take_ownership succeeds when nobody or the "
     "requesting host holds it, and ownership is lost when can.host_timeout_ms passes without a frame from its "
     "host. stop is also accepted on node 0 from any host, tag 0 included (the broadcast stop)."},
    {0x03, "command_ack", Direction::from_node, 8, detail::kCommandAck,
     "Answer to COMMAND, JOG, MOVE, CIRCLE, SHAPER, EXCITE, SEGMENT and SEGMENT_TAIL: accepted (ok) or why not; "
     "echoes the request's tag."},
    {0x04, "jog", Direction::to_node, 4, detail::kJog,
     "Operator jog stream, one axis per frame (a stream per jogging axis). Starts a jog from holding; each "
     "jogging axis stops unless a frame naming it follows its last within its jog.deadman_s. Answered by "
     "COMMAND_ACK (detail names the offending field); a refused frame changes no axis."},
    {0x05, "move", Direction::to_node, 8, detail::kMove,
     "Point-to-point move of one axis with motion.move_ramp_s speed ramps. Answered by COMMAND_ACK."},
    {0x06, "circle", Direction::to_node, 8, detail::kCircle,
     "The S1 circle, counter-clockwise from where the table stands, with motion.circle_dwell_s and "
     "motion.circle_ramp_s. Answered by COMMAND_ACK."},
    {0x07, "shaper", Direction::to_node, 8, detail::kShaper,
     "Input-shaper design for one axis (same as staging its shaper.* parameters and committing); applied at "
     "the next quiet reference. Answered by COMMAND_ACK."},
    {0x08, "param_request", Direction::to_node, 8, detail::kParamRequest,
     "Generic parameter access by id. Answered by PARAM_REPLY. stage/commit/discard act on the requesting "
     "host's own staged set (up to 4 hosts at once, busy beyond); get from any host; set and commit need command "
     "ownership."},
    {0x09, "param_reply", Direction::from_node, 8, detail::kParamReply, "Answer to every PARAM_REQUEST; echoes its tag."},
    {0x0A, "capture_control", Direction::to_node, 8, detail::kCaptureControl,
     "On-target capture. arm/abort/status are answered by CAPTURE_STATUS (echoing the tag); upload by "
     "CAPTURE_DATA frames, or "
     "by CAPTURE_STATUS with an error."},
    {0x0B, "capture_status", Direction::from_node, 8, detail::kCaptureStatus, "Capture state."},
    {0x0C, "heartbeat", Direction::from_node, 8, detail::kHeartbeat,
     "Status, every tlm.heartbeat_ms (0 = off)."},
    {0x0D, "excite", Direction::to_node, 8, detail::kExcite,
     "Open-loop excitation of one axis for identification (docs/autotune.md): its speed command comes from "
     "the generator instead of its controller, the other axis holds; settle 0.2 s after, ramp rate 2 mm/s^2, a "
     "ramp ends after 12 encoder counts. Only while holding (busy otherwise). A capture armed with trigger "
     "motion records the excitation from its first tick to its last. Answered by COMMAND_ACK."},
    {0x0E, "segment", Direction::to_node, 8, detail::kSegment,
     "One element of a program (docs/motion.md \"Streaming\"): a dwell in this frame alone, a line or arc "
     "completed by a SEGMENT_TAIL with the same tag. From holding the first element starts the program; elements "
     "queue behind it while it runs (an underrun waits at rest on the path). Needs command ownership. Answered by "
     "COMMAND_ACK (code = free queue slots) once the element is complete or refused; a refusal leaves the queue "
     "unchanged."},
    {0x0F, "segment_tail", Direction::to_node, 8, detail::kSegmentTail,
     "Second frame of a line or arc: feed and arc centre. Must follow its SEGMENT from the same host; a SEGMENT "
     "without its tail is refused (not_ready) when the next SEGMENT comes. Answered by COMMAND_ACK."},
    {0x10, "spindle", Direction::to_node, 8, detail::kSpindle,
     "The spindle (docs/safety.md \"Spindle\"): start in a direction at a speed, stop, or a new speed. Needs "
     "command ownership. A start is refused (faulted) while a fault, the e-stop or a lost host inhibits it; it never "
     "starts by itself. While it is commanded on and not at speed, feed moves wait. While a program is active "
     "(running, holding, starved or paused) a start or a new speed is refused busy: the program's spindle elements "
     "command it; a stop is always taken. Answered by COMMAND_ACK (code = op)."},
    {0x11, "segment_z", Direction::to_node, 4, detail::kSegmentZ,
     "Z's end point of a line or arc whose Z changes (an arc with it is a helix: Z moves with the angle), between "
     "its SEGMENT and its SEGMENT_TAIL, with the same tag; elements that keep Z send none. One without its "
     "SEGMENT waiting, or a second one, is refused (not_ready) with the element. Answered only when refused; the "
     "tail answers the element."},
    {0x12, "segment_plane", Direction::to_node, 5, detail::kSegmentPlane,
     "An arc outside the XY plane (G18, G19): its plane and Z's end point, between its SEGMENT and its SEGMENT_TAIL "
     "with the same tag, instead of SEGMENT_Z; the centre in SEGMENT_TAIL is then in the chord frame of that plane. "
     "Refused with the element (nothing queued): an unknown plane (out_of_range, plane), one for an element that is "
     "not an arc (out_of_range, plane), one without its SEGMENT waiting or after a SEGMENT_Z or another "
     "SEGMENT_PLANE (not_ready). Answered only when refused; the tail answers the element."},
    {0x13, "probe_result", Direction::from_node, 8, detail::kProbeResult,
     "A probe move's outcome (SEGMENT probe kinds, G38.2-G38.5), sent once when it is decided (at rest), "
     "followed by PROBE_RESULT_Z and PROBE_REST with the same count; again on COMMAND program_status. The host "
     "sends what follows the probe only after it."},
    {0x14, "tlm_output", Direction::from_node, 4, detail::kTlmOutput,
     "Telemetry every tlm.output_ms (0 = off): the force sensor (the DAC codes are TLM_DAC_<AXIS>)."},
    {0x15, "tlm_contour", Direction::from_node, 8, detail::kTlmContour,
     "Telemetry every tlm.contour_ms (0 = off)."},
    {0x16, "tlm_arsc", Direction::from_node, 8, detail::kTlmArsc,
     "Telemetry every tlm.arsc_ms (0 = off): the S3 force loop (arsc.*), the programs' feed-override source."},
    {0x17, "program_status", Direction::from_node, 8, detail::kProgramStatus,
     "Program progress and flow control: with every HEARTBEAT while a program runs, once when its state changes, "
     "and on COMMAND program_status."},
    {0x18, "program_tool", Direction::from_node, 4, detail::kProgramTool,
     "The tool in the spindle, as the node knows it: sent with every PROGRAM_STATUS. Forgotten at a restart "
     "(unknown, never guessed): a host that starts a program after one must say which tool is in."},
    {0x19, "probe_result_z", Direction::from_node, 7, detail::kProbeResultZ,
     "Second frame of PROBE_RESULT: the trip position's z and the rest position's z."},
    {0x1A, "bore_gauge", Direction::to_node, 8, detail::kBoreGauge,
     "Boring on the board (S4, docs/reproduction-s4.md): a finished part's gauge readings at the two overhangs of "
     "the bore.* parameters; the node's planner records the part with the infeeds it told for it (RLS on the log "
     "model, variance perturbation) and answers the next part's infeeds. Its learned state is saved and loaded "
     "with the parameters. Refused with not_ready while bore.enable is off, busy while a save or load runs. "
     "Answered by BORE_INFEED."},
    {0x1B, "bore_infeed", Direction::from_node, 8, detail::kBoreInfeed,
     "Answer to every BORE_GAUGE, echoing its tag: the infeeds to cut with and, in flags, what happened to the "
     "part. The parts counted, the resets and the estimates are the read-only parameters bore.parts, bore.resets, "
     "bore.c_hat_mm, bore.alpha_hat and bore.beta_hat."},
    {0x1C, "tlm_spindle", Direction::from_node, 8, detail::kTlmSpindle,
     "Telemetry every tlm.spindle_ms (0 = off): the spindle's speeds, outputs and last stop cause."},
    {0x1D, "probe_rest", Direction::from_node, 7, detail::kProbeRest,
     "Third frame of PROBE_RESULT: x and y where the motion rests after the probe."},
// The per-axis blocks, block by block so that the ids stay sorted.
#define TNV_TLM_POSITION(name, ...)                                                                           \
  {static_cast<std::uint8_t>(MessageId::tlm_position_##name), "tlm_position_" #name, Direction::from_node, 8, \
   detail::kTlmPosition, "Telemetry every tlm.position_ms (0 = off): the encoder position and the following error of " #name "."},
#define TNV_TLM_SLIDING(name, ...)                                                                            \
  {static_cast<std::uint8_t>(MessageId::tlm_sliding_##name), "tlm_sliding_" #name, Direction::from_node, 8,  \
   detail::kTlmSliding, "Telemetry every tlm.sliding_ms (0 = off): " #name " controller internals (0 for PID)."},
#define TNV_TLM_DAC(name, ...)                                                                            \
  {static_cast<std::uint8_t>(MessageId::tlm_dac_##name), "tlm_dac_" #name, Direction::from_node, 2,      \
   detail::kTlmDac, "Telemetry every tlm.output_ms (0 = off): the DAC code of " #name "."},
    TNV_AXES(TNV_TLM_POSITION)
    TNV_AXES(TNV_TLM_SLIDING)
    TNV_AXES(TNV_TLM_DAC)
#undef TNV_TLM_POSITION
#undef TNV_TLM_SLIDING
#undef TNV_TLM_DAC
    {0x3E, "capture_data", Direction::from_node, 8, detail::kCaptureData,
     "One segment of a capture upload. The lowest priority of all: never delays control traffic or telemetry."},
}};

namespace detail {
// Every message: ids unique and sorted, its fields inside its length and
// apart. A per-axis field or message that no longer fits (a frame full of
// axes, an id taken) fails the build here, not on the bus.
consteval bool messages_well_formed() {
  for (std::size_t i = 0; i < kMessages.size(); ++i) {
    const MessageDef& m = kMessages[i];
    if (m.id >= kMaxMessageId || (i > 0 && m.id <= kMessages[i - 1].id)) return false;
    std::uint32_t used = 0;
    for (const FieldDef& f : m.fields) {
      const std::size_t bytes = wire_size(f.type);
      if (f.byte_offset + bytes > m.dlc) return false;
      for (std::size_t b = f.byte_offset; b < f.byte_offset + bytes; ++b) {
        if ((used & (1u << b)) != 0) return false;
        used |= 1u << b;
      }
    }
  }
  return true;
}
}  // namespace detail
static_assert(detail::messages_well_formed(),
              "protocol table: message ids sorted and unique, fields inside the frame and apart (a per-axis field "
              "that no longer fits needs a new frame layout: docs/architecture.md, an axis)");

constexpr const MessageDef* find_message(std::uint8_t id) noexcept {
  for (const MessageDef& m : kMessages)
    if (m.id == id) return &m;
  return nullptr;
}

consteval const MessageDef& message(MessageId id) {
  for (const MessageDef& m : kMessages)
    if (m.id == static_cast<std::uint8_t>(id)) return m;
  detail::no_such_message();  // not a constant expression: compile error
  return kMessages[0];
}

}  // namespace tnv::fw::can
