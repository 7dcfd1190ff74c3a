#pragma once
// The paper's on-line gain update, S3 eqs. (25)-(26) and Fig. 3, with the
// corrections of issue 8 (each verified symbolically and by the 7x7
// coefficient test in tests/firmware/adaptive/arsc/):
//   - gamma01 = phi111 + phi122 - 1 - gamma03 - d1*            (25); (24) has the wrong sign
//   - h4 = phi111 + phi122 - 1 - d1*  (= gamma01 + gamma03)
//   - P row d4, column gamma13: +gamma42 h6 + h1 theta02       (print: -gamma42 h6)
//   - delta row d4: d4* - h15 h6 - h13 theta02 + h16 theta01 - h12 - h4 h11 - h5 h10
//     (OCR "h_1s h_6", "h_1 theta01")
//   - D* = {d2*, ..., d7*}                                      (OCR "a1*")
// With these, P K^v = delta is exactly d_i(K) = d_i*, i = 2..7, for the
// matrix of Fig. 2.
//
// (26) is singular for every model when gamma01 = 1 or
// gamma01 = gamma03 + gamma41 gamma02 / gamma42 (0.6 with the paper's fixed
// gains), and whenever the model is not minimal (e.g. any exact ARV(2) fit
// of the S3 process). The conditioning guard catches all of these.
#include <Eigen/Core>
#include <array>

#include "firmware/adaptive/arsc/arsc_gains.hpp"
#include "firmware/adaptive/arsc/arv2_model.hpp"
#include "firmware/adaptive/arsc/gain_guard.hpp"
#include "firmware/adaptive/arsc/jury_stability.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw::arsc {

struct GuardLimits {
  double min_theta0 = 1e-6;      // |theta0| (2-norm) below this: theta0 = 0
  double min_phi1_rank = 1e-6;   // |det Phi1| / ||Phi1||_F^2 below this: rank < 2
  double min_rcond = 1e-7;       // reciprocal condition of the column-scaled system
};

ParamCheck validate(const GuardLimits& limits) noexcept;
ParamCheck validate(const FixedGains& fixed) noexcept;

struct GainDesign {
  ArscGains gains{};  // valid only when reason == none
  GuardReason reason = GuardReason::model_not_finite;
  JuryFailure jury = JuryFailure::none;
  double rcond = 0.0;  // of the column-scaled linear system (0 if not reached)
};

// Fig. 3: P and delta for the model, d* = [d1*..d7*] and the fixed gains.
struct Fig3System {
  Eigen::Matrix<double, 6, 6> p;
  Eigen::Matrix<double, 6, 1> delta;
  double gamma01 = 0.0;  // S3 eq. (25)
};
Fig3System fig3_system(const Arv2Model& model, const std::array<double, 7>& d_star,
                       const FixedGains& fixed) noexcept;

// Guards, then (25) and (26) by Gaussian elimination with partial pivoting.
GainDesign solve_faithful_gains(const Arv2Model& model, const std::array<double, 7>& d_star,
                                const FixedGains& fixed, const GuardLimits& limits) noexcept;

// Model-only guards shared by both variants' use of an ARV(2) model
// (theta0 != 0, rank Phi1 = 2, Jury). none when all pass.
GuardReason check_model(const Arv2Model& model, const GuardLimits& limits, JuryFailure& jury) noexcept;

}  // namespace tnv::fw::arsc
