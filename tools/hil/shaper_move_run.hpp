#pragma once
// One HIL point-to-point move with or without the input shaper, scored at
// the tool point (emulator truth: table + structural-mode deflection),
// which the firmware never sees.
#include <optional>
#include <string>
#include <vector>

#include "emulator/scenario.hpp"
#include "firmware/shaper/shaper_design.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/tick_record.hpp"
#include "firmware/trajectory/point_to_point_move.hpp"

namespace tnv::hil {

struct MoveRunRequest {
  emu::Scenario scenario;
  fw::MoveSpec move{};
  std::optional<fw::ShaperSpec> shaper;  // nullopt: unshaped
  fw::ControllerKind controller = fw::ControllerKind::rdvsc;
  double window_s = 3.0;        // recorded after the end of the planned (unshaped) move
  double settle_band_um = 1.0;  // settling: |tool - target| within this for good
  bool keep_trace = false;
};

struct MoveTraceSample {
  double t_s = 0.0;           // since the start of the move
  double unshaped_mm = 0.0;   // the move's own reference
  double reference_mm = 0.0;  // what the controller followed (shaped if on)
  double position_mm = 0.0;   // encoder-measured
  double table_mm = 0.0;      // truth
  double tool_mm = 0.0;       // truth: table + deflection
};

struct MoveRunResult {
  bool completed = false;
  std::string error;                 // why not; empty when completed
  double move_time_s = 0.0;          // planned (unshaped) move time
  double command_end_s = 0.0;        // the reference the loop follows comes to rest (move + shaper span)
  double shaper_delay_s = 0.0;       // centroid of the active taps
  double shaper_duration_s = 0.0;    // span of the active taps
  double target_mm = 0.0;            // end point (firmware frame = physical frame after homing)
  double residual_pp_um = 0.0;       // tool point peak-to-peak from command_end_s to the end of the window
  std::optional<double> settling_s;  // after the planned move end, until |tool - target| <= band for good
  double final_tool_error_um = 0.0;
  double max_following_error_um = 0.0;  // |followed reference - encoder|, what the supervisor checks
  double max_unshaped_error_um = 0.0;   // |unshaped reference - encoder|: what a delay-blind check would see
  fw::FaultRecord fault{};
  std::vector<MoveTraceSample> trace;
};

MoveRunResult run_move(const MoveRunRequest& request, const fw::FirmwareConfig& base_config);

}  // namespace tnv::hil
