#include "tools/hil/arsc_tick_study.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>

#include "emulator/force_adc.hpp"
#include "emulator/machine.hpp"
#include "firmware/adaptive/arsc/outer_arsc.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/arsc_test_stage.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {

namespace {

using hal::Axis;
constexpr double kTickS = 1e-3;

// The force the firmware sees: the ADC code of this tick's snapshot in N
// (the sensor's calibration is a hardware fact, like the DAC scale).
double force_n(const fw::TickRecord& rec, const emu::Scenario& s) {
  const double volts = static_cast<double>(rec.force_code) * emu::kAdcFullScaleV /
                       static_cast<double>((1u << hal::regs::kAdcBits) - 1);
  return volts / s.force_sensor.volts_per_n;
}

fw::FirmwareConfig study_firmware_config(const TickStudyConfig& c) {
  fw::FirmwareConfig base = fw::default_firmware_config();
  const double period_s = kTickS * static_cast<double>(c.ticks_per_sample);
  for (fw::AxisConfig& a : base.axis) {
    a.jog = c.jog;
    // The outer loop sends once per period: the dead man outlasts that silence with a period to spare.
    a.jog.deadman_s = std::max(c.jog.deadman_s, 2.0 * period_s);
  }
  return base;
}

// Servo on, holding, X ready to jog.
std::unique_ptr<HilRig> ready_rig(const emu::Scenario& s, const TickStudyConfig& c, std::string& error) {
  std::unique_ptr<HilRig> rig = HilRig::create(s, study_firmware_config(c), fw::ControllerKind::rdvsc, error);
  if (!rig) return rig;
  rig->home();
  if (rig->task.hold_position() != fw::CommandStatus::ok) {
    error = "servo-on refused";
    return nullptr;
  }
  rig->tick();
  return rig;
}

bool send_feed(fw::TickTask& task, double feed_mm_s) {
  if (feed_mm_s == 0.0 && task.state() == fw::MotionState::holding) return true;  // at rest already
  return task.jog(Axis::x, feed_mm_s) == fw::CommandStatus::ok;
}

}  // namespace

emu::Scenario tick_study_scenario(const emu::MillingParams& milling) {
  emu::Scenario s;
  s.name = "mill-x";
  s.milling = milling;
  s.milling.enabled = true;
  return s;
}

fw::arsc::OuterPoles outer_poles(fw::arsc::PoleSet set, double speedup) noexcept {
  const fw::arsc::Poles7 z = fw::arsc::paper_poles(set);
  fw::arsc::OuterPoles p;
  // Elements 1, 2: the force-loop pair (a conjugate pair for case3/4, two equal real poles for case1/2).
  for (std::size_t i = 0; i < 2; ++i) p.force_s[i] = speedup * std::log(z[i + 1]) / fw::arsc::kPaperSamplePeriod_s;
  if (p.force_s[0].imag() == 0.0) p.force_s[1] = p.force_s[0];
  else p.force_s[1] = std::conj(p.force_s[0]);
  return p;
}

TickTestStage run_tick_test_stage(const TickStudyConfig& c, std::string& error) {
  TickTestStage fit;
  emu::MillingParams m = c.milling;
  m.depth = {c.milling.depth.start_mm, c.milling.depth.start_mm, 1.0, 1.0};
  const emu::Scenario s = tick_study_scenario(m);
  std::unique_ptr<HilRig> rig = ready_rig(s, c, error);
  if (!rig) return fit;
  // Two-level feed 40 +- 10 mm/s (about 120 N at 0.2 mm), switching with probability 1/2
  // every 0.3 s: slower than the axis, comparable to the force's time constant.
  const auto ticks = static_cast<std::size_t>(c.test_stage_s / kTickS);
  const std::vector<double> u = test_stage_input(ticks, 40.0, 10.0, 300, 11);
  std::vector<double> f(ticks + 1), v(ticks + 1), p(ticks + 1);
  const auto read = [&](std::size_t k) {
    const fw::TickRecord& rec = rig->task.last_record();
    f[k] = force_n(rec, s);
    v[k] = rec.axis[0].speed_mm_s;
    p[k] = rec.axis[0].position_mm;
  };
  read(0);
  for (std::size_t k = 0; k < ticks; ++k) {
    if (!send_feed(rig->task, u[k])) {
      error = "test stage: jog refused";
      return fit;
    }
    rig->tick();
    read(k + 1);
  }
  if (rig->task.state() == fw::MotionState::faulted) {
    error = std::string("test stage: firmware fault ") + fw::to_string(rig->task.fault().reason);
    return fit;
  }
  // Drive at the tick: v(k+1) = a v(k) + b u(k-1) (the command reaches the axis one tick later).
  const std::size_t skip = 50;
  {
    const auto n = static_cast<Eigen::Index>(ticks - skip - 1);
    Eigen::MatrixXd x(n, 2);
    Eigen::VectorXd y(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const std::size_t k = skip + static_cast<std::size_t>(i);
      x(i, 0) = v[k];
      x(i, 1) = u[k - 1];
      y(i) = v[k + 1];
    }
    const Eigen::Vector2d ab = x.colPivHouseholderQr().solve(y);
    fit.drive_time_constant_s = -kTickS / std::log(std::clamp(ab(0), 1e-6, 1.0 - 1e-9));
    fit.drive_gain = ab(1) / (1.0 - ab(0));
    fit.drive_rms_mm_s = std::sqrt((x * ab - y).squaredNorm() / static_cast<double>(n));
  }
  // Force over 10 ms with the mean feed: f(j+1) = a f(j) + b vbar(j).
  {
    const std::size_t step = 10;
    const std::size_t count = (ticks - skip) / step - 1;
    const auto n = static_cast<Eigen::Index>(count);
    Eigen::MatrixXd x(n, 2);
    Eigen::VectorXd y(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const std::size_t k = skip + static_cast<std::size_t>(i) * step;
      x(i, 0) = f[k];
      x(i, 1) = (p[k + step] - p[k]) / (kTickS * static_cast<double>(step));
      y(i) = f[k + step];
    }
    const Eigen::Vector2d ab = x.colPivHouseholderQr().solve(y);
    const double a = std::clamp(ab(0), 1e-6, 1.0 - 1e-9);
    fit.force_time_constant_s = -kTickS * static_cast<double>(step) / std::log(a);
    fit.cutting_gain_n_per_mm_s = ab(1) / (1.0 - a);
    fit.force_rms_n = std::sqrt((x * ab - y).squaredNorm() / static_cast<double>(n));
    fit.samples = count;
  }
  return fit;
}

TickStudyResult run_tick_study(const TickStudyConfig& c) {
  TickStudyResult r;
  r.config = c;
  const std::uint32_t n = std::max<std::uint32_t>(1, c.ticks_per_sample);
  r.period_s = kTickS * static_cast<double>(n);

  r.test_stage = run_tick_test_stage(c, r.error);
  if (!r.error.empty()) return r;
  const TickTestStage& ts = r.test_stage;

  using namespace fw::arsc;
  OuterArscConfig ac;
  ac.period_s = r.period_s;
  ac.model.force_time_constant_s = ts.force_time_constant_s;
  ac.model.drive_time_constant_s = ts.drive_time_constant_s;
  ac.model.command_delay_s = kTickS;  // the jog target reaches the axis at the next tick
  ac.model.cutting_gain = ts.cutting_gain_n_per_mm_s * c.feed_scale_mm_s / c.force_ref_n;
  ac.poles = outer_poles(c.poles, c.pole_speedup);
  ac.force_scale_n = c.force_ref_n;
  ac.feed_scale_mm_s = c.feed_scale_mm_s;
  ac.force_ref_n = 0.0;
  ac.feed_min_mm_s = 0.0;
  ac.feed_max_mm_s = c.jog.speed_max_mm_s;
  ac.memory_s = c.memory_s;
  ac.adapt = c.adapt;
  ac.limits.max_gain = 1.0e4;  // normalised; a runaway design (g at a projection bound) is refused
  ac.gain_min = 0.2 * ac.model.cutting_gain;
  ac.gain_max = 20.0 * ac.model.cutting_gain;
  if (const fw::ParamCheck p = validate(ac); !p.ok) {
    r.error = std::string("outer ARSC config: ") + p.field + ": " + p.reason;
    return r;
  }
  OuterArsc arsc(ac);
  if (!arsc.signals().have_gains) {
    r.error = std::string("no gains for the identified model: ") + to_string(arsc.signals().last_reason);
    return r;
  }
  r.initial_gains = arsc.signals().gains;
  r.poles = ac.poles;
  r.target_z = outer_target_poles(discretise(ac.model, r.period_s), r.period_s, ac.poles);

  const emu::Scenario s = tick_study_scenario(c.milling);
  std::unique_ptr<HilRig> rig = ready_rig(s, c, r.error);
  if (!rig) return r;
  fw::TickTask& task = rig->task;
  const fw::DacScale& dac = task.config().axis[0].dac;
  const double start_mm = task.last_record().axis[0].position_mm;
  double last_sample_mm = start_mm;
  const auto ticks = static_cast<std::uint64_t>(std::llround(c.duration_s / kTickS));
  double sum_sq = 0.0, f_ref_n = 0.0, command_mm_s = 0.0;
  std::uint64_t scored = 0, saturated_run = 0, pinned_run = 0;
  const double full_scale_n = emu::kAdcFullScaleV / s.force_sensor.volts_per_n;
  for (std::uint64_t k = 0; k < ticks; ++k) {
    const double t_s = static_cast<double>(k) * kTickS;
    const fw::TickRecord& rec = task.last_record();
    const double f_n = force_n(rec, s);
    // Outer loop: one sample every n ticks, the command is sent before the next tick.
    if (k % n == 0) {
      const double ramp = c.soft_start_s > 0.0 ? std::min(1.0, t_s / c.soft_start_s) : 1.0;
      f_ref_n = ramp * c.force_ref_n;
      const double position_mm = rec.axis[0].position_mm;
      const double mean_feed_mm_s = (position_mm - last_sample_mm) / r.period_s;
      last_sample_mm = position_mm;
      if (c.outer_loop) {
        arsc.set_force_ref_n(f_ref_n);
        command_mm_s = arsc.step(f_n, rec.axis[0].speed_mm_s, mean_feed_mm_s);
        const OuterGains& g = arsc.signals().gains;
        for (double x : {g.k, g.gamma31, g.gamma32, g.gamma33}) r.max_abs_gain = std::max(r.max_abs_gain, std::fabs(x));
      } else {
        command_mm_s = ramp * c.constant_feed_mm_s;
      }
      if (!send_feed(task, command_mm_s)) ++r.refused_jogs;
      ++r.samples;
    }
    if (t_s >= c.settle_s) {
      const double e = std::fabs(f_n - c.force_ref_n) / c.force_ref_n * 100.0;
      if (e > r.force_error_max_pct) r.force_error_max_at_s = t_s;
      r.force_error_max_pct = std::max(r.force_error_max_pct, e);
      sum_sq += e * e;
      ++scored;
    }
    if (k % 10 == 0) {
      const double depth = rig->machine.milling_depth_mm();
      r.trace.push_back({t_s, depth, f_n, f_ref_n, rig->machine.truth(Axis::x).speed_mm_s, command_mm_s,
                         c.outer_loop ? arsc.cutting_gain_n_per_mm_s() : ts.cutting_gain_n_per_mm_s,
                         s.milling.force_n_per_mm_mm_s * depth});
    }
    rig->tick();
    const fw::TickRecord& now = task.last_record();
    const std::uint16_t code = now.axis[0].dac_code;
    if (code == 0 || code == dac.max_code()) {
      ++r.dac_saturated_ticks;
      ++saturated_run;
      r.dac_saturated_longest_s = std::max(r.dac_saturated_longest_s, static_cast<double>(saturated_run) * kTickS);
      if (r.first_dac_saturation_s < 0.0) r.first_dac_saturation_s = t_s;
    } else {
      saturated_run = 0;
    }
    r.max_feed_mm_s = std::max(r.max_feed_mm_s, rig->machine.truth(Axis::x).speed_mm_s);
    ++r.ticks;
    const bool pinned = force_n(now, s) >= 0.999 * full_scale_n;
    r.adc_full_scale_ticks += pinned ? 1u : 0u;
    pinned_run = pinned ? pinned_run + 1 : 0;
    if (task.state() == fw::MotionState::faulted || (c.outer_loop && pinned_run >= 100)) {
      r.diverged = true;
      r.diverged_at_s = t_s;
      if (task.state() == fw::MotionState::faulted) r.fault = fw::to_string(task.fault().reason);
      break;
    }
  }
  r.force_error_rms_pct = scored ? std::sqrt(sum_sq / static_cast<double>(scored)) : 0.0;
  if (r.diverged) r.force_error_max_pct = std::max(r.force_error_max_pct, 100.0);
  r.travel_mm = task.last_record().axis[0].position_mm - start_mm;
  r.deadman_stops = task.jog_deadman_stops();
  r.clamped_samples = arsc.signals().clamped_samples;
  const auto& counts = arsc.signals().reason_counts;
  for (std::size_t i = 1; i < counts.size(); ++i) r.refused_updates += counts[i];
  return r;
}

}  // namespace tnv::hil
