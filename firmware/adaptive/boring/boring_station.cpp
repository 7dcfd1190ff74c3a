#include "firmware/adaptive/boring/boring_station.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace tnv::fw {

namespace {

// The planner's field names as the node's settings call them.
const char* station_field(const char* planner_field) noexcept {
  struct Name {
    const char* planner;
    const char* station;
  };
  constexpr Name names[] = {{"target_deflection_mm", "d0_mm"},       {"sigma_d_mm", "sigma_d_mm"},
                            {"alpha0", "alpha0"},                    {"nominal_infeed_mm_rev", "s0_mm_rev"},
                            {"overhang_min_mm", "top_overhang_mm"},  {"overhang_max_mm", "bottom_overhang_mm"},
                            {"force_angle_deg", "force_angle_deg"},  {"gain_form", "gain_form"},
                            {"reset_count", "reset_count"},          {"reset_after", "reset_after"}};
  for (const Name& n : names)
    if (std::strcmp(n.planner, planner_field) == 0) return n.station;
  return planner_field;
}

// The least overhang difference eq. (10) can use: 1 mm.
constexpr double kMinOverhangSpanMm = 1.0;
// The largest infeed a valid state can hold (the schedule stops at 1 mm/rev).
constexpr double kMaxStateInfeedMmRev = 2.0;

}  // namespace

BoringPlannerParams planner_params(const BoringStationSettings& s) noexcept {
  BoringPlannerParams p;
  p.target_deflection_mm = s.d0_mm;
  p.sigma_d_mm = s.sigma_d_mm;
  p.alpha0 = s.alpha0;
  p.nominal_infeed_mm_rev = s.s0_mm_rev;
  p.overhang_min_mm = std::min(s.top_overhang_mm, s.bottom_overhang_mm);
  p.overhang_max_mm = std::max(s.top_overhang_mm, s.bottom_overhang_mm);
  p.force_angle_deg = s.force_angle_deg;
  p.gain_form = s.gain_form;
  p.reset_count = s.reset_count;
  p.reset_after = static_cast<int>(std::min<std::uint32_t>(s.reset_after, 1000u));
  p.startup_in_rls = s.startup_in_rls;
  return p;
}

ParamCheck validate(const BoringStationSettings& s) noexcept {
  if (!std::isfinite(s.top_overhang_mm)) return param_error("top_overhang_mm", "must be finite (NaN or inf given)");
  if (!std::isfinite(s.bottom_overhang_mm))
    return param_error("bottom_overhang_mm", "must be finite (NaN or inf given)");
  if (!(std::fabs(s.bottom_overhang_mm - s.top_overhang_mm) >= kMinOverhangSpanMm))
    return param_error("bottom_overhang_mm", "must differ from top_overhang_mm by 1 mm or more (eq. (10))");
  ParamCheck c = validate(planner_params(s));
  if (!c.ok) c.field = station_field(c.field);
  return c;
}

ParamCheck validate(const BoringStationState& s) noexcept {
  if (const ParamCheck c = validate(s.planner, BoringPlannerParams{}.initial_covariance); !c.ok) return c;
  for (double v : s.infeed_mm_rev) {
    const bool ok = s.planner.started ? std::isfinite(v) && v > 0.0 && v <= kMaxStateInfeedMmRev : v == 0.0;
    if (!ok) return param_error("infeed_mm_rev", "0 before start-up, else in (0, 2] mm/rev");
  }
  return param_ok();
}

bool operator==(const BoringStationState& a, const BoringStationState& b) noexcept {
  return a.planner == b.planner && a.infeed_mm_rev == b.infeed_mm_rev;
}

double on_infeed_grid(double mm_rev, double step) noexcept { return std::round(mm_rev / step) * step; }

std::array<double, kBoringStationPositions> current_infeeds_mm_rev(const BoringStationSettings& settings,
                                                                   const BoringStationState& state,
                                                                   double step) noexcept {
  if (state.planner.started) return state.infeed_mm_rev;
  const double s0 = on_infeed_grid(settings.s0_mm_rev, step);
  return {s0, s0};
}

void restart(BoringStationState& state) noexcept { state = BoringStationState{}; }

BoringStationAnswer record_bored_part(const BoringStationSettings& settings, BoringStationState& state,
                                      const std::array<double, kBoringStationPositions>& bore_error_mm,
                                      double step) noexcept {
  BoringStationAnswer a;
  if (a.check = validate(settings); !a.check.ok) return a;
  if (a.check = validate(state); !a.check.ok) return a;
  if (!(std::isfinite(step) && step > 0.0)) {
    a.check = param_error("infeed_step", "must be > 0");
    return a;
  }
  for (int i = 0; i < kBoringStationPositions; ++i)
    if (!std::isfinite(bore_error_mm[static_cast<std::size_t>(i)])) {
      a.check = param_error("bore_error_mm", "must be finite (no reading)");
      a.position = i;
      return a;
    }
  if (state.planner.parts >= kMaxBoringParts) {
    a.check = param_error("parts", "the planner has counted 2e8 parts: restart it");
    return a;
  }
  BoringInfeedPlanner planner(planner_params(settings));
  if (a.check = planner.restore(state.planner); !a.check.ok) return a;

  const std::array<double, kBoringStationPositions> cut = current_infeeds_mm_rev(settings, state, step);
  const std::array<double, kBoringStationPositions> overhang_mm = {settings.top_overhang_mm, settings.bottom_overhang_mm};
  std::array<BoreMeasurement, kBoringStationPositions> gauge{};
  for (std::size_t i = 0; i < gauge.size(); ++i) {
    gauge[i] = {overhang_mm[i], cut[i], bore_error_mm[i]};
    a.out_of_band[i] = !planner.in_band(planner.deflection_mm(gauge[i]));
    // Eq. (10) takes logs of the start-up deflections: name the reading that has none.
    if (!state.planner.started && !(planner.deflection_mm(gauge[i]) > 0.0)) {
      a.check = param_error("bore_error_mm", "the start-up part needs deflections > 0 (eq. (10))");
      a.position = static_cast<int>(i);
      return a;
    }
  }
  a.report = planner.record_part(gauge);
  if (!a.report.check.ok) {
    a.check = a.report.check;
    return a;
  }
  BoringStationState next;
  next.planner = planner.state();
  for (std::size_t i = 0; i < gauge.size(); ++i) {
    a.next[i] = planner.infeed(overhang_mm[i]);
    if (!a.next[i].check.ok) {
      a.check = a.next[i].check;
      return a;
    }
    a.next[i].infeed_mm_rev = on_infeed_grid(a.next[i].infeed_mm_rev, step);
    next.infeed_mm_rev[i] = a.next[i].infeed_mm_rev;
  }
  state = next;
  a.check = param_ok();
  return a;
}

}  // namespace tnv::fw
