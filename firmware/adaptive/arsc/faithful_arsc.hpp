#pragma once
// The ARSC loop as the paper prints it (S3 section 2, Fig. 14), with the
// corrections of issue 8: ARV(2) RLS (5), servo + stabilising compensators
// (7), (10), control law (11), gain update (25) + (26) behind the guards
// (Jury (31), rank Phi1 = 2, theta0 != 0, conditioning of (26)); a refused
// update keeps the last good gains and records why.
//
// Timing (stated, issue 8): the control computed at sample t is applied
// from sample t+1 (one-sample computation delay, the paper's "next
// actuator input"). Then the ARV(2) model fitted by the RLS and the closed
// loop of Fig. 2 agree exactly. Per sample, in the order of Fig. 14:
//   MODEL_ESTIMATION       RLS with y(t) and phi(t-1) (u(t-1) = the input applied at t-1)
//   NEXT_INPUT_GENERATION  u(t) from (11) with the gains in force; compensators to t+1
//   ARSC_GAIN_UPDATING     (25), (26) from the new estimates, used from t+1
// Before the first good gains the output is held at 0 and the compensators
// do not run. Fixed size, no allocation: step() may run in a tick.
#include "firmware/adaptive/arsc/arsc_signals.hpp"
#include "firmware/adaptive/arsc/arv2_rls.hpp"
#include "firmware/adaptive/arsc/faithful_gain_solve.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw::arsc {

struct FaithfulArscConfig {
  std::array<double, 7> d_star{};               // desired closed-loop coefficients, S3 eq. (23)
  FixedGains fixed{};                           // S3 eq. (32)
  Arv2Model initial_model = paper_initial_model();  // S3 eq. (29)
  Arv2RlsParams rls{};
  GuardLimits guards{};
  double force_ref = 1.0;    // f* (normalised)
  double u_limit = 1.0e6;    // |u| clamp (normalised); the paper's simulation has none
};

ParamCheck validate(const FaithfulArscConfig& config) noexcept;

class FaithfulArsc {
 public:
  // config must pass validate().
  explicit FaithfulArsc(const FaithfulArscConfig& config) noexcept;

  void reset() noexcept;
  // Measured f(t), v(t) (normalised); returns u(t), to be applied from t+1.
  double step(double force, double feed) noexcept;

  const ArscSignals& signals() const noexcept { return signals_; }
  Arv2Model model() const noexcept { return rls_.model(); }
  const FaithfulArscConfig& config() const noexcept { return config_; }

 private:
  FaithfulArscConfig config_;
  Arv2Rls rls_;
  ArscSignals signals_{};
  double f1_ = 0.0, v1_ = 0.0, f2_ = 0.0, v2_ = 0.0;  // y(t-1), y(t-2); the process starts at rest
  double u1_ = 0.0, u2_ = 0.0;                       // u computed at t-1, t-2
};

}  // namespace tnv::fw::arsc
