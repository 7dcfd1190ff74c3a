#pragma once
// The boring planner as the node runs it (S4 on the board): the operator
// gauges each finished part at the two positions S4 measures (top, overhang
// L1; bottom, L2) and sends the two bore errors; the node records the part
// with the infeeds it told for it and answers the next part's infeeds.
//
// The node keeps no planner object between parts: its settings and learned
// state (BoringStationState) are plain data in the node's parameter set,
// saved and loaded with it. Each part builds a BoringInfeedPlanner from
// them, restores the state, records the part and takes the state back: a
// node restarted between two parts continues bit for bit.
//
// Infeeds are told on a grid (the protocol's resolution, `infeed_step`), and
// the part is recorded with the grid value it was cut with. Fixed size, no
// allocation, no exceptions: runs in the CAN service of the real-time loop.
#include <array>
#include <cstdint>

#include "firmware/adaptive/boring/boring_infeed_planner.hpp"

namespace tnv::fw {

inline constexpr int kBoringTop = 0;      // index of the top reading / infeed (overhang L1)
inline constexpr int kBoringBottom = 1;   // bottom (overhang L2)
inline constexpr int kBoringStationPositions = 2;

// What an operator sets (the bore.* parameters). The rest of the planner's
// parameters keep the paper's values (BoringPlannerParams defaults: band
// 3 sigma_d, P0 = I, alpha floor 0.05, infeed 0.005..1 mm/rev, natural logs);
// the model's overhang range is [min(L1, L2), max(L1, L2)].
struct BoringStationSettings {
  bool enabled = false;             // off: every gauge request is answered not_ready
  double d0_mm = 0.1165;            // target deflection (Table 1 d_opt)
  double sigma_d_mm = 0.016231;     // measurement noise of d, 1 sigma
  double alpha0 = 0.5;              // start-up guess of alpha (eq. (10))
  double s0_mm_rev = 0.5;           // infeed of the start-up part
  double top_overhang_mm = 40.0;    // L1, where the top reading is taken
  double bottom_overhang_mm = 310.0;  // L2
  double force_angle_deg = 60.0;    // phi in eq. (11)
  BoringGainForm gain_form = BoringGainForm::normalised;
  BoringResetCount reset_count = BoringResetCount::measurements;
  std::uint32_t reset_after = 3;
  bool startup_in_rls = false;
};

struct BoringStationState {
  BoringPlannerState planner = fresh_boring_state(BoringPlannerParams{}.initial_covariance);
  // The infeeds told for the part being cut now (top, bottom), on the grid;
  // 0 before start-up, when the part is cut at S0.
  std::array<double, kBoringStationPositions> infeed_mm_rev{};
};

BoringPlannerParams planner_params(const BoringStationSettings& settings) noexcept;

// The planner's checks (validate(BoringPlannerParams)) under the settings'
// names, and L1, L2 at least 1 mm apart (eq. (10) divides by log(L1/L2)).
ParamCheck validate(const BoringStationSettings& settings) noexcept;

// The planner state (validate(BoringPlannerState)) and the infeeds: both 0
// before start-up, else finite and in (0, 2] mm/rev.
ParamCheck validate(const BoringStationState& state) noexcept;

bool operator==(const BoringStationState& a, const BoringStationState& b) noexcept;

// `mm_rev` rounded to the grid `step` (> 0): what the node can tell.
double on_infeed_grid(double mm_rev, double step) noexcept;

// The infeeds for the part being cut now: S0 before start-up, else the ones told.
std::array<double, kBoringStationPositions> current_infeeds_mm_rev(const BoringStationSettings& settings,
                                                                   const BoringStationState& state,
                                                                   double step) noexcept;

struct BoringStationAnswer {
  ParamCheck check;             // !ok: refused, the state is unchanged
  int position = -1;            // the reading the refusal is about (kBoringTop / kBoringBottom), -1 none
  BoringPartReport report;      // startup, reset, out_of_band, ... of the recorded part
  std::array<bool, kBoringStationPositions> out_of_band{};  // measured deflection outside d0 +- 3 sigma_d
  std::array<InfeedCommand, kBoringStationPositions> next{};  // the next part's infeeds, on the grid
};

// A finished part's two readings, the diametral bore errors at L1 and L2
// (mm, + = undersize): eq. (11), then the start-up (eq. (10)) or the RLS
// (eqs. (5), (6)) with the variance perturbation, then eq. (3) at L1 and L2
// for the next part. Refused (nothing changed) when the settings or the
// state are invalid, a reading is not finite, the part count is at its
// limit or the planner refuses the part (a start-up deflection <= 0).
BoringStationAnswer record_bored_part(const BoringStationSettings& settings, BoringStationState& state,
                                      const std::array<double, kBoringStationPositions>& bore_error_mm,
                                      double infeed_step) noexcept;

// Learning starts again: the next part is a start-up part at S0.
void restart(BoringStationState& state) noexcept;

}  // namespace tnv::fw
