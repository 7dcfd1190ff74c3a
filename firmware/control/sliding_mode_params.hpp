#pragma once
// Parameters of DVSC+DDC / R-DVSC+DDC (S1 eqs. (4)-(7), Tables 1 and 2).
// Units: position error in mm, speed error in mm/s, so with G_speed = 1 the
// sliding variable s (and eta, phi) is in mm/s and G_position in 1/s.
#include "firmware/control/axis_controller.hpp"
#include "firmware/control/axis_model.hpp"
#include "firmware/control/param_check.hpp"
#include "hal/axis.hpp"

namespace tnv::fw {

// DAC full scale: 1000 rpm x 10 mm/rev / 60 s.
inline constexpr double kDacFullScaleSpeed_mm_s = 1000.0 * 10.0 / 60.0;

struct SlidingModeParams {
  // Defaults: the paper's X axis, R-DVSC+DDC (Table 1/2).
  double G_position_1_s = 287.0;  // G = [G_position, G_speed]   S1 eq. (5)
  double G_speed = 1.0;
  double eta_mm_s = 0.1971;       // reaching-law gain            S1 eq. (4)
  double phi_mm_s = 1.273;        // boundary-layer thickness     S1 eq. (4)
  double q = 0.9;                 // reaching-law pole            S1 eq. (4)
  double g = 0.1498;              // DDC gain                     S1 eq. (7)
  double gamma = 0.4155;          // recursive-surface weight     S1 eq. (5); 0 = DVSC+DDC
  double u_max_mm_s = kDacFullScaleSpeed_mm_s;  // output clamp
  bool operator==(const SlidingModeParams&) const = default;
};

// Tables 1/2 for the given axis; gamma = 0 for DVSC+DDC.
SlidingModeParams paper_rdvsc_params(hal::Axis axis) noexcept;
SlidingModeParams paper_dvsc_params(hal::Axis axis) noexcept;
// kind dvsc -> paper_dvsc_params, anything else -> paper_rdvsc_params.
SlidingModeParams paper_sliding_mode_params(hal::Axis axis, ControllerKind kind) noexcept;

// Checks, in this order: every field finite; 0 < q < 1; 0 < g < 1
// (|1 - g| < 1, Theorem 1); eta > 0; phi > eta / (q + 1) (Theorem 2);
// 0 <= gamma < 1 and, if gamma > 0, gamma < min(1 - g, q) (Theorem 5 /
// Remark 2); u_max > 0; the model finite; GB != 0 for this model; the
// sliding-mode zero dynamics (zero of G (zI - A)^{-1} B) inside the unit
// circle, i.e. e -> 0 on the surface.
ParamCheck validate(const SlidingModeParams& params, const AxisModel& model) noexcept;

}  // namespace tnv::fw
