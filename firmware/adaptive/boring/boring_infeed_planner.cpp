#include "firmware/adaptive/boring/boring_infeed_planner.hpp"

#include "firmware/adaptive/boring/startup_estimate.hpp"

namespace tnv::fw {

BoringInfeedPlanner::BoringInfeedPlanner(const BoringPlannerParams& params) noexcept {
  status_ = validate(params);
  if (status_.ok) params_ = params;
  restart();
}

ParamCheck BoringInfeedPlanner::set_params(const BoringPlannerParams& params) noexcept {
  const ParamCheck check = validate(params);
  if (!check.ok) return check;
  params_ = params;
  status_ = check;
  restart();
  return check;
}

void BoringInfeedPlanner::restart() noexcept {
  rls_.reset(BoringTheta::Zero(), params_.initial_covariance);
  perturbation_.configure(params_.reset_count, params_.reset_after);
  started_ = false;
  parts_ = 0;
  resets_ = 0;
}

BoringPlannerState BoringInfeedPlanner::state() const noexcept {
  BoringPlannerState s;
  s.started = started_;
  s.parts = parts_;
  s.resets = resets_;
  s.theta = rls_.theta();
  s.covariance = rls_.covariance();
  s.innovation = rls_.last_innovation();
  s.streak = perturbation_.run();
  for (int i = 0; i < kMaxBorePositions; ++i)
    s.position_streak[static_cast<std::size_t>(i)] = perturbation_.position_run(i);
  return s;
}

ParamCheck BoringInfeedPlanner::restore(const BoringPlannerState& s) noexcept {
  if (!status_.ok) return status_;
  if (const ParamCheck check = validate(s, params_.initial_covariance); !check.ok) return check;
  std::array<int, kMaxBorePositions> runs{};
  for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = s.position_streak[i];
  rls_.restore(s.theta, s.covariance, s.innovation);
  perturbation_.restore(s.streak, runs);
  started_ = s.started;
  parts_ = s.parts;
  resets_ = s.resets;
  return param_ok();
}

InfeedCommand BoringInfeedPlanner::infeed(double overhang_mm) const noexcept {
  if (!status_.ok) {
    InfeedCommand out;
    out.check = status_;
    return out;
  }
  if (!started_) {
    InfeedCommand out = optimal_infeed(BoringTheta::Zero(), overhang_mm, params_);  // range check only
    if (out.check.ok) out = InfeedCommand{param_ok(), params_.nominal_infeed_mm_rev, false, false};
    return out;
  }
  return optimal_infeed(rls_.theta(), overhang_mm, params_);
}

double BoringInfeedPlanner::deflection_mm(const BoreMeasurement& m) const noexcept {
  return deflection_from_bore_error_mm(m.bore_error_mm, params_.target_deflection_mm, params_.force_angle_deg);
}

bool BoringInfeedPlanner::in_band(double deflection_mm) const noexcept {
  return std::fabs(deflection_mm - params_.target_deflection_mm) <= band_half_width_mm();
}

double BoringInfeedPlanner::estimated_c_mm() const noexcept {
  return std::exp(ln_of_base(params_.log_base) * rls_.theta()(0));
}

double BoringInfeedPlanner::noise_variance() const noexcept {
  return log_noise_variance(params_.sigma_d_mm, params_.target_deflection_mm, params_.log_base);
}

double BoringInfeedPlanner::gain_denominator_5() const noexcept {
  return params_.gain_form == BoringGainForm::normalised ? 1.0 : noise_variance();
}

double BoringInfeedPlanner::gain_denominator_6() const noexcept {
  return params_.gain_form == BoringGainForm::kalman ? noise_variance() : 1.0;
}

ParamCheck BoringInfeedPlanner::check_measurements(std::span<const BoreMeasurement> ms) const noexcept {
  if (!status_.ok) return status_;
  if (ms.empty() || ms.size() > static_cast<std::size_t>(kMaxBorePositions))
    return param_error("measurements", "a part needs 1 to kMaxBorePositions (8) measurements");
  for (const BoreMeasurement& m : ms) {
    if (!std::isfinite(m.overhang_mm) || m.overhang_mm < params_.overhang_min_mm ||
        m.overhang_mm > params_.overhang_max_mm)
      return param_error("overhang_mm", "must be finite and within [overhang_min_mm, overhang_max_mm]");
    if (!std::isfinite(m.infeed_mm_rev) || !(m.infeed_mm_rev > 0.0))
      return param_error("infeed_mm_rev", "must be finite and > 0");
    if (!std::isfinite(m.bore_error_mm)) return param_error("bore_error_mm", "must be finite (NaN or inf given)");
  }
  return param_ok();
}

BoringPartReport BoringInfeedPlanner::record_part(std::span<const BoreMeasurement> ms) noexcept {
  BoringPartReport report;
  report.check = check_measurements(ms);
  if (!report.check.ok) return report;
  report.measurements = static_cast<int>(ms.size());
  const double s5 = gain_denominator_5();
  const double s6 = gain_denominator_6();

  if (!started_) {
    DeflectionSample samples[kMaxBorePositions];
    for (std::size_t i = 0; i < ms.size(); ++i)
      samples[i] = {ms[i].overhang_mm, ms[i].infeed_mm_rev, deflection_mm(ms[i])};
    const StartupEstimate start =
        startup_estimate(std::span<const DeflectionSample>(samples, ms.size()), params_.alpha0, params_.log_base);
    if (!start.check.ok) {
      report.check = start.check;
      return report;
    }
    LogModelRls rls;
    rls.reset(start.theta, params_.initial_covariance);  // P0 = p0 I
    if (params_.startup_in_rls) {
      for (const DeflectionSample& s : std::span<const DeflectionSample>(samples, ms.size())) {
        const BoringRegressor x = boring_regressor(s.infeed_mm_rev, s.overhang_mm, params_.log_base);
        if (!rls.update(x, model_log(s.deflection_mm, params_.log_base), s5, s6)) {
          report.check = param_error("measurements", "start-up RLS update is not finite; part refused");
          return report;
        }
        ++report.rls_updates;
      }
    }
    for (const DeflectionSample& s : std::span<const DeflectionSample>(samples, ms.size()))
      report.out_of_band += in_band(s.deflection_mm) ? 0 : 1;
    rls_ = rls;
    perturbation_.clear();  // part 1 is cut at S0, not by the planner: it does not count
    started_ = true;
    ++parts_;
    report.startup = true;
    return report;
  }

  // Work on copies; commit only when the whole part went through.
  LogModelRls rls = rls_;
  VariancePerturbation perturbation = perturbation_;
  int resets = 0;
  bool any_out = false;
  for (std::size_t i = 0; i < ms.size(); ++i) {
    const double d = deflection_mm(ms[i]);
    const bool out = !in_band(d);
    any_out = any_out || out;
    report.out_of_band += out ? 1 : 0;
    // Section 5: reset before fitting the measurement that completes the run,
    // so the evidence of the change is fitted with the fresh covariance.
    if (perturbation.on_measurement(static_cast<int>(i), out)) {
      rls.reset_covariance(params_.initial_covariance);
      ++resets;
    }
    if (!(d > 0.0)) {
      ++report.skipped;
      continue;
    }
    const BoringRegressor x = boring_regressor(ms[i].infeed_mm_rev, ms[i].overhang_mm, params_.log_base);
    if (!rls.update(x, model_log(d, params_.log_base), s5, s6)) {
      report = BoringPartReport{};
      report.check = param_error("measurements", "RLS update is not finite; part refused");
      return report;
    }
    ++report.rls_updates;
  }
  if (perturbation.on_part_end(any_out)) {
    rls.reset_covariance(params_.initial_covariance);
    ++resets;
  }
  rls_ = rls;
  perturbation_ = perturbation;
  resets_ += resets;
  ++parts_;
  report.reset = resets > 0;
  return report;
}

}  // namespace tnv::fw
