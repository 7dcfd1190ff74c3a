#include "tools/score/boring_node_resolution.hpp"

#include <algorithm>
#include <cmath>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "firmware/can/param_table.hpp"

namespace tnv::hil {

namespace {

namespace can = fw::can;

// `value` as parameter `name` holds it after a set: the wire's f32 (or integer).
double as_carried(const char* name, double value) {
  const can::ParamDef& p = *can::find_param(name);
  return can::from_wire(p, can::to_wire(p, value));
}

}  // namespace

std::string node_planner_refusal(const fw::BoringPlannerParams& p, const std::vector<double>& positions_mm) {
  const fw::BoringPlannerParams fixed{};
  if (p.log_base != fw::BoringLogBase::natural) return "log_base: the node's planner uses natural logs";
  if (p.startup_in_rls) return "startup_in_rls: the node's planner fits the start-up part by eq. (10) only";
  if (p.initial_covariance != fixed.initial_covariance) return "initial_covariance: the node's planner uses P0 = I";
  if (p.band_sigmas != fixed.band_sigmas) return "band_sigmas: the node's band is d0 +- 3 sigma_d";
  if (p.alpha_min != fixed.alpha_min) return "alpha_min: the node's alpha floor is 0.05";
  if (p.infeed_min_mm_rev != fixed.infeed_min_mm_rev || p.infeed_max_mm_rev != fixed.infeed_max_mm_rev)
    return "infeed range: the node's schedule spans 0.005 .. 1 mm/rev";
  if (positions_mm.size() != 2) return "positions_mm: the node gauges two positions (top, bottom)";
  if (p.overhang_min_mm != std::min(positions_mm[0], positions_mm[1]) ||
      p.overhang_max_mm != std::max(positions_mm[0], positions_mm[1]))
    return "overhang range: the node's model spans its two gauge positions";
  return "";
}

fw::BoringStationSettings node_bore_settings(const fw::BoringPlannerParams& p, const std::vector<double>& positions_mm) {
  fw::BoringStationSettings s;
  s.enabled = true;
  s.d0_mm = as_carried("bore.d0_mm", p.target_deflection_mm);
  s.sigma_d_mm = as_carried("bore.sigma_d_mm", p.sigma_d_mm);
  s.alpha0 = as_carried("bore.alpha0", p.alpha0);
  s.s0_mm_rev = as_carried("bore.s0_mm_rev", p.nominal_infeed_mm_rev);
  s.top_overhang_mm = as_carried("bore.l1_mm", positions_mm.size() > 0 ? positions_mm[0] : p.overhang_min_mm);
  s.bottom_overhang_mm = as_carried("bore.l2_mm", positions_mm.size() > 1 ? positions_mm[1] : p.overhang_max_mm);
  s.force_angle_deg = as_carried("bore.force_angle_deg", p.force_angle_deg);
  s.gain_form = p.gain_form;
  s.reset_count = p.reset_count;
  s.reset_after = static_cast<std::uint32_t>(std::max(p.reset_after, 0));
  s.startup_in_rls = false;
  return s;
}

fw::BoringPlannerParams at_node_resolution(const fw::BoringPlannerParams& p) {
  fw::BoringPlannerParams r = p;
  r.target_deflection_mm = as_carried("bore.d0_mm", p.target_deflection_mm);
  r.sigma_d_mm = as_carried("bore.sigma_d_mm", p.sigma_d_mm);
  r.alpha0 = as_carried("bore.alpha0", p.alpha0);
  r.nominal_infeed_mm_rev = as_carried("bore.s0_mm_rev", p.nominal_infeed_mm_rev);
  r.overhang_min_mm = as_carried("bore.l1_mm", p.overhang_min_mm);
  r.overhang_max_mm = as_carried("bore.l2_mm", p.overhang_max_mm);
  r.force_angle_deg = as_carried("bore.force_angle_deg", p.force_angle_deg);
  return r;
}

std::optional<double> gauge_on_wire_mm(double bore_error_mm) {
  const can::FieldDef& f = can::fields::kBoreTop;
  hal::CanFrame frame = can::make_frame(can::fields::kBoreGaugeMsg, 1);
  if (!can::write(frame, f, bore_error_mm)) return std::nullopt;
  if (static_cast<std::int16_t>(can::read_raw(frame, f)) == can::kBoreNoReading) return std::nullopt;
  return can::read(frame, f);
}

double node_infeed_step_mm_rev() { return can::fields::kBoreInfeedTop.scale; }

}  // namespace tnv::hil
