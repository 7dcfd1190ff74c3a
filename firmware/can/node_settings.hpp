#pragma once
// Everything a node can be told over CAN and keeps in storage: the
// firmware config plus the bus, telemetry, motion-default, capture, shaper
// and boring-planner settings. param_table.hpp maps each tunable to a
// parameter id. One member is no parameter: the boring planner's learned
// state (BORE_GAUGE changes it), kept here so that it is saved, loaded and
// validated with the parameters, whole (param_image.hpp).
#include <array>
#include <cstdint>

#include "firmware/adaptive/boring/boring_station.hpp"
#include "firmware/can/protocol_enums.hpp"
#include "firmware/shaper/shaper_design.hpp"
#include "firmware/tick/firmware_config.hpp"

namespace tnv::fw::can {

struct CanSettings {
  std::uint32_t node_id = 1;          // 1..31 (kMaxNodeId); applies at the next start
  std::uint32_t bitrate_kbit = 1000;  // 125, 250, 500, 1000; applies at the next start
  std::uint32_t host_timeout_ms = 0;  // stop motion when the host is silent this long; 0 = off
};

// Period of each cyclic message, ms; 0 = off.
struct TelemetryPeriods {
  std::uint32_t heartbeat_ms = 100;
  std::uint32_t position_ms = 10;  // TLM_POSITION_<AXIS>: position and following error
  std::uint32_t sliding_ms = 0;
  std::uint32_t output_ms = 0;
  std::uint32_t contour_ms = 0;
  std::uint32_t arsc_ms = 0;
  std::uint32_t spindle_ms = 0;
};

// What MOVE and CIRCLE frames do not carry (CircleSpec / MoveSpec defaults).
struct MotionDefaults {
  double circle_ramp_s = 0.1;
  double circle_dwell_s = 0.5;
  double move_ramp_s = 0.02;
  double move_dwell_s = 0.0;
};

struct CaptureSettings {
  // The channel mask of capture_channels.hpp, bits 0-31 and 32-63; default set in default_node_settings().
  std::uint32_t channels = 0;
  std::uint32_t channels_high = 0;
  CaptureTrigger trigger = CaptureTrigger::motion;
  std::uint32_t decimation = 1;  // ticks per sample
};

// Band of the closed-loop excitations (EXCITE sweep / multisine), which the
// frame has no room for (excitation.hpp).
struct ExciteSettings {
  double f_min_hz = 1.0;
  double f_max_hz = 100.0;
  std::uint32_t tones = 40;  // multisine
  double carrier_mm_s = 0.0;  // sweep / multisine: the reference's constant speed (0: a standing table)
};

struct ShaperSettings {
  ShaperSpec spec{};     // type, mode.freq_hz, mode.zeta (one mode over CAN)
  bool enabled = false;
};

struct NodeSettings {
  FirmwareConfig firmware{};
  CanSettings can{};
  TelemetryPeriods telemetry{};
  MotionDefaults motion{};
  CaptureSettings capture{};
  ExciteSettings excite{};
  std::array<ShaperSettings, hal::kAxisCount> shaper{};
  BoringStationSettings bore{};     // bore.* parameters
  BoringStationState bore_state{};  // what the planner learned: not a parameter
};

// default_firmware_config() (the papers' values) and the defaults above.
// Runs the PID tuning rule (milliseconds): never in the real-time loop.
NodeSettings default_node_settings() noexcept;

// default_node_settings(), computed on the first call (at a node's
// construction) and kept: the node's restore_defaults copies from it.
const NodeSettings& cached_default_node_settings() noexcept;

}  // namespace tnv::fw::can
