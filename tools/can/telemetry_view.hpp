#pragma once
// The latest value of everything a node streams (heartbeat and the cyclic
// TLM_* messages), decoded through the protocol table, plus what it cost
// on the bus. Feed it from NodeClient's listener.
#include <array>
#include <cstdint>
#include <optional>

#include "firmware/spindle/spindle_control.hpp"
#include "hal/axis.hpp"
#include "tools/can/node_messages.hpp"

namespace tnv::can_host {

struct OutputTelemetry {
  std::array<double, hal::kAxisCount> dac_code{};
  double force_n = 0.0;
};

struct ContourTelemetry {
  double contour_um = 0.0;
  double motion_tick = -1.0;
};

// TLM_ARSC: the force loop setting the feed override (arsc.*).
struct ArscTelemetry {
  double force_n = 0.0;
  double force_ref_n = 0.0;
  double feed_override = 0.0;
  double cutting_gain_n_per_mm_s = 0.0;
};

// TLM_SPINDLE (docs/safety.md "Spindle"): speeds signed, negative is reverse.
struct SpindleTelemetry {
  double target_rpm = 0.0;    // asked for; 0 when commanded off
  double command_rpm = 0.0;   // the ramped command to the drive
  double measured_rpm = 0.0;  // from the spindle encoder
  std::uint8_t flags = 0;     // TLM_SPINDLE.flags (can::SpindleFlag bits)
  fw::SpindleStopCause stop_cause = fw::SpindleStopCause::none;

  bool commanded_on() const noexcept;
  bool at_speed() const noexcept;
  bool inhibited() const noexcept;
  bool reverse() const noexcept;
};

// One word for the spindle, from its flags: "inhibited" (a fault, the e-stop or
// a lost host forbids a start), "at_speed", "ramping" (commanded on, not yet at
// speed), "stopping" (commanded off, the enable still held), "off".
const char* spindle_state(const SpindleTelemetry& s) noexcept;

struct TelemetryView {
  std::optional<Heartbeat> heartbeat;
  // Per axis, in axis order (one frame per axis: an axis not heard from yet reads 0).
  std::optional<std::array<double, hal::kAxisCount>> position_mm;
  std::optional<std::array<double, hal::kAxisCount>> following_mm;  // reference - position
  std::optional<std::array<double, hal::kAxisCount>> s_mm_s;        // sliding variable (0 for PID)
  std::optional<std::array<double, hal::kAxisCount>> d_hat_mm_s;    // disturbance estimate
  std::optional<OutputTelemetry> output;
  std::optional<ContourTelemetry> contour;
  std::optional<ArscTelemetry> arsc;
  std::optional<SpindleTelemetry> spindle;
  std::optional<ProgramTool> program_tool;  // PROGRAM_TOOL: the tool the node knows in the spindle
  std::uint64_t frames = 0;  // every frame taken
  std::uint64_t bits = 0;    // their nominal bits on the wire (no stuff bits)

  void take(const hal::CanFrame& frame, can::MessageId id);
};

}  // namespace tnv::can_host
