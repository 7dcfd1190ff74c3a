#pragma once
// The fields the node reads and writes, looked up by name at compile time
// (a typo is a compile error). Shared by the node and the host tools.
#include <array>
#include <optional>

#include "firmware/can/protocol_messages.hpp"
#include "hal/axis.hpp"

namespace tnv::fw::can::fields {

inline constexpr const MessageDef& kEstopMsg = message(MessageId::estop);
inline constexpr const MessageDef& kCommandMsg = message(MessageId::command);
inline constexpr const MessageDef& kAckMsg = message(MessageId::command_ack);
inline constexpr const MessageDef& kJogMsg = message(MessageId::jog);
inline constexpr const MessageDef& kMoveMsg = message(MessageId::move);
inline constexpr const MessageDef& kCircleMsg = message(MessageId::circle);
inline constexpr const MessageDef& kShaperMsg = message(MessageId::shaper);
inline constexpr const MessageDef& kExciteMsg = message(MessageId::excite);
inline constexpr const MessageDef& kParamRequestMsg = message(MessageId::param_request);
inline constexpr const MessageDef& kParamReplyMsg = message(MessageId::param_reply);
inline constexpr const MessageDef& kCaptureControlMsg = message(MessageId::capture_control);
inline constexpr const MessageDef& kCaptureStatusMsg = message(MessageId::capture_status);
inline constexpr const MessageDef& kCaptureDataMsg = message(MessageId::capture_data);
inline constexpr const MessageDef& kFaultEventMsg = message(MessageId::fault_event);
inline constexpr const MessageDef& kHeartbeatMsg = message(MessageId::heartbeat);
// The per-axis telemetry messages (TLM_POSITION_<AXIS>, ...), in axis order.
inline constexpr std::array<const MessageDef*, hal::kAxisCount> kPositionMsgs{
#define TNV_POSITION_MSG(name, ...) &message(MessageId::tlm_position_##name),
    TNV_AXES(TNV_POSITION_MSG)
#undef TNV_POSITION_MSG
};
inline constexpr std::array<const MessageDef*, hal::kAxisCount> kSlidingMsgs{
#define TNV_SLIDING_MSG(name, ...) &message(MessageId::tlm_sliding_##name),
    TNV_AXES(TNV_SLIDING_MSG)
#undef TNV_SLIDING_MSG
};
inline constexpr std::array<const MessageDef*, hal::kAxisCount> kDacMsgs{
#define TNV_DAC_MSG(name, ...) &message(MessageId::tlm_dac_##name),
    TNV_AXES(TNV_DAC_MSG)
#undef TNV_DAC_MSG
};
inline constexpr const MessageDef& kOutputMsg = message(MessageId::tlm_output);
inline constexpr const MessageDef& kContourMsg = message(MessageId::tlm_contour);
inline constexpr const MessageDef& kBoreGaugeMsg = message(MessageId::bore_gauge);
inline constexpr const MessageDef& kBoreInfeedMsg = message(MessageId::bore_infeed);
inline constexpr const MessageDef& kSegmentMsg = message(MessageId::segment);
inline constexpr const MessageDef& kSegmentTailMsg = message(MessageId::segment_tail);
inline constexpr const MessageDef& kSegmentZMsg = message(MessageId::segment_z);
inline constexpr const MessageDef& kSegmentPlaneMsg = message(MessageId::segment_plane);
inline constexpr const MessageDef& kProgramStatusMsg = message(MessageId::program_status);
inline constexpr const MessageDef& kProgramToolMsg = message(MessageId::program_tool);
inline constexpr const MessageDef& kProbeResultMsg = message(MessageId::probe_result);
inline constexpr const MessageDef& kProbeResultZMsg = message(MessageId::probe_result_z);
inline constexpr const MessageDef& kProbeRestMsg = message(MessageId::probe_rest);
inline constexpr const MessageDef& kArscMsg = message(MessageId::tlm_arsc);
inline constexpr const MessageDef& kSpindleMsg = message(MessageId::spindle);
inline constexpr const MessageDef& kTlmSpindleMsg = message(MessageId::tlm_spindle);

inline constexpr const FieldDef& kSpindleOp = field(kSpindleMsg, "op");
inline constexpr const FieldDef& kSpindleDirection = field(kSpindleMsg, "direction");
inline constexpr const FieldDef& kSpindleRpm = field(kSpindleMsg, "rpm");
inline constexpr const FieldDef& kTlmSpindleTarget = field(kTlmSpindleMsg, "target");
inline constexpr const FieldDef& kTlmSpindleCommand = field(kTlmSpindleMsg, "command");
inline constexpr const FieldDef& kTlmSpindleMeasured = field(kTlmSpindleMsg, "measured");
inline constexpr const FieldDef& kTlmSpindleFlags = field(kTlmSpindleMsg, "flags");
inline constexpr const FieldDef& kTlmSpindleStopCause = field(kTlmSpindleMsg, "stop_cause");

inline constexpr const FieldDef& kCommandTag = field(kCommandMsg, "tag");
inline constexpr const FieldDef& kCommandCode = field(kCommandMsg, "code");
inline constexpr const FieldDef& kCommandAxis = field(kCommandMsg, "axis");
inline constexpr const FieldDef& kCommandArg = field(kCommandMsg, "arg");
inline constexpr const FieldDef& kCommandValue = field(kCommandMsg, "value");

inline constexpr const FieldDef& kAckTag = field(kAckMsg, "tag");
inline constexpr const FieldDef& kAckRequest = field(kAckMsg, "request");
inline constexpr const FieldDef& kAckCode = field(kAckMsg, "code");
inline constexpr const FieldDef& kAckResult = field(kAckMsg, "result");
inline constexpr const FieldDef& kAckState = field(kAckMsg, "state");
inline constexpr const FieldDef& kAckFault = field(kAckMsg, "fault");
inline constexpr const FieldDef& kAckDetail = field(kAckMsg, "detail");
inline constexpr const FieldDef& kAckOwner = field(kAckMsg, "owner");

inline constexpr const FieldDef& kJogTag = field(kJogMsg, "tag");
inline constexpr const FieldDef& kJogAxis = field(kJogMsg, "axis");
inline constexpr const FieldDef& kJogSpeed = field(kJogMsg, "speed");

inline constexpr const FieldDef& kMoveAxis = field(kMoveMsg, "axis");
inline constexpr const FieldDef& kMoveSpeed = field(kMoveMsg, "speed");
inline constexpr const FieldDef& kMoveDistance = field(kMoveMsg, "distance");

inline constexpr const FieldDef& kCircleRadius = field(kCircleMsg, "radius");
inline constexpr const FieldDef& kCircleFeed = field(kCircleMsg, "feed");

inline constexpr const FieldDef& kShaperAxis = field(kShaperMsg, "axis");
inline constexpr const FieldDef& kShaperType = field(kShaperMsg, "type");
inline constexpr const FieldDef& kShaperZeta = field(kShaperMsg, "zeta");
inline constexpr const FieldDef& kShaperFreq = field(kShaperMsg, "freq");

inline constexpr const FieldDef& kExciteAxis = field(kExciteMsg, "axis");
inline constexpr const FieldDef& kExciteKind = field(kExciteMsg, "kind");
inline constexpr const FieldDef& kExciteDuration = field(kExciteMsg, "duration");
inline constexpr const FieldDef& kExciteLevel = field(kExciteMsg, "level");

inline constexpr const FieldDef& kParamOp = field(kParamRequestMsg, "op");
inline constexpr const FieldDef& kParamId = field(kParamRequestMsg, "param");
inline constexpr const FieldDef& kParamValue = field(kParamRequestMsg, "value");
inline constexpr const FieldDef& kReplyTag = field(kParamReplyMsg, "tag");
inline constexpr const FieldDef& kReplyResult = field(kParamReplyMsg, "result");
inline constexpr const FieldDef& kReplyParam = field(kParamReplyMsg, "param");
inline constexpr const FieldDef& kReplyValue = field(kParamReplyMsg, "value");

inline constexpr const FieldDef& kCaptureOp = field(kCaptureControlMsg, "op");
inline constexpr const FieldDef& kCaptureFrames = field(kCaptureControlMsg, "frames");
inline constexpr const FieldDef& kCaptureOffset = field(kCaptureControlMsg, "offset");
inline constexpr const FieldDef& kStatusTag = field(kCaptureStatusMsg, "tag");
inline constexpr const FieldDef& kStatusState = field(kCaptureStatusMsg, "state");
inline constexpr const FieldDef& kStatusResult = field(kCaptureStatusMsg, "result");
inline constexpr const FieldDef& kStatusChannels = field(kCaptureStatusMsg, "channels");
inline constexpr const FieldDef& kStatusDecimation = field(kCaptureStatusMsg, "decimation");
inline constexpr const FieldDef& kStatusSamples = field(kCaptureStatusMsg, "samples");
inline constexpr const FieldDef& kDataSequence = field(kCaptureDataMsg, "sequence");
inline constexpr const FieldDef& kDataBytes = field(kCaptureDataMsg, "data");

inline constexpr const FieldDef& kFaultReason = field(kFaultEventMsg, "reason");
inline constexpr const FieldDef& kFaultAxis = field(kFaultEventMsg, "axis");
inline constexpr const FieldDef& kFaultTick = field(kFaultEventMsg, "tick_low");
inline constexpr const FieldDef& kFaultValue = field(kFaultEventMsg, "value");

inline constexpr const FieldDef& kHbState = field(kHeartbeatMsg, "state");
inline constexpr const FieldDef& kHbFault = field(kHeartbeatMsg, "fault");
inline constexpr const FieldDef& kHbErrors = field(kHeartbeatMsg, "errors");
inline constexpr const FieldDef& kHbOverruns = field(kHeartbeatMsg, "overruns");
inline constexpr const FieldDef& kHbFreeSlots = field(kHeartbeatMsg, "free_slots");
inline constexpr const FieldDef& kHbOwner = field(kHeartbeatMsg, "owner");
inline constexpr const FieldDef& kHbAxes = field(kHeartbeatMsg, "axes");

inline constexpr const FieldDef& kSlidingS = field(*kSlidingMsgs[0], "s");
inline constexpr const FieldDef& kSlidingDHat = field(*kSlidingMsgs[0], "d_hat");
// The per-axis messages' fields (every axis' message has the same layout).
inline constexpr const FieldDef& kPosition = field(*kPositionMsgs[0], "position");
inline constexpr const FieldDef& kFollowing = field(*kPositionMsgs[0], "following");
inline constexpr const FieldDef& kDacCode = field(*kDacMsgs[0], "code");
inline constexpr const FieldDef& kOutputForce = field(kOutputMsg, "force");
inline constexpr const FieldDef& kContour = field(kContourMsg, "contour");
inline constexpr const FieldDef& kContourTick = field(kContourMsg, "motion_tick");
inline constexpr const FieldDef& kArscForce = field(kArscMsg, "force");
inline constexpr const FieldDef& kArscForceRef = field(kArscMsg, "force_ref");
inline constexpr const FieldDef& kArscOverride = field(kArscMsg, "feed_override");
inline constexpr const FieldDef& kArscGain = field(kArscMsg, "cutting_gain");

inline constexpr const FieldDef& kBoreOp = field(kBoreGaugeMsg, "op");
inline constexpr const FieldDef& kBorePart = field(kBoreGaugeMsg, "part");
inline constexpr const FieldDef& kBoreTop = field(kBoreGaugeMsg, "top");
inline constexpr const FieldDef& kBoreBottom = field(kBoreGaugeMsg, "bottom");
inline constexpr const FieldDef& kBoreReplyTag = field(kBoreInfeedMsg, "tag");
inline constexpr const FieldDef& kBoreResult = field(kBoreInfeedMsg, "result");
inline constexpr const FieldDef& kBoreDetail = field(kBoreInfeedMsg, "detail");
inline constexpr const FieldDef& kBoreFlags = field(kBoreInfeedMsg, "flags");
inline constexpr const FieldDef& kBoreInfeedTop = field(kBoreInfeedMsg, "infeed_top");
inline constexpr const FieldDef& kBoreInfeedBottom = field(kBoreInfeedMsg, "infeed_bottom");
inline constexpr const FieldDef& kSegmentTag = field(kSegmentMsg, "tag");
inline constexpr const FieldDef& kSegmentKind = field(kSegmentMsg, "kind");
inline constexpr const FieldDef& kSegmentX = field(kSegmentMsg, "x");
inline constexpr const FieldDef& kSegmentY = field(kSegmentMsg, "y");
inline constexpr const FieldDef& kTailTag = field(kSegmentTailMsg, "tag");
inline constexpr const FieldDef& kTailFeed = field(kSegmentTailMsg, "feed");
inline constexpr const FieldDef& kTailCentreNormal = field(kSegmentTailMsg, "centre_normal");
inline constexpr const FieldDef& kTailCentreAlong = field(kSegmentTailMsg, "centre_along");
inline constexpr const FieldDef& kSegmentZTag = field(kSegmentZMsg, "tag");
inline constexpr const FieldDef& kSegmentZField = field(kSegmentZMsg, "z");
inline constexpr const FieldDef& kPlaneTag = field(kSegmentPlaneMsg, "tag");
inline constexpr const FieldDef& kPlaneField = field(kSegmentPlaneMsg, "plane");
inline constexpr const FieldDef& kPlaneZ = field(kSegmentPlaneMsg, "z");

inline constexpr const FieldDef& kProgramState = field(kProgramStatusMsg, "state");
inline constexpr const FieldDef& kProgramFreeSlots = field(kProgramStatusMsg, "free_slots");
inline constexpr const FieldDef& kProgramUnderruns = field(kProgramStatusMsg, "underruns");
inline constexpr const FieldDef& kProgramSegment = field(kProgramStatusMsg, "segment");
inline constexpr const FieldDef& kProgramOverride = field(kProgramStatusMsg, "feed_override");
inline constexpr const FieldDef& kProgramToolNumber = field(kProgramToolMsg, "tool");
inline constexpr const FieldDef& kProbeCount = field(kProbeResultMsg, "count");
inline constexpr const FieldDef& kProbeOutcome = field(kProbeResultMsg, "outcome");
inline constexpr const FieldDef& kProbeTripX = field(kProbeResultMsg, "x");
inline constexpr const FieldDef& kProbeTripY = field(kProbeResultMsg, "y");
inline constexpr const FieldDef& kProbeZCount = field(kProbeResultZMsg, "count");
inline constexpr const FieldDef& kProbeTripZ = field(kProbeResultZMsg, "z");
inline constexpr const FieldDef& kProbeRestZ = field(kProbeResultZMsg, "rest_z");
inline constexpr const FieldDef& kProbeRestCount = field(kProbeRestMsg, "count");
inline constexpr const FieldDef& kProbeRestX = field(kProbeRestMsg, "x");
inline constexpr const FieldDef& kProbeRestY = field(kProbeRestMsg, "y");

// The axis whose message of a per-axis block `id` is (`block` is that
// block's messages in axis order), none for another id.
constexpr std::optional<hal::Axis> axis_of(const std::array<const MessageDef*, hal::kAxisCount>& block,
                                           std::uint8_t id) noexcept {
  for (const hal::Axis a : hal::kAxes)
    if (block[hal::index(a)]->id == id) return a;
  return std::nullopt;
}

// Field index within its message (COMMAND_ACK.detail names the offending field).
constexpr std::uint8_t index_of(const MessageDef& m, const FieldDef& f) noexcept {
  for (std::size_t i = 0; i < m.fields.size(); ++i)
    if (&m.fields[i] == &f) return static_cast<std::uint8_t>(i);
  return 0;
}

}  // namespace tnv::fw::can::fields
