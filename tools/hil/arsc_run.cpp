#include "tools/hil/arsc_run.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "emulator/noise_stream.hpp"
#include "firmware/adaptive/arsc/faithful_arsc.hpp"
#include "firmware/adaptive/arsc/robust_arsc.hpp"

namespace tnv::hil {

namespace {

using namespace fw::arsc;

// One interface over the two variants for the run loop.
struct Loop {
  virtual ~Loop() = default;
  virtual double step(double force, double feed) = 0;
  virtual const ArscSignals& signals() const = 0;
  virtual void fill(ArscTracePoint& p) const = 0;
};

struct FaithfulLoop final : Loop {
  explicit FaithfulLoop(const FaithfulArscConfig& c) : arsc(c) {}
  double step(double f, double v) override { return arsc.step(f, v); }
  const ArscSignals& signals() const override { return arsc.signals(); }
  void fill(ArscTracePoint& p) const override {
    const Arv2Model m = arsc.model();
    p.theta = {-m.phi1(0, 0), -m.phi1(0, 1), -m.phi2(0, 0), -m.phi2(0, 1), m.theta0(0),
               -m.phi1(1, 0), -m.phi1(1, 1), -m.phi2(1, 0), -m.phi2(1, 1), m.theta0(1)};
    p.cutting_gain = -m.phi1(0, 1);
  }
  FaithfulArsc arsc;
};

struct RobustLoop final : Loop {
  explicit RobustLoop(const RobustArscConfig& c) : arsc(c) {}
  double step(double f, double v) override { return arsc.step(f, v); }
  const ArscSignals& signals() const override { return arsc.signals(); }
  void fill(ArscTracePoint& p) const override { p.cutting_gain = arsc.model().cutting_gain; }
  RobustArsc arsc;
};

}  // namespace

ArscScenarioNoise arsc_force_noise(const emu::Scenario& s) {
  ArscScenarioNoise out;
  out.noise.seed = s.noise.seed;
  if (s.noise.force_adc_v_rms == 0.0) return out;
  if (!(s.force_sensor.volts_per_n > 0.0)) {
    out.error = "force_sensor.volts_per_n is 0: the force ADC would read noise only";
    return out;
  }
  const double noise_n = s.noise.force_adc_v_rms / s.force_sensor.volts_per_n;  // V / (V/N)
  out.noise.rms = noise_n / kS3ForceReferenceN;                                // f* = 1 is 150 N
  return out;
}

double robust_gain_trend_alpha(const ArscRunConfig& c) noexcept {
  if (c.robust_gain_trend_alpha > 0.0) return c.robust_gain_trend_alpha;
  return c.force_noise.rms > 0.0 ? kNoisyGainTrendAlpha : 1.0;
}

ArscRunResult run_arsc(const ArscRunConfig& config) {
  ArscRunResult r;
  r.config = config;
  r.process_coefficients = emu::milling_coefficients(config.process);
  const Poles7 poles = paper_poles(config.poles);
  // One stream for the test stage and the cut, in that order (the force ADC's stream number).
  emu::NoiseStream noise = emu::make_noise_stream(config.force_noise.seed, emu::NoiseStreamId::force_adc);
  const auto measured = [&](double force) {
    return config.force_noise.rms > 0.0 ? force + config.force_noise.rms * noise.normal() : force;
  };

  std::unique_ptr<Loop> loop;
  if (config.variant == ArscVariant::faithful) {
    FaithfulArscConfig c;
    c.d_star = desired_coefficients(poles);
    c.rls = config.faithful_rls;
    c.force_ref = config.force_ref;
    loop = std::make_unique<FaithfulLoop>(c);
  } else {
    std::vector<TestStageSample> stage = run_test_stage(config.process, config.depth.start_mm, config.test_stage_samples);
    for (TestStageSample& sample : stage) sample.force = measured(sample.force);
    r.test_stage = fit_structured_model(stage, false);
    const StructuredModel& m = r.test_stage->model;
    RobustArscConfig c;
    c.d_star = desired_coefficients(six_of_seven(poles));
    c.drive = m.drive;
    c.estimator.a21 = m.a21;
    c.estimator.initial_gain = m.cutting_gain;
    c.estimator.forgetting = config.robust_forgetting;
    c.estimator.initial_covariance = config.robust_initial_covariance;
    c.gain_trend.alpha = robust_gain_trend_alpha(config);
    c.force_ref = config.force_ref;
    loop = std::make_unique<RobustLoop>(c);
  }

  emu::MillingProcess process(config.process);
  const auto samples = static_cast<std::size_t>(std::llround(config.duration_s / config.process.sample_s));
  r.trace.reserve(samples + 1);
  double u_applied = 0.0;  // the process is at rest with no input before the start
  double sum_sq = 0.0;
  for (std::size_t n = 0; n <= samples; ++n) {
    const double t_s = static_cast<double>(n) * config.process.sample_s;
    const double depth_mm = emu::depth_profile_mm(config.depth, t_s);
    const double f = process.force(), v = process.feed();
    const double f_measured = measured(f);
    const double u_next = loop->step(f_measured, v);

    ArscTracePoint p;
    p.t_s = t_s;
    p.depth_mm = depth_mm;
    p.force = f;
    p.force_measured = f_measured;
    p.feed = v;
    p.u = u_applied;
    const ArscSignals& s = loop->signals();
    p.gains = s.gains;
    p.have_gains = s.have_gains;
    p.reason = s.last_reason;
    p.true_cutting_gain = r.process_coefficients.b21 * depth_mm;
    loop->fill(p);
    r.trace.push_back(p);
    if (s.have_gains && !r.first_gains_s) r.first_gains_s = t_s;

    const double lim = config.divergence_limit;
    const bool diverging = !(std::fabs(f) <= lim && std::fabs(v) <= lim && std::fabs(u_next) <= lim);
    if (t_s >= config.settle_s - 1e-9 || diverging) {  // a divergence always counts
      const double e = std::fabs(f - config.force_ref) / config.force_ref * 100.0;
      r.force_error_max_pct = std::max(r.force_error_max_pct, std::isfinite(e) ? e : 1e300);
      sum_sq += e * e;
      ++r.scored_samples;
      if (e > 10.0) ++r.samples_over_10pct;
    }
    if (diverging) {
      r.diverged = true;
      r.diverged_at_s = t_s;
      break;
    }
    process.step(u_applied, depth_mm);  // S3 eqs. (27)-(28) with u(t), delta(t)
    u_applied = u_next;                 // computed at t, applied from t+1
  }
  r.reason_counts = loop->signals().reason_counts;
  r.force_error_rms_pct = r.scored_samples ? std::sqrt(sum_sq / static_cast<double>(r.scored_samples)) : 0.0;
  return r;
}

ArscSeedSweep run_arsc_seeds(const ArscRunConfig& config, int seeds) {
  ArscSeedSweep out;
  out.seeds = std::max(seeds, 1);
  double rms_sum = 0.0;
  for (int k = 0; k < out.seeds; ++k) {
    ArscRunConfig c = config;
    c.force_noise.seed = config.force_noise.seed + static_cast<std::uint64_t>(k);
    ArscRunResult r = run_arsc(c);
    out.force_error_max_pct_worst = std::max(out.force_error_max_pct_worst, r.force_error_max_pct);
    rms_sum += r.force_error_rms_pct;
    out.diverged_runs += r.diverged ? 1 : 0;
    if (k == 0) out.first = std::move(r);
  }
  out.force_error_rms_pct_mean = rms_sum / static_cast<double>(out.seeds);
  return out;
}

}  // namespace tnv::hil
