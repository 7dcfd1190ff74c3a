#pragma once
// PID baseline on position, made a fair competitor of DVSC+DDC: it gets the
// model-based feed-forward the sliding-mode law has implicitly.
//
//   e_k   = x_ref,k - x_k (position, mm)
//   u_ff  = (v_ref,k+1 - A22 v_ref,k) / B2    nominal-model velocity +
//                                             acceleration feed-forward
//   u_k   = u_ff + kp e_k + ki T sum_{j<=k} e_j + kd D_k
//   D_k   = a D_{k-1} + (1 - a) (e_k - e_{k-1}) / T,  a = tf / (tf + T)
//           (tf = 0: plain backward difference)
//   clamp to +-u_max; anti-windup by conditional integration: the integral
//   is held while the command is clamped and e pushes further into the clamp.
//
// First tick after reset: e_{k-1} := e_k (no derivative kick), integral 0.
// set_params(): validated first, applied whole or not at all; with ki > 0 the
// integral absorbs the change of the kp and kd terms so the command does not
// jump (bumpless).
#include "firmware/control/axis_controller.hpp"
#include "firmware/control/axis_model.hpp"
#include "firmware/control/param_check.hpp"
#include "firmware/control/pid_params.hpp"

namespace tnv::fw {

class PidController final : public AxisController {
 public:
  // nominal: the model used for the feed-forward and the period T. If the
  // parameters are invalid the controller is unconfigured (config_status()),
  // update() returns 0 until a valid set_params().
  PidController(const AxisModel& nominal, const PidParams& params) noexcept;

  double update(const AxisState& x, const AxisReference& ref) noexcept override;
  void reset() noexcept override;
  ControllerSignals signals() const noexcept override { return signals_; }

  ParamCheck set_params(const PidParams& params) noexcept;

  const PidParams& params() const noexcept { return params_; }
  const AxisModel& model() const noexcept { return model_; }
  bool configured() const noexcept { return status_.ok; }
  const ParamCheck& config_status() const noexcept { return status_; }

 private:
  void apply(const PidParams& params) noexcept;

  AxisModel model_;
  PidParams params_;
  ParamCheck status_;
  double filter_a_ = 0.0;        // derivative filter pole a = tf / (tf + T)
  double integral_mm_s_ = 0.0;   // ki T sum(e): the integral term itself
  double e_prev_mm_ = 0.0;
  double de_filtered_mm_s_ = 0.0;  // D_k: filtered error rate
  bool primed_ = false;
  ControllerSignals signals_{};
};

}  // namespace tnv::fw
