#pragma once
// What the boring infeed planner (S4) has learned from the parts measured so
// far: the RLS estimate and covariance (eqs. (5), (6)), the variance
// perturbation's runs (section 5) and the counters. Exported so that it can
// be saved with the node's parameters and restored at start-up or by a load:
// a planner restored from it plans every following part exactly as the one
// it was taken from (bit for bit).
//
// validate() says whether a state is one record_part() can have produced;
// an implausible one (a corrupt image) is refused whole.
#include <array>
#include <cstdint>

#include "firmware/adaptive/boring/log_model.hpp"
#include "firmware/adaptive/boring/variance_perturbation.hpp"
#include "firmware/control/param_check.hpp"

namespace tnv::fw {

// More parts than any machine bores in its life; a state past it is corrupt.
// At most 9 resets a part keeps the reset count inside an int32 too.
inline constexpr std::int32_t kMaxBoringParts = 200'000'000;
// |theta|, |innovation| beyond this are no log-deflection model of a boring bar.
inline constexpr double kMaxBoringEstimate = 1e6;
// The longest run the variance perturbation counts (reset_after <= 100).
inline constexpr std::int32_t kMaxBoringStreak = 100;

struct BoringPlannerState {
  bool started = false;        // the start-up part was recorded (eq. (10))
  std::int32_t parts = 0;      // parts recorded since the planner (re)started, the start-up part included
  std::int32_t resets = 0;     // variance-perturbation resets of P
  BoringTheta theta = BoringTheta::Zero();                     // (log C, alpha, beta), eqs. (4), (5)
  BoringCovariance covariance = BoringCovariance::Identity();  // P, eqs. (6), (8)
  double innovation = 0.0;     // y - x' theta of the last RLS update
  std::int32_t streak = 0;     // out-of-band measurements (or parts) in a row
  std::array<std::int32_t, kMaxBorePositions> position_streak{};  // per position (reset_count positions)
};

// The state of a planner that has not started: theta 0, P = p0 I, nothing counted.
BoringPlannerState fresh_boring_state(double initial_covariance) noexcept;

// Plausible for a planner whose P0 = p0 I: before start-up exactly
// fresh_boring_state(p0); after it parts >= 1, resets <= 9 per part, runs
// in [0, 100], theta and the innovation finite and bounded, P finite,
// exactly symmetric, 0 <= P_ii <= p0 (RLS without forgetting never grows
// P) and |P_ij| <= sqrt(P_ii P_jj) (positive semi-definite, to round-off).
ParamCheck validate(const BoringPlannerState& state, double initial_covariance) noexcept;

bool operator==(const BoringPlannerState& a, const BoringPlannerState& b) noexcept;

}  // namespace tnv::fw
