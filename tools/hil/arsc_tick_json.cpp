#include "tools/hil/arsc_tick_json.hpp"

namespace tnv::hil {

using nlohmann::json;
using fw::arsc::OuterGains;

nlohmann::json tick_study_json(const TickStudyResult& r) {
  const TickTestStage& ts = r.test_stage;
  const OuterGains& g = r.initial_gains;
  json poles_s = json::array(), target_z = json::array();
  for (const auto& s : r.poles.force_s) poles_s.push_back({s.real(), s.imag()});
  for (const auto& z : r.target_z) target_z.push_back({z.real(), z.imag()});
  const double ticks = r.ticks > 0 ? static_cast<double>(r.ticks) : 1.0;
  json j = {{"label", r.config.label},
            {"error", r.error},
            {"outer_loop", r.config.outer_loop},
            {"period_s", r.period_s},
            {"period_ms", r.period_s * 1e3},
            {"pole_set", to_string(r.config.poles)},
            {"pole_speedup", r.config.pole_speedup},
            {"adapt", r.config.adapt},
            {"force_ref_n", r.config.force_ref_n},
            {"settle_s", r.config.settle_s},
            {"duration_s", r.config.duration_s},
            {"force_error_max_pct", r.force_error_max_pct},
            {"force_error_max_at_s", r.force_error_max_at_s},
            {"force_error_rms_pct", r.force_error_rms_pct},
            {"force_error_true_max_pct", r.force_error_true_max_pct},
            {"force_error_true_rms_pct", r.force_error_true_rms_pct},
            {"scenario", r.config.table.name},
            {"diverged", r.diverged},
            {"diverged_at_s", r.diverged ? json(r.diverged_at_s) : json(nullptr)},
            {"fault", r.fault.empty() ? json(nullptr) : json(r.fault)},
            {"dac_saturated_ticks", r.dac_saturated_ticks},
            {"dac_saturated_fraction", static_cast<double>(r.dac_saturated_ticks) / ticks},
            {"dac_saturated_longest_s", r.dac_saturated_longest_s},
            {"first_dac_saturation_s", r.first_dac_saturation_s < 0.0 ? json(nullptr) : json(r.first_dac_saturation_s)},
            {"adc_full_scale_ticks", r.adc_full_scale_ticks},
            {"command_clamped_samples", r.clamped_samples},
            {"command_clamped_after_settle", r.clamped_after_settle},
            {"last_clamp_s", r.last_clamp_s < 0.0 ? json(nullptr) : json(r.last_clamp_s)},
            {"samples", r.samples},
            {"ticks", r.ticks},
            {"refused_gain_updates", r.refused_updates},
            {"refused_segments", r.refused_segments},
            {"program_end_s", r.program_end_s < 0.0 ? json(nullptr) : json(r.program_end_s)},
            {"path", to_string(r.config.path)},
            {"accel_ratio_max", r.accel_ratio_max},
            {"jerk_ratio_max", r.jerk_ratio_max},
            {"override_min_seen", r.override_min_seen},
            {"override_max_seen", r.override_max_seen},
            {"travel_mm", r.travel_mm},
            {"travel_x_mm", r.travel_x_mm},
            {"max_feed_mm_s", r.max_feed_mm_s},
            {"force_poles_rad_s", poles_s},
            {"target_poles_z", target_z},
            {"initial_gains", {{"k", g.k}, {"gamma31", g.gamma31}, {"gamma32", g.gamma32}, {"gamma33", g.gamma33}}},
            {"max_abs_gain", r.max_abs_gain},
            {"program", {{"feed_mm_s", r.config.outer_loop ? r.config.program_feed_mm_s : r.config.constant_feed_mm_s},
                         {"segment_mm", r.config.segment_mm},
                         {"start_mm", r.config.start_mm},
                         {"end_x_mm", r.config.end_x_mm},
                         {"path_speed_mm_s", r.config.path_limits.speed_mm_s},
                         {"path_accel_mm_s2", r.config.path_limits.accel_mm_s2},
                         {"path_jerk_mm_s3", r.config.path_limits.jerk_mm_s3}}},
            {"arsc_params", {{"enable", r.arsc.enabled},
                             {"force_ref_n", r.arsc.force_ref_n},
                             {"period_ticks", r.arsc.period_ticks},
                             {"pole_re_rad_s", r.arsc.pole_re_rad_s},
                             {"pole_im_rad_s", r.arsc.pole_im_rad_s},
                             {"force_time_constant_s", r.arsc.force_time_constant_s},
                             {"cutting_gain_n_per_mm_s", r.arsc.cutting_gain_n_per_mm_s},
                             {"drive_time_constant_s", r.arsc.drive_time_constant_s},
                             {"memory_s", r.arsc.memory_s},
                             {"adapt", r.arsc.adapt}}},
            {"test_stage", {{"force_time_constant_s", ts.force_time_constant_s},
                            {"cutting_gain_n_per_mm_s", ts.cutting_gain_n_per_mm_s},
                            {"drive_time_constant_s", ts.drive_time_constant_s},
                            {"drive_gain", ts.drive_gain},
                            {"force_rms_n", ts.force_rms_n},
                            {"drive_rms_mm_s", ts.drive_rms_mm_s}}}};
  if (r.config.path == StudyPath::stock_step) {
    const StockStepCase& k = r.config.stock;
    j["stock_step"] = {{"spindle_rpm", k.spindle_rpm},
                       {"start_depth_mm", k.start_depth_mm},
                       {"step_mm", k.step_mm},
                       {"step_after_mm", k.step_after_mm},
                       {"step_ramp_mm", k.step_ramp_mm},
                       {"judged_after_s", k.judged_after_s},
                       {"step_at_s", r.step_at_s < 0.0 ? json(nullptr) : json(r.step_at_s)},
                       {"depth_before_mm", r.depth_before_mm},
                       {"depth_after_mm", r.depth_after_mm},
                       {"feed_before_mm_s", r.feed_before_mm_s},
                       {"feed_after_mm_s", r.feed_after_mm_s},
                       {"force_error_pct", r.step_error_pct},
                       {"force_error_measured_pct", r.step_error_measured_pct},
                       {"after_max_pct", r.after_step_max_pct},
                       {"after_measured_max_pct", r.after_step_measured_max_pct},
                       {"crashes", r.crashes}};
  }
  if (!r.config.outer_loop) {  // no force loop: nothing was designed
    j["constant_feed_mm_s"] = r.config.constant_feed_mm_s;
    for (const char* key : {"force_poles_rad_s", "target_poles_z", "initial_gains", "pole_set", "pole_speedup"})
      j[key] = nullptr;
  }
  return j;
}

}  // namespace tnv::hil
