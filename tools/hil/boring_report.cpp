#include "tools/hil/boring_report.hpp"

#include <cstdio>

namespace tnv::hil {

namespace {

nlohmann::json settings_json(const BoringRunRequest& r, int seeds) {
  const fw::BoringPlannerParams& p = r.planner;
  nlohmann::json j = {{"sigma_mm", p.sigma_d_mm},
          {"process_sigma_mm", r.process_sigma_mm},
          {"band_sigma_mm", r.band_sigma_mm},
          {"band_half_width_mm", p.band_sigmas * r.band_sigma_mm},
          {"d0_mm", p.target_deflection_mm},
          {"alpha0", p.alpha0},
          {"s0_mm_rev", p.nominal_infeed_mm_rev},
          {"infeed_range_mm_rev", {p.infeed_min_mm_rev, p.infeed_max_mm_rev}},
          {"positions_mm", r.positions_mm},
          {"parts", r.parts},
          {"change_at", r.change_at},
          {"seeds", seeds},
          {"gain_form", fw::to_string(p.gain_form)},
          {"reset_count", fw::to_string(p.reset_count)},
          {"reset_after", p.reset_after},
          {"startup_in_rls", p.startup_in_rls},
          {"log_base", fw::to_string(p.log_base)},
          {"p0", p.initial_covariance}};
  if (r.gauge_noise_mm_rms > 0.0 || r.gauge_resolution_mm > 0.0)  // a bench's gauge (--scenario)
    j["bench_gauge"] = {{"noise_mm_rms", r.gauge_noise_mm_rms},
                        {"resolution_mm", r.gauge_resolution_mm},
                        {"seed", r.gauge_seed}};
  return j;
}

nlohmann::json part_json(const BoringPartRecord& p) {
  nlohmann::json positions = nlohmann::json::array();
  for (const BoringPositionRecord& q : p.positions)
    positions.push_back({{"overhang_mm", q.overhang_mm},
                         {"infeed_mm_rev", q.infeed_mm_rev},
                         {"optimal_infeed_mm_rev", q.optimal_infeed_mm_rev},
                         {"true_deflection_mm", q.true_deflection_mm},
                         {"measured_deflection_mm", q.measured_deflection_mm},
                         {"infeed_limited", q.infeed_limited},
                         {"cut_infeed_mm_rev", q.cut_infeed_mm_rev},
                         {"cut_overhang_mm", q.cut_overhang_mm}});
  return {{"part", p.part},
          {"pass_error_mm", {{"min", p.pass_min_error_mm}, {"max", p.pass_max_error_mm}}},
          {"true", {{"c_mm", p.true_c_mm}, {"alpha", p.true_alpha}, {"beta", p.true_beta}}},
          {"estimate", {{"c_mm", p.c_hat_mm}, {"alpha", p.alpha_hat}, {"beta", p.beta_hat}}},
          {"bad", p.bad},
          {"reset", p.reset},
          {"out_of_band", p.out_of_band},
          {"positions", positions}};
}

}  // namespace

nlohmann::json boring_sweep_json(const BoringRunRequest& r, const BoringSweepResult& s) {
  nlohmann::json segments = nlohmann::json::array();
  for (const BoringSegmentStats& g : s.segments)
    segments.push_back({{"first_part", g.first_part},
                        {"last_part", g.last_part},
                        {"bad_parts_mean", g.bad_parts_mean},
                        {"bad_parts_min", g.bad_parts_min},
                        {"bad_parts_max", g.bad_parts_max},
                        {"resets_mean", g.resets_mean},
                        {"seeds_without_bad", g.seeds_without_bad},
                        {"seeds_without_reset", g.seeds_without_reset},
                        {"seeds_with_one_reset", g.seeds_with_one_reset},
                        {"estimate_error_at_end",
                         {{"c_rel", g.c_rel_error_end},
                          {"alpha", g.alpha_error_end},
                          {"beta", g.beta_error_end},
                          {"c_rel_abs", g.c_rel_abs_error_end},
                          {"alpha_abs", g.alpha_abs_error_end},
                          {"beta_abs", g.beta_abs_error_end}}}});
  nlohmann::json parts = nlohmann::json::array();
  for (const BoringPartRecord& p : s.seed1.parts) parts.push_back(part_json(p));
  nlohmann::json j = {{"settings", settings_json(r, s.seeds)},
                      {"planner", s.planner},
                      {"bad_parts_mean", s.bad_parts_mean},
                      {"bad_parts_max", s.bad_parts_max},
                      {"resets_mean", s.resets_mean},
                      {"deflection_rms_mm", s.deflection_rms_mean_mm},
                      {"segments", segments},
                      {"bad_fraction_by_part", s.bad_fraction_by_part},
                      {"reset_fraction_by_part", s.reset_fraction_by_part},
                      {"seed1", {{"bad_parts", s.seed1.bad_parts}, {"resets", s.seed1.resets}, {"parts", parts}}}};
  if (s.first_seed != 1) j["settings"]["first_seed"] = s.first_seed;  // a part of a split sweep
  if (!s.error.empty()) j["error"] = s.error;
  return j;
}

std::string boring_sweep_text(const BoringRunRequest& r, const BoringSweepResult& s) {
  const fw::BoringPlannerParams& p = r.planner;
  std::string out;
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "S4 adaptive boring: sigma_d %.6g mm (gauge %.6g mm), alpha0 %.3g, S0 %.3g mm/rev, %d parts, %d seeds\n"
                "planner: gain form %s, reset after %d %s out of d0 %.4g +- %.4g mm, start-up in RLS %s, log %s\n"
                "bad part: true deflection outside d0 +- %.4g mm at either position\n",
                p.sigma_d_mm, r.process_sigma_mm, p.alpha0, p.nominal_infeed_mm_rev, r.parts, s.seeds, fw::to_string(p.gain_form),
                p.reset_after, fw::to_string(p.reset_count), p.target_deflection_mm, p.band_sigmas * p.sigma_d_mm,
                p.startup_in_rls ? "yes" : "no", fw::to_string(p.log_base), p.band_sigmas * r.band_sigma_mm);
  out += buf;
  if (s.first_seed != 1) {  // a part of a split sweep
    std::snprintf(buf, sizeof buf, "seeds %llu..%llu (seed1 below: seed %llu)\n",
                  static_cast<unsigned long long>(s.first_seed),
                  static_cast<unsigned long long>(s.first_seed + static_cast<std::uint64_t>(s.seeds) - 1),
                  static_cast<unsigned long long>(s.first_seed));
    out += buf;
  }
  if (r.gauge_noise_mm_rms > 0.0 || r.gauge_resolution_mm > 0.0) {
    std::snprintf(buf, sizeof buf, "bench gauge: %.4g mm rms on the bore error, read in steps of %.4g mm\n",
                  r.gauge_noise_mm_rms, r.gauge_resolution_mm);
    out += buf;
  }
  out += "planner runs: " + s.planner + "\n\n";
  std::snprintf(buf, sizeof buf, "bad parts: mean %.3f, max %d    resets: mean %.3f    rms(d - d0) parts 2..: %.4f mm\n\n",
                s.bad_parts_mean, s.bad_parts_max, s.resets_mean, s.deflection_rms_mean_mm);
  out += buf;
  out += "parts     bad mean  min  max  no-bad   resets mean  no-reset  one-reset   at segment end: C_hat/C-1  alpha err  beta err\n";
  for (const BoringSegmentStats& g : s.segments) {
    std::snprintf(buf, sizeof buf, "%3d-%-3d   %8.3f  %3d  %3d  %5.1f%%   %11.3f  %7.1f%%  %8.1f%%   %+22.3f  %+9.3f  %+8.3f\n",
                  g.first_part, g.last_part, g.bad_parts_mean, g.bad_parts_min, g.bad_parts_max,
                  100.0 * g.seeds_without_bad, g.resets_mean, 100.0 * g.seeds_without_reset,
                  100.0 * g.seeds_with_one_reset, g.c_rel_error_end, g.alpha_error_end, g.beta_error_end);
    out += buf;
  }
  if (s.seed1.parts.empty()) return out;
  out += "\nseed 1: per part (S = commanded infeed mm/rev, S* = optimal, d = true deflection mm, m = measured)\n";
  const BoringPartRecord& first = s.seed1.parts.front();
  out += "part";
  for (const BoringPositionRecord& q : first.positions) {
    std::snprintf(buf, sizeof buf, " |  L=%-4.0f S       S*      d       m     ", q.overhang_mm);
    out += buf;
  }
  out += " |  C_hat    alpha  beta\n";
  const std::size_t max_rows = 60;
  for (std::size_t k = 0; k < s.seed1.parts.size() && k < max_rows; ++k) {
    const BoringPartRecord& rec = s.seed1.parts[k];
    std::snprintf(buf, sizeof buf, "%4d", rec.part);
    out += buf;
    for (const BoringPositionRecord& q : rec.positions) {
      std::snprintf(buf, sizeof buf, " |  %7.4f %7.4f %7.4f %7.4f ", q.infeed_mm_rev, q.optimal_infeed_mm_rev,
                    q.true_deflection_mm, q.measured_deflection_mm);
      out += buf;
    }
    std::snprintf(buf, sizeof buf, " |  %7.4f %6.3f %6.3f %s%s\n", rec.c_hat_mm, rec.alpha_hat, rec.beta_hat,
                  rec.bad ? " BAD" : "", rec.reset ? " RESET" : "");
    out += buf;
  }
  if (s.seed1.parts.size() > max_rows) out += "(more parts in --json)\n";
  if (!s.error.empty()) out += "error: " + s.error + "\n";
  return out;
}

}  // namespace tnv::hil
