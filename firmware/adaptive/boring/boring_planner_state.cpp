#include "firmware/adaptive/boring/boring_planner_state.hpp"

#include <cmath>

namespace tnv::fw {

namespace {

bool bounded(double v) noexcept { return std::isfinite(v) && std::fabs(v) <= kMaxBoringEstimate; }

bool run_length(std::int32_t n) noexcept { return n >= 0 && n <= kMaxBoringStreak; }

ParamCheck check_covariance(const BoringCovariance& p, double p0) noexcept {
  if (!p.allFinite()) return param_error("covariance", "not finite");
  for (int i = 0; i < 3; ++i) {
    if (!(p(i, i) >= 0.0 && p(i, i) <= p0)) return param_error("covariance", "a variance outside [0, p0]");
    for (int j = 0; j < i; ++j) {
      // LogModelRls keeps P exactly symmetric (0.5 (P + P')).
      if (p(i, j) != p(j, i)) return param_error("covariance", "not symmetric");
      // Positive semi-definite: a correlation of at most 1, with room for round-off.
      const double limit = std::sqrt(p(i, i) * p(j, j)) * (1.0 + 1e-6) + 1e-12 * p0;
      if (std::fabs(p(i, j)) > limit) return param_error("covariance", "a correlation above 1");
    }
  }
  return param_ok();
}

}  // namespace

BoringPlannerState fresh_boring_state(double initial_covariance) noexcept {
  BoringPlannerState s;
  s.covariance = initial_covariance * BoringCovariance::Identity();
  return s;
}

ParamCheck validate(const BoringPlannerState& s, double p0) noexcept {
  if (!(std::isfinite(p0) && p0 > 0.0)) return param_error("initial_covariance", "must be > 0");
  if (!s.started) {
    // Nothing is learned before the start-up part: anything else is damage.
    if (!(s == fresh_boring_state(p0))) return param_error("started", "a planner that has not started has learned nothing");
    return param_ok();
  }
  if (!(s.parts >= 1 && s.parts <= kMaxBoringParts)) return param_error("parts", "must be in [1, 2e8] once started");
  // A part resets P at most once per measurement (reset_after 1) or once at its end.
  const double max_resets = static_cast<double>(s.parts) * (kMaxBorePositions + 1);
  if (!(s.resets >= 0 && static_cast<double>(s.resets) <= max_resets)) return param_error("resets", "more than 9 per part");
  if (!run_length(s.streak)) return param_error("streak", "must be in [0, 100]");
  for (std::int32_t n : s.position_streak)
    if (!run_length(n)) return param_error("position_streak", "must be in [0, 100]");
  for (int i = 0; i < 3; ++i)
    if (!bounded(s.theta(i))) return param_error("theta", "not finite or beyond 1e6");
  if (!bounded(s.innovation)) return param_error("innovation", "not finite or beyond 1e6");
  return check_covariance(s.covariance, p0);
}

bool operator==(const BoringPlannerState& a, const BoringPlannerState& b) noexcept {
  return a.started == b.started && a.parts == b.parts && a.resets == b.resets && a.theta == b.theta &&
         a.covariance == b.covariance && a.innovation == b.innovation && a.streak == b.streak &&
         a.position_streak == b.position_streak;
}

}  // namespace tnv::fw
