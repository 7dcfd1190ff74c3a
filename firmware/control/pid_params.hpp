#pragma once
// Parameters of the PID baseline (pid_controller.hpp). Error e = x_ref - x
// in mm, command in mm/s. Defaults: the X-axis gains from the stated tuning
// rule (pid_tuning.hpp, tune_pid_equal_crossover on the paper's X model and
// X DVSC+DDC parameters); a test keeps them in step with the tuner.
#include "firmware/control/axis_model.hpp"
#include "firmware/control/param_check.hpp"
#include "firmware/control/sliding_mode_params.hpp"

namespace tnv::fw {

struct PidParams {
  double kp = 560.8273;                 // (mm/s)/mm = 1/s
  double ki = 33695.64;                 // (mm/s)/(mm s) = 1/s^2, integral term ki T sum(e)
  double kd = 2.333590;                 // (mm/s)/(mm/s), derivative term kd (e_k - e_{k-1})/T
  double derivative_filter_tf_s = 0.0;  // first-order filter on the derivative; 0 = off
  double u_max_mm_s = kDacFullScaleSpeed_mm_s;
  bool feedforward = true;  // model-based velocity + acceleration feed-forward
  bool operator==(const PidParams&) const = default;
};

// Checks: all finite; kp > 0; ki >= 0; kd >= 0; filter >= 0; u_max > 0;
// model finite; with feed-forward B2 != 0.
ParamCheck validate(const PidParams& params, const AxisModel& model) noexcept;

}  // namespace tnv::fw
