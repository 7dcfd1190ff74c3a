#pragma once
// The ARSC variant that holds the force (issue 8 item 2): the same servo
// structure, fixed gains, timing and pole sets as FaithfulArsc, with the
// cause of the literal version's failure removed:
//   - the model is the structure that is identifiable: the feed drive
//     (a11, b11, c11) and the force pole a21 come from the test-and-learning
//     stage before the cut (the drive is the machine's own axis); only the
//     cutting gain g = b21 delta, which moves with the depth, is adapted
//     on line (CuttingGainRls: scalar, forgetting, projection, dead zone);
//   - the gains are designed on that 3-state model (6th-order loop,
//     RobustGains), where the design equations are well conditioned,
//     instead of on a 4-state ARV(2) model whose exact fits make (26)
//     singular;
//   - with a noisy force signal, the design takes the estimate through
//     an alpha-beta tracker (gain_trend_filter.hpp; off by default).
// Same per-sample order as the faithful loop (estimate, next input, gain
// update) and the same one-sample computation delay. When the output is
// clamped at u_limit the servo compensator (7) holds instead of
// integrating (conditional anti-windup; never active in the S3 runs,
// whose u_limit is not reached). Fixed size, no allocation.
#include "firmware/adaptive/arsc/arsc_signals.hpp"
#include "firmware/adaptive/arsc/cutting_gain_rls.hpp"
#include "firmware/adaptive/arsc/gain_trend_filter.hpp"
#include "firmware/adaptive/arsc/robust_gain_solve.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw::arsc {

struct RobustArscConfig {
  std::array<double, 6> d_star{};  // six of the seven poles, pole_sets.hpp
  FixedGains fixed{};
  DriveModel drive{};
  CuttingGainRlsParams estimator{};
  GainTrendParams gain_trend{};  // alpha 1: design with the estimate itself
  RobustDesignLimits limits{};
  double force_ref = 1.0;
  double u_limit = 1.0e6;
};

ParamCheck validate(const RobustArscConfig& config) noexcept;

class RobustArsc {
 public:
  explicit RobustArsc(const RobustArscConfig& config) noexcept;

  void reset() noexcept;
  double step(double force, double feed) noexcept;
  // f*(t) of S3 eq. (7): a time-varying reference (e.g. a soft start). Finite, > 0.
  bool set_force_ref(double force_ref) noexcept;

  const ArscSignals& signals() const noexcept { return signals_; }
  StructuredModel model() const noexcept;  // with the estimator's gain
  double design_gain() const noexcept { return design_gain_; }  // the gain the gains were designed for
  const RobustArscConfig& config() const noexcept { return config_; }

 private:
  void design() noexcept;

  RobustArscConfig config_;
  CuttingGainRls estimator_;
  GainTrendFilter trend_;
  ArscSignals signals_{};
  double f1_ = 0.0, v1_ = 0.0;
  double design_gain_ = 0.0;
};

}  // namespace tnv::fw::arsc
