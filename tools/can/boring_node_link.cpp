#include "tools/can/boring_node_link.hpp"

#include "firmware/can/param_table.hpp"
#include "tools/score/boring_node_resolution.hpp"

namespace tnv::can_host {

namespace {

const can::ParamDef& bore_param(const char* name) { return *can::find_param(name); }

double read_param(NodeClient& client, const char* name) { return client.get(bore_param(name)); }

}  // namespace

std::string BoringNodeLink::start(const fw::BoringPlannerParams& params, const std::vector<double>& positions_mm) {
  if (const std::string why = hil::node_planner_refusal(params, positions_mm); !why.empty()) return why;
  const fw::BoringStationSettings s = hil::node_bore_settings(params, positions_mm);
  const struct {
    const char* name;
    double value;
  } values[] = {{"bore.enable", 1.0},
                {"bore.d0_mm", s.d0_mm},
                {"bore.sigma_d_mm", s.sigma_d_mm},
                {"bore.alpha0", s.alpha0},
                {"bore.s0_mm_rev", s.s0_mm_rev},
                {"bore.l1_mm", s.top_overhang_mm},
                {"bore.l2_mm", s.bottom_overhang_mm},
                {"bore.force_angle_deg", s.force_angle_deg},
                {"bore.gain_form", static_cast<double>(s.gain_form)},
                {"bore.reset_count", static_cast<double>(s.reset_count)},
                {"bore.reset_after", static_cast<double>(s.reset_after)}};
  try {
    // One set, applied whole: L1 and L2 are checked together.
    for (const auto& v : values) client_.stage(bore_param(v.name), v.value);
    client_.commit();
    told_ = client_.bore(can::BoreOp::restart);
  } catch (const std::exception& e) {
    told_.reset();
    return e.what();
  }
  resets_ = 0;
  return "";
}

std::vector<hil::BoringLinkInfeed> BoringNodeLink::infeeds(std::string& error) {
  std::vector<hil::BoringLinkInfeed> out;
  if (!told_) {
    error = "the planner was not started";
    return out;
  }
  out.push_back({told_->infeed_top_mm_rev, told_->has(can::kBoreTopLimited)});
  out.push_back({told_->infeed_bottom_mm_rev, told_->has(can::kBoreBottomLimited)});
  return out;
}

double BoringNodeLink::received_reading_mm(double bore_error_mm) const {
  return hil::gauge_on_wire_mm(bore_error_mm).value_or(bore_error_mm);
}

hil::BoringLinkPart BoringNodeLink::record(int part, const std::vector<double>& bore_error_mm) {
  hil::BoringLinkPart out;
  if (bore_error_mm.size() != 2) {
    out.error = "the node takes two readings (top, bottom)";
    return out;
  }
  for (double e : bore_error_mm)
    if (!bore_reading_fits(e)) {
      out.error = "a reading beyond what BORE_GAUGE carries (+-3.2767 mm)";
      return out;
    }
  try {
    const auto number = static_cast<std::uint16_t>(static_cast<unsigned>(part) & 0xFFFFu);
    const BoreInfeed r = client_.bore(can::BoreOp::record, number, bore_error_mm[0], bore_error_mm[1]);
    told_ = r;
    out.reset = r.has(can::kBoreReset);
    out.out_of_band = r.out_of_band();
    if (out.reset) resets_ = static_cast<int>(read_param(client_, "bore.resets"));
    out.resets_total = resets_;
    out.c_hat_mm = read_param(client_, "bore.c_hat_mm");
    out.alpha_hat = read_param(client_, "bore.alpha_hat");
    out.beta_hat = read_param(client_, "bore.beta_hat");
  } catch (const std::exception& e) {
    told_.reset();
    out.error = e.what();
  }
  return out;
}

std::string BoringNodeLink::describe() const { return "the node's planner over CAN (BORE_GAUGE)"; }

}  // namespace tnv::can_host
