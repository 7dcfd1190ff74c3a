#pragma once
// An operator jog stream through the real-time shaper, in HIL: the pendant
// holds each row's speeds (re-sent every tick) until the next row; after
// the last row it goes silent, so a non-zero last row is stopped by the
// firmware's dead man. Scored at the tool point after the axes stop.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/shaper/shaper_design.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_record.hpp"
#include "hal/axis.hpp"

namespace tnv::hil {

struct JogCommand {
  double t_s = 0.0;
  std::array<double, hal::kAxisCount> speed_mm_s{};  // per axis, by hal::index
};

// The CSV's header: t_s and a speed column per axis of the list
// (`t_s,x_mm_s,y_mm_s`).
std::string jog_csv_header();

// CSV with the header jog_csv_header(), rows in increasing time, t >= 0.
// Empty lines and lines starting with '#' are skipped. On error returns
// nullopt and sets `error` to "line N: ..." naming the field.
std::optional<std::vector<JogCommand>> parse_jog_csv(const std::string& text, std::string& error);

struct JogRunRequest {
  emu::Scenario scenario;
  std::vector<JogCommand> commands;
  std::array<std::optional<fw::ShaperSpec>, hal::kAxisCount> shaper{};  // per axis; nullopt: unshaped
  fw::ControllerKind controller = fw::ControllerKind::rdvsc;
  double window_s = 1.5;  // recorded after every axis is back at rest
  double settle_band_um = 1.0;
  bool keep_trace = false;
};

struct JogTraceSample {
  double t_s = 0.0;  // since the first command
  // Per axis, by hal::index:
  std::array<double, hal::kAxisCount> unshaped_mm{};
  std::array<double, hal::kAxisCount> reference_mm{};
  std::array<double, hal::kAxisCount> tool_mm{};
};

struct JogAxisResult {
  double start_mm = 0.0;
  double end_mm = 0.0;               // where the shaped reference came to rest
  double unshaped_end_mm = 0.0;      // where the operator's stream came to rest
  double residual_pp_um = 0.0;       // tool point, from the stop to the end of the window
  std::optional<double> settling_s;  // after the stop, |tool - end| <= band for good
  double max_following_error_um = 0.0;
  double shaper_delay_s = 0.0;
};

struct JogRunResult {
  bool completed = false;
  std::string error;
  double stop_s = 0.0;  // every axis at rest (holding)
  std::uint32_t deadman_stops = 0;
  std::uint32_t refused_commands = 0;
  std::array<JogAxisResult, hal::kAxisCount> axis{};
  std::vector<JogTraceSample> trace;
};

JogRunResult run_jog(const JogRunRequest& request, const fw::FirmwareConfig& base_config);

}  // namespace tnv::hil
