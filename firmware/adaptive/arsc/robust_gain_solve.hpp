#pragma once
// Robust variant's gain design: the same controller (S3 eqs. (7), (10),
// (11), same fixed gains (32), gamma01 from the first coefficient as in
// (25)) placed on the process model that is actually identifiable:
//   v(t) + a11 v(t-1) = b11 u(t-1) - c11 f(t-1)      feed drive, S3 eq. (27)
//   f(t) + a21 f(t-1) = g v(t-1)                     cutting, S3 eq. (28), g = b21 delta
// with the same one-sample computation delay as the faithful variant.
// That process has 3 states (f, v, the input in flight), so the closed
// loop is 6th order, not 7th: the 4-state ARV(2) realisation of Fig. 2 has
// an uncontrollable mode for it and (26) is singular for every exact fit.
// Six of the seven poles of each set are placed (all but the lone real
// pole, see pole_sets.hpp).
//
// In polynomial form (z = forward shift), with plant y = [B_f; B_v] u / A,
//   A   = z [(z + a21)(z + a11) + g c11],  B_f = g b11,  B_v = b11 (z + a21)
//   D   = (z - g01)(z - g03),  r1 = g41 (z - g03),  r2 = g41 g02 + g42 (z - g01)
//   N_f = k D + g21 r1 + g22 r2 + (z - 1)(g31 D + g11 r1)
//   N_v = (z - 1)(g32 D + g12 r1 + g13 r2)
//   closed loop: A (z - 1) D - B_f N_f - B_v N_v = z^6 + d1* z^5 + ... + d6*
// The z^5 coefficient gives g01 = a11 + a21 - 1 - g03 - d1* (the analogue of
// (25)); the rest is 5 linear equations in the 6 gains
// {k, g11, g13, g22, g31, g32}: one free direction. FreeDirection says
// how it is used: min_norm (smallest gains that place the poles) or
// min_g_sensitivity (of all gain sets that place the poles, the one whose
// closed-loop polynomial moves least when the cutting gain g is wrong:
// minimise || d(closed loop)/dg || over the free direction; g is the
// parameter the estimator is least sure of, and it lags the depth).
#include <array>
#include <cstdint>

#include "firmware/adaptive/arsc/arsc_gains.hpp"
#include "firmware/adaptive/arsc/gain_guard.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw::arsc {

struct DriveModel {
  double a11 = -0.5488;  // S3 eq. (27) at T = 0.15 s
  double b11 = 0.4512;
  double c11 = 0.4512;   // load of the cutting force on the feed (b11 in the paper's normalisation)
};

struct StructuredModel {
  DriveModel drive{};
  double a21 = -0.4724;  // S3 eq. (28)
  double cutting_gain = 0.158;  // g = b21 delta
};

enum class FreeDirection : std::uint8_t { min_norm = 0, min_g_sensitivity = 1 };

struct RobustDesignLimits {
  FreeDirection free_direction = FreeDirection::min_g_sensitivity;
  double min_rcond = 1e-12;  // of the (row-scaled) 5x5 normal matrix
  double max_gain = 1.0e3;   // any |gain| above: refuse
};

ParamCheck validate(const DriveModel& drive) noexcept;
ParamCheck validate(const RobustDesignLimits& limits) noexcept;

struct RobustDesign {
  ArscGains gains{};  // valid only when reason == none
  GuardReason reason = GuardReason::model_not_finite;
  double rcond = 0.0;
};

RobustDesign solve_robust_gains(const StructuredModel& model, const std::array<double, 6>& d_star,
                                const FixedGains& fixed, const RobustDesignLimits& limits) noexcept;

// Closed-loop coefficients [d1..d6] for given gains (the same polynomial
// algebra, evaluated), to check a design.
std::array<double, 6> robust_closed_loop_coefficients(const StructuredModel& model, const ArscGains& gains) noexcept;

}  // namespace tnv::fw::arsc
