#pragma once
// The boring planner's rows of the parameter table (0x0070..0x007F): its
// settings (NodeSettings::bore) and, read-only, what it has learned
// (NodeSettings::bore_state). Expanded inside param_table.cpp's kParams,
// whose accessor macros (TNV_REAL, TNV_INT) and constants they use; kept
// apart so that the table file stays one screenful per block.
// Every setting applies live (the planner runs between parts, not in the
// tick) from the next part's infeeds on; BORE_GAUGE restart starts the
// learning again. Ranges: what S4's model (Table 1) and eq. (10) can use.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "firmware/can/node_settings.hpp"

namespace tnv::fw::can {

// The bore.* parameter a BoringStationSettings check names (0 if none).
inline std::uint16_t bore_param_for(const char* field) noexcept {
  struct Row {
    const char* field;
    std::uint16_t id;
  };
  constexpr Row rows[] = {{"d0_mm", 0x0071},          {"sigma_d_mm", 0x0072},         {"alpha0", 0x0073},
                          {"s0_mm_rev", 0x0074},      {"top_overhang_mm", 0x0075},    {"bottom_overhang_mm", 0x0076},
                          {"force_angle_deg", 0x0077}, {"gain_form", 0x0078},         {"reset_count", 0x0079},
                          {"reset_after", 0x007A}};
  for (const Row& r : rows)
    if (std::strcmp(r.field, field) == 0) return r.id;
  return 0;
}

}  // namespace tnv::fw::can

// Read-only views of the learned state; 0 before start-up.
#define TNV_BORE_LEARNED(expr)                                                      \
  [](const NodeSettings& s) noexcept -> double {                                    \
    const BoringPlannerState& st = s.bore_state.planner;                            \
    return st.started ? static_cast<double>(expr) : 0.0;                            \
  },                                                                                \
      nullptr, nullptr, nullptr

#define TNV_BORE_PARAMS                                                                                                \
  {0x0070, "bore.enable", ParamType::boolean, "", 0, 1, kOnOff, Access::read_write, Apply::live, kOpen,                \
   TNV_INT(bore.enabled), "adaptive boring infeed planner (S4) answers BORE_GAUGE"},                                   \
      {0x0071, "bore.d0_mm", ParamType::f32, "mm", 0.001, 1, "", Access::read_write, Apply::live, kOpen,               \
       TNV_REAL(bore.d0_mm), "target spindle deflection d0 (S4 eq. (3))"},                                             \
      {0x0072, "bore.sigma_d_mm", ParamType::f32, "mm", 1e-5, 0.5, "", Access::read_write, Apply::live, kOpen,         \
       TNV_REAL(bore.sigma_d_mm), "measurement noise sigma_d of d; a part is in band within d0 +- 3 sigma_d"},         \
      {0x0073, "bore.alpha0", ParamType::f32, "", 0.01, 3, "", Access::read_write, Apply::live, kOpen,                 \
       TNV_REAL(bore.alpha0), "start-up guess of the infeed exponent alpha (S4 eq. (10))"},                            \
      {0x0074, "bore.s0_mm_rev", ParamType::f32, "mm/rev", 0.005, 1, "", Access::read_write, Apply::live, kOpen,       \
       TNV_REAL(bore.s0_mm_rev), "infeed of the start-up part S0"},                                                    \
      {0x0075, "bore.l1_mm", ParamType::f32, "mm", 1, 2000, "", Access::read_write, Apply::live, kOpen,                \
       TNV_REAL(bore.top_overhang_mm), "spindle overhang L1 at the top gauge position"},                               \
      {0x0076, "bore.l2_mm", ParamType::f32, "mm", 1, 2000, "", Access::read_write, Apply::live, kOpen,                \
       TNV_REAL(bore.bottom_overhang_mm), "spindle overhang L2 at the bottom gauge position; |L2 - L1| >= 1 mm"},      \
      {0x0077, "bore.force_angle_deg", ParamType::f32, "deg", 0, 89, "", Access::read_write, Apply::live, kOpen,       \
       TNV_REAL(bore.force_angle_deg), "cutting-force angle phi: d = d0 + bore error / (2 cos phi) (S4 eq. (11))"},    \
      {0x0078, "bore.gain_form", ParamType::enumeration, "", 0, 2, "0=normalised 1=kalman 2=printed",                  \
       Access::read_write, Apply::live, kOpen, TNV_INT(bore.gain_form),                                                \
       "Sigma in S4 eqs. (5)/(6): (1, 1), (Sigma, Sigma) or as printed (Sigma, 1)"},                                  \
      {0x0079, "bore.reset_count", ParamType::enumeration, "", 0, 2, "0=measurements 1=parts 2=positions",             \
       Access::read_write, Apply::live, kOpen, TNV_INT(bore.reset_count),                                              \
       "what the variance perturbation counts 'in a row' (docs/reproduction-s4.md)"},                                  \
      {0x007A, "bore.reset_after", ParamType::u32, "", 1, 100, "", Access::read_write, Apply::live, kOpen,             \
       TNV_INT(bore.reset_after), "out-of-band results in a row that reset P (S4: three)"},                            \
      {0x007B, "bore.parts", ParamType::u32, "", 0, kBig, "", Access::read_only, Apply::live, kOpen,                   \
       TNV_BORE_LEARNED(st.parts), "parts recorded since the planner (re)started, the start-up part included"},        \
      {0x007C, "bore.resets", ParamType::u32, "", 0, kBig, "", Access::read_only, Apply::live, kOpen,                  \
       TNV_BORE_LEARNED(st.resets), "variance-perturbation resets of P since the planner (re)started"},                \
      {0x007D, "bore.c_hat_mm", ParamType::f32, "mm", 0, kBig, "", Access::read_only, Apply::live, kOpen,              \
       TNV_BORE_LEARNED(std::exp(st.theta(0))), "estimated C of d = C S^alpha L^beta (S4 eq. (2)); 0 before start-up"}, \
      {0x007E, "bore.alpha_hat", ParamType::f32, "", 0, kBig, "", Access::read_only, Apply::live, kOpen,               \
       TNV_BORE_LEARNED(st.theta(1)), "estimated infeed exponent alpha; 0 before start-up"},                           \
  {                                                                                                                    \
    0x007F, "bore.beta_hat", ParamType::f32, "", 0, kBig, "", Access::read_only, Apply::live, kOpen,                   \
        TNV_BORE_LEARNED(st.theta(2)), "estimated overhang exponent beta; 0 before start-up"                           \
  }
