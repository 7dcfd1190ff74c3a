#pragma once
// Adaptive infeed planner for single-pass boring (S4, Lee 1983): after
// each part the bore error is measured at two or more overhangs; the
// planner turns it into spindle deflection (eq. (11)), estimates
// theta = (log C, alpha, beta) of d = C S^alpha L^beta by RLS (eqs. (4)-(8)),
// resets P after "three in a row" out of d0 +- 3 sigma_d (variance
// perturbation, section 5) and gives the next part's infeed along the bore,
// S_opt(L) (eq. (3)).
//
//   part 1:   infeed(L) = S0;  record_part() -> start-up (eq. (10)), P = p0 I
//   part k>1: infeed(L) = S_opt(L; theta_hat);  record_part() -> RLS
//
// Runs between parts, not in the tick, but keeps the firmware rules: fixed
// size, no allocation, no exceptions; a part whose data are invalid is
// refused whole with the field named, and nothing changes.
#include <span>

#include "firmware/adaptive/boring/bore_measurement.hpp"
#include "firmware/adaptive/boring/boring_planner_state.hpp"
#include "firmware/adaptive/boring/infeed_schedule.hpp"
#include "firmware/adaptive/boring/log_model_rls.hpp"
#include "firmware/adaptive/boring/variance_perturbation.hpp"

namespace tnv::fw {

struct BoringPartReport {
  ParamCheck check;       // !ok: the part was refused, nothing changed
  bool startup = false;   // this part started the planner (eq. (10))
  bool reset = false;     // the variance perturbation reset P during this part
  int measurements = 0;
  int out_of_band = 0;    // measured deflection outside d0 +- band_sigmas sigma_d
  int rls_updates = 0;
  int skipped = 0;        // deflection <= 0 (no log): counted for the band, not fitted
};

class BoringInfeedPlanner {
 public:
  // Invalid params leave the planner unconfigured (config_status()):
  // infeed() and record_part() then refuse.
  explicit BoringInfeedPlanner(const BoringPlannerParams& params = {}) noexcept;

  // Validated first, applied whole or not at all; a valid set restarts the
  // planner (the next part is a start-up part).
  ParamCheck set_params(const BoringPlannerParams& params) noexcept;
  void restart() noexcept;

  // Infeed to cut with at overhang L: S0 before start-up, eq. (3) after.
  InfeedCommand infeed(double overhang_mm) const noexcept;

  // The measurements of one finished part, in the order they are taken
  // (1..kMaxBorePositions; the start-up part needs >= 2 overhangs).
  BoringPartReport record_part(std::span<const BoreMeasurement> measurements) noexcept;

  // What the planner has learned (to save it), and putting it back: the
  // state is checked (validate(state, p0)) and taken whole, or refused with
  // nothing changed. Parameters are not part of it: restore into a planner
  // set up with the parameters the state was learned with.
  BoringPlannerState state() const noexcept;
  ParamCheck restore(const BoringPlannerState& state) noexcept;

  double deflection_mm(const BoreMeasurement& m) const noexcept;  // eq. (11)
  bool in_band(double deflection_mm) const noexcept;
  double band_half_width_mm() const noexcept { return params_.band_sigmas * params_.sigma_d_mm; }

  bool configured() const noexcept { return status_.ok; }
  const ParamCheck& config_status() const noexcept { return status_; }
  const BoringPlannerParams& params() const noexcept { return params_; }
  bool started() const noexcept { return started_; }
  int parts_recorded() const noexcept { return parts_; }
  int resets() const noexcept { return resets_; }
  int streak() const noexcept { return perturbation_.streak(); }
  const BoringTheta& theta() const noexcept { return rls_.theta(); }  // in the params' log base
  const BoringCovariance& covariance() const noexcept { return rls_.covariance(); }
  double estimated_c_mm() const noexcept;
  double estimated_alpha() const noexcept { return rls_.theta()(1); }
  double estimated_beta() const noexcept { return rls_.theta()(2); }
  // Sigma = Var(v_k) (first order, at d0) and the denominators s5, s6 the
  // gain form puts in eqs. (5), (6).
  double noise_variance() const noexcept;
  double gain_denominator_5() const noexcept;
  double gain_denominator_6() const noexcept;

 private:
  ParamCheck check_measurements(std::span<const BoreMeasurement> measurements) const noexcept;

  BoringPlannerParams params_{};
  ParamCheck status_{};
  LogModelRls rls_{};
  VariancePerturbation perturbation_{};
  bool started_ = false;
  int parts_ = 0;
  int resets_ = 0;
};

}  // namespace tnv::fw
