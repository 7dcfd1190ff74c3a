#pragma once
// Enumerations carried in protocol fields. Their numbers are wire values:
// append, never renumber.
#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include "hal/listed_enum.hpp"

#include "hal/axis.hpp"

namespace tnv::fw::can {

// 2: request tags (byte 0 of every answered request, echoed by its reply), hosts and ownership.
// 3: program streaming (SEGMENT, SEGMENT_TAIL, PROGRAM_STATUS, COMMAND 14..19); HEARTBEAT
//    carries the motion queue's free slots in byte 5, its overrun count shrank to u8 (byte 4).
// 4: the spindle (SPINDLE, TLM_SPINDLE, spindle.* and tlm.spindle_ms, error spindle_running; SEGMENT kinds
//    rapid and rapid_exact_stop).
// 5: room for any number of axes: identifier [10:5] message, [4:0] node (nodes 1..31); one message per
//    axis for TLM_POSITION (now with the following error; TLM_FOLLOWING and tlm.following_ms are gone),
//    TLM_SLIDING and the DAC codes (TLM_DAC), blocks of 4 ids from 0x20; TLM_OUTPUT keeps the force; JOG names its axis; SPINDLE moved to 0x10, CAPTURE_DATA to 0x3E;
//    HEARTBEAT byte 7 is `axes` (homed and shaper bits per axis); capture.channels_high.
// 6: program pauses (SEGMENT kind pause, PROGRAM_STATUS state paused, COMMAND cycle_start) and the
//    program's spindle commands (SEGMENT kinds spindle_forward, spindle_reverse, spindle_stop).
// 7: the tool in the spindle: SEGMENT kind tool_change (an M6 pause carrying its tool) and PROGRAM_TOOL (0x18),
//    the tool the node knows to be in the spindle (-1 unknown), sent with every PROGRAM_STATUS.
// 8: Z in programs: SEGMENT_Z (0x11), Z's end point of a line or arc (a helix) whose Z changes, between its
//    SEGMENT and SEGMENT_TAIL; elements without it keep Z where they start.
// 9: arcs in the ZX (G18) and YZ (G19) planes: SEGMENT_PLANE (0x12), the arc's plane and Z's end point, in
//    place of SEGMENT_Z; the tail's centre is in that plane's chord frame. XY elements are unchanged.
// 10: probe moves (G38.2-G38.5): SEGMENT kinds probe_toward_or_error, probe_toward, probe_away_or_error,
//    probe_away; PROBE_RESULT (0x13), PROBE_RESULT_Z (0x19) and PROBE_REST (0x1D); error probe_pending.
// 11: feeds per revolution (G95): SEGMENT kinds line_per_rev and line_per_rev_exact_stop, the feed in mm/rev in
//    SEGMENT_TAIL's centre_normal; the node scales the path speed by the spindle speed it measures. SEGMENT kinds
//    line_per_rev_depth and line_per_rev_depth_exact_stop: the feed per revolution the boring planner's infeeds
//    along the bar's overhang (centre_normal the overhang at the end).
inline constexpr std::uint32_t kProtocolVersion = 11;

// Result of every request (COMMAND_ACK.result, PARAM_REPLY.result). The
// codes, in wire order: the enum, its names and the protocol's value
// list (protocol_messages.hpp) all come from this one list.
#define TNV_ERROR_CODES(X) \
  X(ok) \
  X(unknown_id)              /* no parameter with this id */ \
  X(read_only)               /* the parameter cannot be written */ \
  X(out_of_range)            /* outside the parameter's range, or not one of its values */ \
  X(not_finite)              /* NaN or infinity */ \
  X(busy)                    /* not allowed while the machine moves (or a transfer is running) */ \
  X(bad_length)              /* the frame's DLC is not the message's length */ \
  X(unknown_command)         /* unknown command code, operation or message */ \
  X(faulted)                 /* a fault is latched: clear it first */ \
  X(invalid)                 /* the set as a whole is inconsistent (e.g. phi <= eta/(q+1)); nothing applied */ \
  X(storage_error)           /* saving or loading the parameters failed */ \
  X(storage_corrupt)         /* the stored parameter image is damaged or from another version */ \
  X(not_ready)               /* the request needs something that is not there (no capture, shaper not configured) */ \
  X(cause_present)           /* clear faults refused: the cause (e.g. e-stop) is still asserted */ \
  X(bad_axis)                /* axis byte is not 0 (x), 1 (y) or, where allowed, 255 (all) */ \
  X(commissioning_required)  /* a safety parameter changes only in commissioning mode; nothing applied */ \
  X(not_permitted)           /* this node's local configuration forbids it (tnv-fw: [safety] allow_commissioning) */ \
  X(no_host)                 /* the request's tag names host 0: only ESTOP and the broadcast stop may be anonymous */ \
  X(not_owner)               /* needs command ownership, which another host (or no host) holds */ \
  /* Segment refusals (motion/segment.hpp SegmentRefusal) the codes above cannot say; the queue is unchanged. */ \
  X(queue_full)              /* no free slot in the motion queue: wait for the free slots the acks and heartbeat report */ \
  X(zero_length)             /* a line or arc shorter than 1 um */ \
  X(bad_arc)                 /* arc radius below the minimum, or start and end radius differ beyond the tolerance */ \
  X(feed_above_limit)        /* feed above what the axis speed limits allow on this element */ \
  X(outside_workspace)       /* the end point lies outside the soft travel limits */ \
  X(not_homed)               /* homing.required is on and an axis the motion moves is not homed (COMMAND home) */ \
  X(spindle_running)         /* spindle.* parameters change only while the spindle is stopped and still: stop it first */ \
  X(probe_pending)           /* a probe move (G38.x) is queued or running: wait for its PROBE_RESULT, then send what follows */

TNV_LISTED_ENUM(ErrorCode, TNV_ERROR_CODES)

// COMMAND.code, in wire order: the enum, its names and the protocol's
// value list (protocol_messages.hpp) all come from this one list.
#define TNV_COMMAND_CODES(X) \
  X(enable)               /* servo on, hold where the table stands */ \
  X(disable)              /* servo off (DACs mid-scale, enables dropped) */ \
  X(stop)                 /* controlled stop: decelerate along the path, then hold */ \
  X(clear_faults)         /* unlatch the fault if its cause is gone */ \
  X(zero)                 /* set the axis' position to COMMAND.value (mm); only when at rest */ \
  X(select_controller)    /* COMMAND.arg = 0 pid, 1 dvsc, 2 rdvsc; only when at rest */ \
  X(shaper_enable)        /* COMMAND.arg = 0 off, 1 on */ \
  X(save_params)          /* write the live parameter set to storage */ \
  X(load_params)          /* read the stored set and apply it whole; only when at rest */ \
  X(restore_defaults)     /* the papers' defaults (not saved until save_params); only when at rest */ \
  X(take_ownership)       /* the requesting host becomes the one that may command (if nobody else holds it) */ \
  X(release_ownership)    /* the owner gives command ownership up */ \
  X(enter_commissioning)  /* safety parameters become writable; only while disabled (docs/safety.md) */ \
  X(leave_commissioning)  /* back to normal; also left on enable, motion or a fault */ \
  /* Program control (a program is the segments streamed by SEGMENT / SEGMENT_TAIL). */ \
  X(feed_hold)            /* brake on the path and wait there; the queue is kept */ \
  X(feed_resume)          /* continue after a feed hold */ \
  X(feed_override)        /* COMMAND.arg = path speed in percent of the programmed feeds, 0..150 */ \
  X(end_program)          /* the last segment has been sent: running the queue dry is then the end, not an underrun */ \
  X(abort_program)        /* controlled stop on the path; the queue and a half-received segment are dropped */ \
  X(program_status)       /* answer, and send a PROGRAM_STATUS now */ \
  X(home)                 /* homing cycle of COMMAND.axis (0 x, 1 y, 255 x then y); from enable or disable (docs/safety.md "Homing") */ \
  X(cycle_start)          /* the program goes on from the pause it rests at (PROGRAM_STATUS paused); not_ready otherwise */

TNV_LISTED_ENUM(CommandCode, TNV_COMMAND_CODES)

// PARAM_REQUEST.op
#define TNV_PARAM_OPS(X) \
  X(get)      /* read; the reply carries the value */ \
  X(set)      /* write one parameter and apply it now (validated with the whole set) */ \
  X(stage)    /* write into the pending set; nothing applied yet (range-checked now) */ \
  X(commit)   /* validate the pending set with everything else and apply it whole, between ticks */ \
  X(discard)  /* drop the pending set */

TNV_LISTED_ENUM(ParamOp, TNV_PARAM_OPS)

// CAPTURE_CONTROL.op
#define TNV_CAPTURE_OPS(X) \
  X(arm)     /* start waiting for the trigger (capture.* parameters say what and when) */ \
  X(abort)   /* stop recording; keeps what was recorded */ \
  X(status)  /* reply with CAPTURE_STATUS */ \
  X(upload)  /* send CAPTURE_CONTROL.frames CAPTURE_DATA frames from byte CAPTURE_CONTROL.offset */

TNV_LISTED_ENUM(CaptureOp, TNV_CAPTURE_OPS)

// SPINDLE.op
#define TNV_SPINDLE_OPS(X) \
  X(start)  /* turn in SPINDLE.direction at SPINDLE.rpm (also a new direction or speed while it turns) */ \
  X(stop)   /* ramp down, enable dropped at standstill */ \
  X(speed)  /* a new SPINDLE.rpm while it is commanded on; the direction stays */

TNV_LISTED_ENUM(SpindleOp, TNV_SPINDLE_OPS)

// TLM_SPINDLE.flags bits
enum SpindleFlag : std::uint8_t {
  kSpindleOn = 1u << 0,           // commanded on (a start since the last stop)
  kSpindleEnabled = 1u << 1,      // the drive's enable output (stays on through a controlled stop)
  kSpindleReverse = 1u << 2,      // the direction output
  kSpindleAtSpeed = 1u << 3,      // within the at-speed window for spindle.at_speed_ticks
  kSpindleFeedWaiting = 1u << 4,  // a feed move waits for it this tick
  kSpindleInhibited = 1u << 5,    // a fault, the e-stop or a lost host forbids a start
};

// CAPTURE_STATUS.state
#define TNV_CAPTURE_STATES(X) X(idle) X(armed) X(recording) X(done)

TNV_LISTED_ENUM(CaptureState, TNV_CAPTURE_STATES)

// BORE_GAUGE.op
#define TNV_BORE_OPS(X) \
  X(record)   /* a finished part's readings: record it, answer the next part's infeeds */ \
  X(query)    /* the infeeds of the part being cut now; nothing changes */ \
  X(restart)  /* learning starts again: the next part is the start-up part, cut at S0 */

TNV_LISTED_ENUM(BoreOp, TNV_BORE_OPS)

// PROGRAM_STATUS.state: the state of the program a host streams (program_tracker.hpp).
#define TNV_PROGRAM_STATES(X) \
  X(none)      /* no program since start-up */ \
  X(running) \
  X(holding)   /* feed hold */ \
  X(stopping)  /* braking on the path after abort / stop */ \
  X(starved)   /* underrun: at rest on the path until elements arrive */ \
  X(done)      /* ran its queue dry after end_program */ \
  X(aborted)   /* stopped before its end (abort, stop, fault, host timeout, disable) */ \
  X(paused)    /* at rest at a program pause (SEGMENT kind pause: M0, M1, M6) until COMMAND cycle_start */

TNV_LISTED_ENUM(ProgramState, TNV_PROGRAM_STATES)

// BORE_INFEED.flags bits
enum BoreFlag : std::uint8_t {
  kBoreStarted = 1u << 0,        // the planner has started: infeeds follow S4 eq. (3)
  kBoreStartup = 1u << 1,        // the recorded part was the start-up part (eq. (10))
  kBoreReset = 1u << 2,          // the variance perturbation reset P during the recorded part
  kBoreTopOut = 1u << 3,         // top reading out of d0 +- 3 sigma_d
  kBoreBottomOut = 1u << 4,      // bottom reading out of band
  kBoreTopLimited = 1u << 5,     // eq. (3) clamped to the infeed range at the top
  kBoreBottomLimited = 1u << 6,  // ... at the bottom
  kBoreAlphaFloor = 1u << 7,     // alpha^ below 0.05: the schedule used 0.05
};

// BORE_GAUGE.top / bottom raw value of a gauge that has no reading (over range).
inline constexpr std::int16_t kBoreNoReading = -32768;

enum class CaptureTrigger : std::uint8_t {
  immediate = 0,  // recording starts at arm
  motion,         // at the first tick of motion (circle, move or jog); stops when the motion ends
  fault,          // at the tick a fault latches (post-mortem of what follows)
};

// HEARTBEAT.errors bits
enum HeartbeatBit : std::uint16_t {
  kHbStorageFault = 1u << 0,
  kHbParamsUnsaved = 1u << 1,
  kHbTxDropped = 1u << 2,
  kHbJogDeadman = 1u << 3,
  kHbCaptureRecording = 1u << 4,
  kHbCaptureDone = 1u << 5,
  kHbBoardBusErrors = 1u << 6,
  kHbLateTicks = 1u << 7,
  kHbParamsStaged = 1u << 8,
  // bits 9 and 10: free (the shaper bits are HEARTBEAT.axes since protocol 5)
  kHbHostTimeout = 1u << 11,
  kHbCanErrors = 1u << 12,
  kHbCommissioning = 1u << 13,
  // bits 14 and 15: free (the homed bits are HEARTBEAT.axes since protocol 5)
};

// HEARTBEAT.axes: the per-axis bits, by axis index (hal/axis.hpp): bit i
// axis i is homed, bit kHbAxesPerKind + i its input shaper is on. Four
// axes fit; a fifth needs a wider field.
inline constexpr std::size_t kHbAxesPerKind = 4;
static_assert(hal::kAxisCount <= kHbAxesPerKind, "HEARTBEAT.axes holds the homed and shaper bits of four axes");
constexpr std::uint8_t hb_homed_bit(hal::Axis axis) noexcept {
  return static_cast<std::uint8_t>(1u << hal::index(axis));
}
constexpr std::uint8_t hb_shaper_bit(hal::Axis axis) noexcept {
  return static_cast<std::uint8_t>(1u << (kHbAxesPerKind + hal::index(axis)));
}

struct HeartbeatBitDoc {
  std::uint16_t mask;
  const char* name;
  const char* doc;
};
inline constexpr HeartbeatBitDoc kHeartbeatBits[] = {
    {kHbStorageFault, "storage_fault", "the last save/load (or the load at start-up) failed"},
    {kHbParamsUnsaved, "params_unsaved", "the live parameters differ from what was last saved or loaded"},
    {kHbTxDropped, "tx_dropped", "frames were dropped because the transmit queue was full"},
    {kHbJogDeadman, "jog_deadman", "a jog stopped because its stream went silent"},
    {kHbCaptureRecording, "capture_recording", "a capture is armed or recording"},
    {kHbCaptureDone, "capture_done", "a finished capture is ready for upload"},
    {kHbBoardBusErrors, "board_bus_errors", "the I/O-board register bus reported errors"},
    {kHbLateTicks, "late_ticks", "ticks with a measured period beyond tolerance"},
    {kHbParamsStaged, "params_staged", "a pending (staged) parameter set waits for commit"},
    {kHbHostTimeout, "host_timeout", "motion was stopped because the host went silent"},
    {kHbCanErrors, "can_errors", "the CAN controller reported error frames (bus error, error-passive, bus-off)"},
    {kHbCommissioning, "commissioning", "commissioning mode: safety parameters are writable (docs/safety.md)"},
};

}  // namespace tnv::fw::can
