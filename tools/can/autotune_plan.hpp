#pragma once
// `tnvctl autotune` without the command line: from an identified axis, the
// design of tools/tune/axis_design.hpp as parameter changes against what
// the node has now, the predicted linearised closed loops of the old and
// the new gains on the identified model, and the atomic apply (stage
// every change, one commit: the node applies all of them or none).
#include <complex>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_table.hpp"
#include "tools/can/node_client.hpp"
#include "tools/tune/axis_design.hpp"
#include "tools/tune/loop_prediction.hpp"

namespace tnv::can_host {

struct ParamChange {
  const can::ParamDef* param = nullptr;
  double old_value = 0.0;  // read from the node
  double new_value = 0.0;  // the design (the node stores it as float32)
};

using tune::LoopPrediction;

struct AxisPrediction {
  LoopPrediction rdvsc_old, rdvsc_new;
  LoopPrediction dvsc_old, dvsc_new;  // gamma = 0
  LoopPrediction pid_old, pid_new;
  // The speed observer's error dynamics (I - L C) Phi of the gains, also
  // when observer.enable is off (designed, not switched on).
  LoopPrediction observer_old, observer_new;
};

struct AxisPlan {
  hal::Axis axis = hal::Axis::x;
  tune::AxisIdentification id;
  tune::AxisDesign design;
  std::vector<ParamChange> changes;
  AxisPrediction prediction;
};

// The parameters autotune writes for one axis, in order: model.*, the
// sliding-mode gains, pid.kp/ki/kd/derivative_filter_tf_s, friction.*,
// observer.*. The design must be ok.
std::vector<ParamChange> design_changes(const tune::AxisDesign& design, hal::Axis axis);
// The design's input shaper (tune::shaper_for_mode: ZVD at the mode the
// tool-side accelerometer identified) as x|y.shaper.type, freq_hz, zeta
// and enable = on; nothing when the design has none (the shaper is left
// as it is).
std::vector<ParamChange> shaper_changes(const tune::AxisDesign& design, hal::Axis axis);

// Reads the current values of every change (old_value) and predicts the
// loops of the old and the new gains on the identified model.
AxisPlan plan_autotune(NodeClient& client, const tune::AxisIdentification& id, const tune::AxisDesign& design);

// Stages every change and commits once: applied whole, or (RequestError
// refused, the staged set discarded) not at all. Returns the values read
// back after the commit, in order.
std::vector<double> apply_changes(NodeClient& client, const std::vector<ParamChange>& changes);

nlohmann::json plan_json(const AxisPlan& plan);
nlohmann::json prediction_json(const LoopPrediction& p);
// "0.912, 0.55±0.21i, ..." (largest modulus first).
std::string poles_text(const std::vector<std::complex<double>>& poles);

}  // namespace tnv::can_host
