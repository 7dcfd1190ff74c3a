#pragma once
// The end-milling process of S3 section 3, exactly as the paper simulates
// it (normalised units, sample period T):
//   v(t) + a11 v(t-1) = b11 {u(t-1) - f(t-1)}        S3 eq. (27) feed drive
//   f(t) + a21 f(t-1) = b21 delta(t-1) v(t-1)        S3 eq. (28) cutting
//   a11 = -exp(-T/T_v), b11 = K_vs (1 + a11), a21 = -exp(-T/T_f), b21 = C_fs (1 + a21)
// delta is the depth of cut in mm (issue 8). u is the input actually applied
// over the sample. The judge: it knows nothing about any controller.
#include <string>

#include "emulator/scenario.hpp"

namespace tnv::emu {

struct MillingProcessParams {
  double sample_s = 0.15;               // T
  double feed_time_constant_s = 0.25;   // T_v
  double feed_gain = 1.0;               // K_vs
  double force_time_constant_s = 0.20;  // T_f
  double cutting_coefficient = 1.5;     // C_fs
};

struct MillingCoefficients {
  double a11 = 0.0, b11 = 0.0, a21 = 0.0, b21 = 0.0;
};

// The coefficients below S3 eq. (28). Params must be positive and finite.
MillingCoefficients milling_coefficients(const MillingProcessParams& params) noexcept;
// Empty if valid, else "<field>: <reason>".
std::string validate_milling_process(const MillingProcessParams& params);

// Piecewise-linear depth of S3 Fig. 4: start -> peak over rise_s, back to
// start over fall_s, then start.
double depth_profile_mm(const DepthProfile& profile, double t_s) noexcept;

class MillingProcess {
 public:
  explicit MillingProcess(const MillingProcessParams& params) noexcept;
  void reset() noexcept { force_ = feed_ = 0.0; }  // at rest
  // One sample: y(t) -> y(t+1) with u(t) applied and delta(t) in mm.
  void step(double u_applied, double depth_mm) noexcept;
  double force() const noexcept { return force_; }  // f(t), normalised
  double feed() const noexcept { return feed_; }    // v(t), normalised
  const MillingCoefficients& coefficients() const noexcept { return c_; }

 private:
  MillingCoefficients c_;
  double force_ = 0.0;
  double feed_ = 0.0;
};

}  // namespace tnv::emu
