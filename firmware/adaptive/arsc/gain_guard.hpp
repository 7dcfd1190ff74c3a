#pragma once
// Why a gain update was refused. When any guard fails the controller keeps
// the last good gains and reports the reason (S3 section 3 lists the
// conditions: Jury (31), rank Phi1 = 2, theta0 != 0; the conditioning
// guard on the linear system (26) is ours, issue 8).
#include <cstdint>

namespace tnv::fw::arsc {

enum class GuardReason : std::uint8_t {
  none = 0,            // gains updated
  model_not_finite,    // an estimate is NaN or inf
  theta0_zero,         // |theta0| too small: the input does not reach the model
  phi1_rank,           // rank Phi1 < 2
  model_unstable,      // Jury test (31) failed: estimated open loop not asymptotically stable
  ill_conditioned,     // the gain equations (26) are (numerically) singular
  gains_not_finite,    // the solve produced NaN or inf
  gain_out_of_range,   // robust variant: a gain above its bound
};

inline constexpr int kGuardReasonCount = 8;

constexpr const char* to_string(GuardReason r) noexcept {
  switch (r) {
    case GuardReason::none: return "none";
    case GuardReason::model_not_finite: return "model_not_finite";
    case GuardReason::theta0_zero: return "theta0_zero";
    case GuardReason::phi1_rank: return "phi1_rank";
    case GuardReason::model_unstable: return "model_unstable";
    case GuardReason::ill_conditioned: return "ill_conditioned";
    case GuardReason::gains_not_finite: return "gains_not_finite";
    case GuardReason::gain_out_of_range: return "gain_out_of_range";
  }
  return "?";
}

}  // namespace tnv::fw::arsc
