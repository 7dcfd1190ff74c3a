#include "tools/hil/boring_run.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

#include "firmware/adaptive/boring/bore_measurement.hpp"
#include "tools/hil/boring_direct_link.hpp"

namespace tnv::hil {

BoringRunRequest paper_boring_request(double sigma_d_mm, double alpha0) {
  BoringRunRequest r;
  r.planner.sigma_d_mm = sigma_d_mm;
  r.planner.alpha0 = alpha0;
  r.process_sigma_mm = sigma_d_mm;
  r.band_sigma_mm = sigma_d_mm;
  return r;
}

BoringRunRequest with_scenario_gauge(BoringRunRequest r, const emu::Scenario& s) {
  r.gauge_noise_mm_rms = s.noise.bore_gauge_um_rms * 1e-3;
  r.gauge_resolution_mm = s.noise.bore_gauge_resolution_um * 1e-3;
  r.gauge_seed = s.noise.seed;
  return r;
}

namespace {

emu::BoringProcessConfig process_config(const BoringRunRequest& r, std::uint64_t seed) {
  const int c1 = r.change_at.size() > 0 ? r.change_at[0] : 0;
  const int c2 = r.change_at.size() > 1 ? r.change_at[1] : 0;
  emu::BoringProcessConfig c = emu::paper_boring_process(r.process_sigma_mm, seed, c1, c2);
  c.preset_deflection_mm = r.planner.target_deflection_mm;
  c.force_angle_deg = r.planner.force_angle_deg;
  c.gauge_noise_mm_rms = r.gauge_noise_mm_rms;
  c.gauge_resolution_mm = r.gauge_resolution_mm;
  c.gauge_seed = emu::mix_seed(r.gauge_seed, seed);
  return c;
}

}  // namespace

std::string validate_boring_request(const BoringRunRequest& r) {
  if (const fw::ParamCheck check = fw::validate(r.planner); !check.ok)
    return std::string(check.field) + ": " + check.reason;
  if (!(r.parts >= 1 && r.parts <= 100'000)) return "parts: must be in [1, 100000]";
  if (r.change_at.size() > 2) return "change_at: at most two change points (the paper's three sets)";
  for (std::size_t i = 0; i < r.change_at.size(); ++i) {
    if (r.change_at[i] < 2) return "change_at: a change point must be a part number >= 2";
    if (i > 0 && r.change_at[i] <= r.change_at[i - 1]) return "change_at: change points must increase";
  }
  if (!(std::isfinite(r.band_sigma_mm) && r.band_sigma_mm > 0.0)) return "band_sigma_mm: must be > 0 and finite";
  if (r.positions_mm.size() < 2 || r.positions_mm.size() > static_cast<std::size_t>(fw::kMaxBorePositions))
    return "positions_mm: 2 to 8 measuring positions";
  for (double p : r.positions_mm)
    if (!(std::isfinite(p) && p >= r.planner.overhang_min_mm && p <= r.planner.overhang_max_mm))
      return "positions_mm: each must lie in [overhang_min_mm, overhang_max_mm]";
  return emu::validate_boring_process(process_config(r, 1));
}

BoringRunResult run_boring(const BoringRunRequest& r, std::uint64_t seed, BoringPlannerLink& planner) {
  if (const std::string error = validate_boring_request(r); !error.empty()) throw std::invalid_argument(error);
  emu::BoringProcess process(process_config(r, seed));
  const double d0 = r.planner.target_deflection_mm;
  const double band_mm = r.planner.band_sigmas * r.band_sigma_mm;

  BoringRunResult result;
  result.seed = seed;
  if (const std::string error = planner.start(r.planner, r.positions_mm); !error.empty()) {
    result.error = "planner not started: " + error;
    return result;
  }
  result.parts.reserve(static_cast<std::size_t>(r.parts));
  std::vector<double> gauge(r.positions_mm.size());
  for (int part = 1; part <= r.parts; ++part) {
    BoringPartRecord rec;
    rec.part = part;
    rec.true_c_mm = process.c_mm(part);
    rec.true_alpha = process.parameters(part).alpha;
    rec.true_beta = process.parameters(part).beta;
    std::string error;
    const std::vector<BoringLinkInfeed> infeeds = planner.infeeds(error);
    if (infeeds.size() != r.positions_mm.size()) {
      result.error = "part " + std::to_string(part) + ": no infeeds: " + error;
      return result;
    }
    for (std::size_t i = 0; i < r.positions_mm.size(); ++i) {
      const double L = r.positions_mm[i];
      const double s = infeeds[i].infeed_mm_rev;
      BoringPositionRecord pos;
      pos.overhang_mm = L;
      pos.infeed_mm_rev = s;
      pos.infeed_limited = infeeds[i].infeed_limited;
      pos.cut_infeed_mm_rev = s;
      pos.cut_overhang_mm = L;
      pos.optimal_infeed_mm_rev = process.optimal_infeed_mm_rev(part, L);
      pos.true_deflection_mm = process.deflection_mm(part, s, L);
      gauge[i] = process.measure_bore_error_mm(part, s, L);
      pos.measured_deflection_mm = fw::deflection_from_bore_error_mm(planner.received_reading_mm(gauge[i]), d0,
                                                                     r.planner.force_angle_deg);
      rec.positions.push_back(pos);
    }
    if (!add_gauged_part(result, std::move(rec), planner.record(part, gauge), d0, band_mm)) return result;
  }
  result.deflection_rms_mm = deflection_rms_mm(result, d0);
  return result;
}

bool add_gauged_part(BoringRunResult& result, BoringPartRecord rec, const BoringLinkPart& report, double d0_mm,
                     double band_mm) {
  for (const BoringPositionRecord& pos : rec.positions)
    rec.bad = rec.bad || std::fabs(pos.true_deflection_mm - d0_mm) > band_mm;
  if (!report.error.empty()) {
    result.error = "part " + std::to_string(rec.part) + ": " + report.error;
    return false;
  }
  rec.reset = report.reset;
  rec.out_of_band = report.out_of_band;
  rec.c_hat_mm = report.c_hat_mm;
  rec.alpha_hat = report.alpha_hat;
  rec.beta_hat = report.beta_hat;
  rec.resets = report.resets_total - result.resets;
  result.resets = report.resets_total;
  result.bad_parts += rec.bad ? 1 : 0;
  result.parts.push_back(std::move(rec));
  return true;
}

double deflection_rms_mm(const BoringRunResult& result, double d0_mm) {
  double sum_sq = 0.0;
  int n_sq = 0;
  for (const BoringPartRecord& rec : result.parts) {
    if (rec.part <= 1) continue;
    for (const BoringPositionRecord& pos : rec.positions) {
      sum_sq += (pos.true_deflection_mm - d0_mm) * (pos.true_deflection_mm - d0_mm);
      ++n_sq;
    }
  }
  return n_sq > 0 ? std::sqrt(sum_sq / n_sq) : 0.0;
}

BoringRunResult run_boring(const BoringRunRequest& r, std::uint64_t seed) {
  BoringDirectLink planner;
  return run_boring(r, seed, planner);
}

}  // namespace tnv::hil
