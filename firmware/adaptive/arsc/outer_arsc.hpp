#pragma once
// The robust ARSC as an outer loop over the axis controller, designed for
// the rate it runs at (issue 8 item 5): every period it reads the force
// and the feed and returns the feed the axis should run at (on the board
// the feed-override source, arsc_feed_source.hpp, turns it into the
// program's feed override for the planner and the R-DVSC+DDC loops),
// instead of writing the DAC. What it keeps of the robust variant: the servo
// compensator (S3 eq. 7), the control law (11), only the cutting gain
// adapted on line (S3 eq. 28, CuttingGainRls: scalar, forgetting,
// projection, dead zone), the gains re-solved from the new estimate every
// sample (estimation, next input, gain update: S3 Fig. 14's order), last
// good gains kept when a design is refused. What changed and why:
//   - the model is FeedForceModel in continuous time (test stage at the
//     tick), sampled exactly at this loop's period; the design is in
//     delta form with the paper's poles mapped through continuous time
//     (outer_gain_solve.hpp), so the gains do not explode at 1 ms;
//   - no computation delay: the command acts one tick after its sample
//     (the loop computes in microseconds), which the model carries;
//   - anti-windup for the whole compensator: the output is clamped to the
//     feed range, the command in flight is the clamped one, and eta holds
//     while the clamp is active and integrating would push further out.
// Physical units outside, normalised by force_scale_n / feed_scale_mm_s
// inside. Fixed size, no allocation, no exceptions.
#include <array>
#include <cstdint>

#include "firmware/adaptive/arsc/cutting_gain_rls.hpp"
#include "firmware/adaptive/arsc/feed_force_model.hpp"
#include "firmware/adaptive/arsc/gain_guard.hpp"
#include "firmware/adaptive/arsc/outer_gain_solve.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw::arsc {

struct OuterArscConfig {
  double period_s = 0.001;
  FeedForceModel model{};           // from the test stage; cutting_gain at the start of the cut
  OuterPoles poles{};
  OuterDesignLimits limits{};
  double force_scale_n = 150.0;     // normalisation (the paper's f* = 1)
  double feed_scale_mm_s = 10.0;
  double force_ref_n = 150.0;       // f*; set_force_ref_n changes it on line
  double feed_min_mm_s = 0.0;       // command range (no negative chip: the cut stops at 0);
  double feed_max_mm_s = 100.0;     // set_feed_range_mm_s() narrows it on line
  // Estimator (normalised cutting gain g): memory -> lambda = exp(-T / memory_s).
  double memory_s = 0.15;
  double gain_min = 0.02;
  double gain_max = 5.0;
  double initial_covariance = 1.0;  // of the per-sample gain (1 - exp(-T/T_f)) g
  double max_covariance = 1.0e3;
  double min_feed_mm_s = 0.5;       // |mean feed| below this: no estimator update
  bool adapt = true;                // false: the cutting gain stays at the model's (fixed gains, for comparison)
};

ParamCheck validate(const OuterArscConfig& config) noexcept;

struct OuterArscSignals {
  OuterGains gains{};
  bool have_gains = false;
  GuardReason last_reason = GuardReason::none;
  std::array<std::uint32_t, kGuardReasonCount> reason_counts{};
  double rcond = 0.0;
  double eta = 0.0;               // servo compensator (normalised force-seconds)
  double command_mm_s = 0.0;      // this sample's output (after the clamp)
  bool clamped = false;           // the law asked for more than the feed range
  bool estimator_updated = false;
  std::uint32_t samples = 0;
  std::uint32_t clamped_samples = 0;
};

class OuterArsc {
 public:
  // config must have passed validate(config).
  explicit OuterArsc(const OuterArscConfig& config) noexcept;

  void reset() noexcept;
  // One period: force_n and feed_mm_s at the sample, mean_feed_mm_s over
  // the period that just ended (encoder travel / T). Returns the feed
  // command for the next period. Non-finite inputs: hold the last command.
  double step(double force_n, double feed_mm_s, double mean_feed_mm_s) noexcept;
  // f* on line (e.g. a soft start). Finite, >= 0; false otherwise.
  bool set_force_ref_n(double force_ref_n) noexcept;
  // The command range of the next steps (e.g. the feed override's range
  // times the programmed feed), within the configured one; lo <= hi, finite;
  // false (and no change) otherwise. lo == hi pins the command (anti-windup on).
  bool set_feed_range_mm_s(double lo_mm_s, double hi_mm_s) noexcept;
  // A new cut with what was learnt: the compensator, the command in flight
  // and the force history restart from zero, the cutting-gain estimate and
  // the gains designed from it stay (a resumed program after a feed hold).
  void restart() noexcept;

  // Current estimate of the cutting gain G = K delta in N per mm/s.
  double cutting_gain_n_per_mm_s() const noexcept;
  const OuterArscSignals& signals() const noexcept { return signals_; }
  const OuterArscConfig& config() const noexcept { return config_; }

 private:
  SampledFeedForce plant_at(double cutting_gain) const noexcept;
  void design() noexcept;

  OuterArscConfig config_;
  SampledFeedForce unit_plant_{};  // sampled at g = 1: the f row scales with g
  double gain_per_sample_ = 0.0;   // 1 - exp(-T / T_f): g per sample on the mean feed
  CuttingGainRls estimator_;
  OuterArscSignals signals_{};
  double f1_ = 0.0;                // f(t-1), normalised
  double u1_ = 0.0;                // u(t-1), normalised, as applied (clamped)
  bool history_ = false;           // f1_ is a real sample (not the first since a reset / restart)
  double range_lo_ = 0.0;          // command range now, normalised
  double range_hi_ = 0.0;
};

}  // namespace tnv::fw::arsc
