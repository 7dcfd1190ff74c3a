#include "tools/hil/boring_direct_link.hpp"

#include "firmware/can/param_table.hpp"
#include "tools/score/boring_node_resolution.hpp"

namespace tnv::hil {

std::string BoringDirectLink::start(const fw::BoringPlannerParams& params, const std::vector<double>& positions_mm) {
  const fw::BoringPlannerParams p = node_resolution_ ? at_node_resolution(params) : params;
  planner_.emplace(p);
  if (!planner_->configured()) {
    const fw::ParamCheck& c = planner_->config_status();
    const std::string error = std::string(c.field) + ": " + c.reason;
    planner_.reset();
    return error;
  }
  positions_mm_ = positions_mm;
  if (node_resolution_) {
    // The overhangs as bore.l1_mm / bore.l2_mm carry them.
    const fw::can::ParamDef& l = *fw::can::find_param("bore.l1_mm");
    for (double& x : positions_mm_) x = fw::can::from_wire(l, fw::can::to_wire(l, x));
  }
  infeeds_mm_rev_.clear();
  return "";
}

std::vector<BoringLinkInfeed> BoringDirectLink::infeeds(std::string& error) {
  std::vector<BoringLinkInfeed> out;
  if (!planner_) {
    error = "the planner was not started";
    return out;
  }
  infeeds_mm_rev_.clear();
  for (double l : positions_mm_) {
    const fw::InfeedCommand cmd = planner_->infeed(l);
    if (!cmd.check.ok) {
      error = std::string("planner refused infeed: ") + cmd.check.field + ": " + cmd.check.reason;
      out.clear();
      return out;
    }
    // The node tells infeeds on BORE_INFEED's grid, and records the part with them.
    const double s = node_resolution_ ? fw::on_infeed_grid(cmd.infeed_mm_rev, node_infeed_step_mm_rev()) : cmd.infeed_mm_rev;
    out.push_back({s, cmd.infeed_limited});
    infeeds_mm_rev_.push_back(s);
  }
  return out;
}

double BoringDirectLink::received_reading_mm(double bore_error_mm) const {
  if (!node_resolution_) return bore_error_mm;
  return gauge_on_wire_mm(bore_error_mm).value_or(bore_error_mm);
}

BoringLinkPart BoringDirectLink::record(int part, const std::vector<double>& bore_error_mm) {
  BoringLinkPart out;
  if (!planner_ || infeeds_mm_rev_.size() != positions_mm_.size() || bore_error_mm.size() != positions_mm_.size()) {
    out.error = "part " + std::to_string(part) + ": readings without infeeds, or one per position missing";
    return out;
  }
  std::vector<fw::BoreMeasurement> gauge;
  for (std::size_t i = 0; i < positions_mm_.size(); ++i) {
    if (node_resolution_ && !gauge_on_wire_mm(bore_error_mm[i])) {
      out.error = "a reading beyond what BORE_GAUGE carries (+-3.2767 mm)";
      return out;
    }
    gauge.push_back({positions_mm_[i], infeeds_mm_rev_[i], received_reading_mm(bore_error_mm[i])});
  }
  const fw::BoringPartReport report = planner_->record_part(gauge);
  if (!report.check.ok) {
    out.error = std::string("planner refused the measurements: ") + report.check.field + ": " + report.check.reason;
    return out;
  }
  infeeds_mm_rev_.clear();
  out.reset = report.reset;
  out.resets_total = planner_->resets();
  out.out_of_band = report.out_of_band;
  out.c_hat_mm = planner_->estimated_c_mm();
  out.alpha_hat = planner_->estimated_alpha();
  out.beta_hat = planner_->estimated_beta();
  return out;
}

std::string BoringDirectLink::describe() const {
  return node_resolution_ ? "firmware planner in this process, at the node's resolution" : "firmware planner in this process, exact";
}

}  // namespace tnv::hil
