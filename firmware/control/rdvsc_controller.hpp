#pragma once
// DVSC+DDC and R-DVSC+DDC, per axis (S1 eqs. (4)-(7)). One class: the
// DVSC+DDC kind is the R-DVSC+DDC law with gamma forced to 0.
//
//   e_k   = x_k - x_ref,k
//   s_k   = G e_k + gamma s_{k-1}                                         (5)
//   d^_k  = d^_{k-1} + (GB)^-1 g [s_k - q s_{k-1} + eta sat(s_{k-1}/phi)]  (7)
//   u_k   = -d^_k + (GB)^-1 (-G A x_k + G x_ref,k+1 - gamma s_k + q s_k
//                            - eta sat(s_k/phi))                           (6)
//
// Decisions beyond the paper (documented here, tested in
// tests/firmware/control/):
// - reset(): s_{-1} = 0, d^_{-1} = 0, and the first tick after reset skips
//   the DDC update (d^_0 = d^_{-1} = 0). Eq. (7) at k = 0 would read the whole
//   initial s_0 = G e_0 as a disturbance effect, which it is not (no command
//   has acted yet) and kick the command; from k = 1 on, (7) is exact, so
//   S1 eq. (9) holds for every k >= 0. Standing on a resting reference the
//   first command is exactly 0.
// - clamp: u is clamped to +-u_max. Eq. (7) assumes the computed command was
//   applied; after a clamped tick the DDC is fed the command actually
//   applied (its innovation minus GB (u_applied - u_law)), so the estimator
//   keeps estimating the plant disturbance instead of winding up on the
//   actuator limit. Without clamping this is exactly (7).
// - set_params(): validated first, applied whole or not at all. d^ (a
//   speed, independent of the gains) is kept; s_{k-1} is re-formed with the
//   new G and gamma from the stored e_{k-1}, s_{k-2}; the next tick skips the
//   DDC update (the last command came from the old law).
// - non-finite measurement or reference: output 0 and reset().
#include <Eigen/Core>

#include "firmware/control/axis_controller.hpp"
#include "firmware/control/axis_model.hpp"
#include "firmware/control/param_check.hpp"
#include "firmware/control/sliding_mode_params.hpp"

namespace tnv::fw {

class RdvscController final : public AxisController {
 public:
  // Paper model and paper parameters for this axis and kind.
  RdvscController(ControllerKind kind, hal::Axis axis) noexcept;
  // model: what the controller believes (normally paper_axis_model()).
  // kind dvsc forces gamma = 0; kind pid is rejected. If the parameters are
  // invalid for the model the controller is unconfigured: config_status()
  // says why, update() returns 0 until a valid set_params().
  RdvscController(ControllerKind kind, const AxisModel& model, const SlidingModeParams& params) noexcept;

  double update(const AxisState& x, const AxisReference& ref) noexcept override;
  void reset() noexcept override;
  ControllerSignals signals() const noexcept override { return signals_; }

  // Validate and apply atomically (between ticks). Returns the check; on
  // failure the old parameters stay in force.
  ParamCheck set_params(const SlidingModeParams& params) noexcept;

  ControllerKind kind() const noexcept { return kind_; }
  const SlidingModeParams& params() const noexcept { return params_; }
  const AxisModel& model() const noexcept { return model_; }
  bool configured() const noexcept { return status_.ok; }
  const ParamCheck& config_status() const noexcept { return status_; }
  // d^_k and the unclamped law output u_k of the last tick (for tests/telemetry).
  double d_hat_mm_s() const noexcept { return d_hat_mm_s_; }
  double u_law_mm_s() const noexcept { return u_law_mm_s_; }

 private:
  ParamCheck check(const SlidingModeParams& params) const noexcept;
  void apply(const SlidingModeParams& params) noexcept;

  ControllerKind kind_;
  AxisModel model_;
  SlidingModeParams params_;
  ParamCheck status_;
  // Derived from model and params at apply().
  Eigen::RowVector2d G_ = Eigen::RowVector2d::Zero();
  Eigen::RowVector2d GA_ = Eigen::RowVector2d::Zero();
  double GB_ = 1.0;
  double inv_GB_ = 1.0;
  // History.
  double s_prev_ = 0.0;        // s_{k-1}
  double s_prev2_ = 0.0;       // s_{k-2}, to re-form s_{k-1} on a gain change
  Eigen::Vector2d e_prev_ = Eigen::Vector2d::Zero();  // e_{k-1}
  double d_hat_mm_s_ = 0.0;    // d^_{k-1} before update, d^_k after
  double u_law_mm_s_ = 0.0;    // unclamped u of the last tick
  double u_applied_mm_s_ = 0.0;
  bool ddc_armed_ = false;     // false on the first tick after reset / set_params
  ControllerSignals signals_{};
};

}  // namespace tnv::fw
