#pragma once
// Robust variant's estimator: only the cutting gain g = b21 delta of the
// force equation S3 eq. (28),
//   f(t) + a21 f(t-1) = g v(t-1),
// is adapted; a21 (the process time constant) and the feed drive come from
// the test-and-learning stage before the cut. A scalar RLS with forgetting,
// updated only while the feed is large enough to carry information, and
// projected onto [g_min, g_max]. Why: in closed loop f and v move together,
// so the full ARV(2) regression is (nearly) collinear; one parameter with
// a non-zero regressor is identifiable from every sample.
#include "firmware/control/param_check.hpp"

namespace tnv::fw::arsc {

struct CuttingGainRlsParams {
  double a21 = -0.4724;              // force-equation pole (pre-identified), |a21| < 1
  double initial_gain = 0.158;       // g at the start of the cut (pre-identified)
  double gain_min = 1e-3;            // projection bounds, 0 < min < max
  double gain_max = 10.0;
  double forgetting = 0.05;          // lambda: near dead-beat for the noiseless S3 process; near 1 with noise
  double initial_covariance = 10.0;  // > 0
  double max_covariance = 1.0e3;     // P is never above this (no wind-up while unexcited)
  double min_feed = 0.05;            // |v(t-1)| below this: no update (normalised)
};

ParamCheck validate(const CuttingGainRlsParams& params) noexcept;

class CuttingGainRls {
 public:
  explicit CuttingGainRls(const CuttingGainRlsParams& params) noexcept : params_(params) { reset(); }
  void reset() noexcept {
    gain_ = params_.initial_gain;
    covariance_ = params_.initial_covariance;
  }
  // y = f(t) + a21 f(t-1), regressor v(t-1). true if updated.
  bool update(double force, double force_prev, double feed_prev) noexcept;
  double gain() const noexcept { return gain_; }
  double covariance() const noexcept { return covariance_; }
  const CuttingGainRlsParams& params() const noexcept { return params_; }

 private:
  CuttingGainRlsParams params_;
  double gain_ = 0.0;
  double covariance_ = 0.0;
};

}  // namespace tnv::fw::arsc
