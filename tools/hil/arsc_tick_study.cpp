#include "tools/hil/arsc_tick_study.hpp"

#include <algorithm>
#include <cmath>

#include "emulator/cutting_at_tool.hpp"
#include "firmware/adaptive/arsc/outer_arsc.hpp"
#include "firmware/io/force_code.hpp"
#include "tools/hil/hil_rig.hpp"
#include "tools/hil/program_feeder.hpp"

namespace tnv::hil {

using hal::Axis;

double study_force_n(const fw::TickRecord& rec, const fw::FirmwareConfig& firmware) noexcept {
  return fw::force_code_to_n(rec.force_code, firmware.force_sensor.n_per_volt);
}

fw::FirmwareConfig study_firmware_config(const TickStudyConfig& c, const fw::arsc::ArscSourceParams& arsc) {
  fw::FirmwareConfig base = fw::default_firmware_config();
  for (fw::AxisConfig& a : base.axis) a.path = c.path_limits;
  base.arsc = arsc;
  return base;
}

std::unique_ptr<HilRig> ready_study_rig(const emu::Scenario& s, const fw::FirmwareConfig& firmware,
                                        const TickStudyConfig& c, std::string& error) {
  std::unique_ptr<HilRig> rig = HilRig::create(s, firmware, fw::ControllerKind::rdvsc, error);
  if (!rig) return rig;
  rig->home();
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    if (rig->task.zero(hal::axis_from_index(i), c.start_mm[i]) != fw::CommandStatus::ok) {
      error = "zero refused";
      return nullptr;
    }
  }
  if (rig->task.hold_position() != fw::CommandStatus::ok) {
    error = "servo-on refused";
    return nullptr;
  }
  rig->tick();
  if (c.path == StudyPath::stock_step) {
    // The spindle at speed before the program, as an operator starts it.
    if (rig->task.spindle_start(fw::SpindleDirection::forward, c.stock.spindle_rpm) != fw::SpindleResult::ok) {
      error = "spindle start refused";
      return nullptr;
    }
    for (int k = 0; k < 20'000 && !rig->task.last_record().spindle.at_speed; ++k) rig->tick();
    if (!rig->task.last_record().spindle.at_speed) {
      error = "the spindle did not come to speed";
      return nullptr;
    }
  }
  return rig;
}

emu::Scenario stock_step_scenario(const emu::Scenario& table, const StockStepCase& k) {
  emu::Scenario s = table;
  s.name = "stock-step";
  s.milling.enabled = false;
  s.stock.enabled = true;
  const double tool_z_mm = emu::tool_point_z_mm(emu::power_up_position_mm(s, Axis::z), s.tool);
  s.stock.top_mm = tool_z_mm + k.start_depth_mm;
  s.stock.x_min_mm = emu::power_up_position_mm(s, Axis::x) + 0.5 * s.tool.diameter_mm + k.entry_mm;
  return s;
}

emu::Scenario study_scenario(const TickStudyConfig& c, const emu::MillingParams& milling) {
  return c.path == StudyPath::stock_step ? stock_step_scenario(c.table, c.stock) : tick_study_scenario(c.table, milling);
}

StudyProgram study_cut_program(const TickStudyConfig& c, double feed_mm_s, bool with_step) {
  if (c.path != StudyPath::stock_step || !with_step) {
    const StudyPath path = c.path == StudyPath::arc && with_step ? StudyPath::arc : StudyPath::line;
    return study_program(path, c.start_mm, c.end_x_mm, c.arc_at_x_mm, feed_mm_s, c.segment_mm);
  }
  const double x0 = c.start_mm[hal::index(Axis::x)];
  return stock_step_program(c.start_mm, x0 + c.stock.step_after_mm, c.stock.step_mm, c.stock.step_ramp_mm,
                            x0 + c.stock.length_mm, feed_mm_s, c.segment_mm);
}

emu::Scenario tick_study_scenario(const emu::Scenario& table, const emu::MillingParams& milling) {
  emu::Scenario s = table;
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

fw::arsc::ArscSourceParams study_arsc_params(const TickStudyConfig& c, const TickTestStage& fit) noexcept {
  fw::arsc::ArscSourceParams p;
  p.enabled = c.outer_loop;
  p.force_ref_n = c.force_ref_n;
  p.period_ticks = std::max<std::uint32_t>(1, c.ticks_per_sample);
  const fw::arsc::OuterPoles poles = outer_poles(c.poles, c.pole_speedup);
  p.pole_re_rad_s = poles.force_s[0].real();
  p.pole_im_rad_s = std::fabs(poles.force_s[0].imag());
  p.force_time_constant_s = fit.force_time_constant_s;
  p.cutting_gain_n_per_mm_s = fit.cutting_gain_n_per_mm_s;
  p.drive_time_constant_s = fit.drive_time_constant_s;
  p.memory_s = c.memory_s;
  p.adapt = c.adapt;
  p.soft_start_s = c.soft_start_s;
  return p;
}

namespace {

// Per-tick judging, kept apart from the run's sequencing.
struct Judge {
  const TickStudyConfig& c;
  TickStudyResult& r;
  std::array<std::array<double, 4>, hal::kAxisCount> ref{};  // x_ref,k .. x_ref,k-3 per axis
  std::uint64_t seen = 0, scored = 0, saturated_run = 0, pinned_run = 0;
  double sum_sq = 0.0, true_sum_sq = 0.0;

  void limits(const fw::TickRecord& rec) {
    constexpr double dt = kTickPeriodS;
    for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
      auto& h = ref[i];
      h = {rec.axis[i].reference_mm, h[0], h[1], h[2]};
      if (seen < 3) continue;
      const double a = (h[0] - 2.0 * h[1] + h[2]) / (dt * dt);
      const double j = (h[0] - 3.0 * h[1] + 3.0 * h[2] - h[3]) / (dt * dt * dt);
      r.accel_ratio_max = std::max(r.accel_ratio_max, std::fabs(a) / c.path_limits.accel_mm_s2);
      r.jerk_ratio_max = std::max(r.jerk_ratio_max, std::fabs(j) / c.path_limits.jerk_mm_s3);
    }
    ++seen;
  }
  void force(double t_s, double f_n) {
    if (t_s < c.settle_s) return;
    const double e = std::fabs(f_n - c.force_ref_n) / c.force_ref_n * 100.0;
    if (e > r.force_error_max_pct) r.force_error_max_at_s = t_s;
    r.force_error_max_pct = std::max(r.force_error_max_pct, e);
    sum_sq += e * e;
    ++scored;
  }
  void true_force(double t_s, double f_n) {
    if (t_s < c.settle_s) return;
    const double e = std::fabs(f_n - c.force_ref_n) / c.force_ref_n * 100.0;
    r.force_error_true_max_pct = std::max(r.force_error_true_max_pct, e);
    true_sum_sq += e * e;
  }
  void dac(double t_s, std::uint16_t code, std::uint16_t max_code) {
    if (code != 0 && code != max_code) {
      saturated_run = 0;
      return;
    }
    ++r.dac_saturated_ticks;
    ++saturated_run;
    r.dac_saturated_longest_s = std::max(r.dac_saturated_longest_s, static_cast<double>(saturated_run) * kTickPeriodS);
    if (r.first_dac_saturation_s < 0.0) r.first_dac_saturation_s = t_s;
  }
  // True when the force has sat at the ADC's full scale for 0.1 s.
  bool pinned(double f_n, double full_scale_n) {
    const bool at = f_n >= 0.999 * full_scale_n;
    r.adc_full_scale_ticks += at ? 1u : 0u;
    pinned_run = at ? pinned_run + 1 : 0;
    return pinned_run >= 100;
  }
};

// stock-step: when the depth stepped, and the force judged_after_s later.
constexpr double kStepBeginsMm = 0.01;
struct StepJudge {
  const TickStudyConfig& c;
  TickStudyResult& r;
  double last_depth_mm = 0.0;
  // The path feed over the last kFeedLookBack ticks: the feed "before" is the settled cut's, not the
  // planner's slowdown at the step's corner.
  static constexpr std::size_t kFeedLookBack = 500;
  std::array<double, kFeedLookBack> feeds{};
  std::size_t ticks_seen = 0;
  bool judged = false;

  void observe(double t_s, double depth_mm, double true_force_n, double measured_force_n, double feed_mm_s) {
    const auto error_pct = [this](double f_n) { return std::fabs(f_n - c.force_ref_n) / c.force_ref_n * 100.0; };
    // The step begins where a_p first leaves the start depth (the ramp's start: 1 s from there is the stricter reading).
    if (r.step_at_s < 0.0 && depth_mm > c.stock.start_depth_mm + kStepBeginsMm) {
      r.step_at_s = t_s;
      r.depth_before_mm = last_depth_mm;
      r.feed_before_mm_s = ticks_seen >= kFeedLookBack ? feeds[ticks_seen % kFeedLookBack] : 0.0;  // 0.5 s before
    }
    last_depth_mm = depth_mm;
    feeds[ticks_seen++ % kFeedLookBack] = feed_mm_s;
    if (r.step_at_s < 0.0 || t_s < r.step_at_s + c.stock.judged_after_s) return;
    if (!judged) {
      judged = true;
      r.step_error_pct = error_pct(true_force_n);
      r.step_error_measured_pct = error_pct(measured_force_n);
      r.depth_after_mm = depth_mm;
      r.feed_after_mm_s = feed_mm_s;
    }
    r.after_step_max_pct = std::max(r.after_step_max_pct, error_pct(true_force_n));
    r.after_step_measured_max_pct = std::max(r.after_step_measured_max_pct, error_pct(measured_force_n));
  }
};

}  // namespace

TickStudyResult run_tick_study(const TickStudyConfig& c) {
  TickStudyResult r;
  r.config = c;
  r.period_s = kTickPeriodS * static_cast<double>(std::max<std::uint32_t>(1, c.ticks_per_sample));
  r.test_stage = run_tick_test_stage(c, r.error);
  if (!r.error.empty()) return r;
  r.arsc = study_arsc_params(c, r.test_stage);
  const fw::FirmwareConfig firmware = study_firmware_config(c, r.arsc);
  if (const fw::ConfigError e = fw::validate(firmware); !e.ok()) {
    r.error = std::string("firmware config: ") + e.section + ": " + e.field + ": " + e.reason;
    return r;
  }
  {
    const fw::arsc::OuterArscConfig oc = fw::arsc::outer_config(r.arsc);
    const fw::arsc::OuterArsc loop(oc);
    r.initial_gains = loop.signals().gains;
    r.poles = oc.poles;
    r.target_z = fw::arsc::outer_target_poles(fw::arsc::discretise(oc.model, r.period_s), r.period_s, oc.poles);
  }

  const emu::Scenario s = study_scenario(c, c.milling);
  std::unique_ptr<HilRig> rig = ready_study_rig(s, firmware, c, r.error);
  if (!rig) return r;
  fw::TickTask& task = rig->task;
  const emu::CuttingAtTool* tool_cut = rig->machine.cutting_at_tool();  // stock-step only
  const double feed_mm_s = c.outer_loop ? c.program_feed_mm_s : c.constant_feed_mm_s;
  const StudyProgram program = study_cut_program(c, feed_mm_s, true);
  StepJudge step{c, r};
  ProgramFeeder feeder(program.segments);
  const std::uint16_t dac_max = task.config().axis[0].dac.max_code();
  constexpr auto kMaxForceCode = static_cast<std::uint16_t>((1u << hal::regs::kAdcBits) - 1u);
  const double full_scale_n = fw::force_code_to_n(kMaxForceCode, firmware.force_sensor.n_per_volt);
  const auto ticks = static_cast<std::uint64_t>(std::llround(c.duration_s / kTickPeriodS));
  Judge judge{c, r};
  r.override_min_seen = fw::motion::kMaxFeedOverride;
  fw::motion::PlanePoint last{task.last_record().axis[0].position_mm, task.last_record().axis[1].position_mm};
  const double start_x = last[0];
  std::uint32_t clamped_before = 0;
  for (std::uint64_t k = 0; k < ticks; ++k) {
    const double t_s = static_cast<double>(k) * kTickPeriodS;
    if (!feeder.feed(task)) break;
    const fw::TickRecord& rec = task.last_record();
    const double f_n = study_force_n(rec, firmware);
    judge.force(t_s, f_n);
    // held by the ADC at this record's latch
    const double true_force_n = tool_cut != nullptr ? tool_cut->force().force_n() : rig->machine.milling_force_n();
    judge.true_force(t_s, true_force_n);
    const double vx = rig->machine.truth(hal::kPlaneFirst).speed_mm_s, vy = rig->machine.truth(hal::kPlaneSecond).speed_mm_s;
    const double speed = std::hypot(vx, vy);
    if (tool_cut != nullptr) step.observe(t_s, tool_cut->depth_mm(), true_force_n, f_n, speed);
    if (k % 10 == 0) {
      const double depth = tool_cut != nullptr ? tool_cut->depth_mm() : rig->machine.milling_depth_mm();
      const double share = speed > 1e-6 ? std::max(vx, 0.0) / speed : 1.0;
      const double gain = c.outer_loop ? task.feed_source().status().cutting_gain_n_per_mm_s
                                       : r.test_stage.cutting_gain_n_per_mm_s;
      // The process' gain: K delta x the X share ([milling]); where the tool is, the secant F_ss / v.
      const double true_gain =
          tool_cut != nullptr
              ? (speed > 1e-6 ? tool_cut->force().steady_force_n(
                                    depth, tool_cut->force().feed_per_tooth_mm(
                                               speed, rig->machine.spindle_truth().speed_rpm)) /
                                    speed
                              : 0.0)
              : s.milling.force_n_per_mm_mm_s * depth * share;
      r.trace.push_back({t_s, depth, f_n, c.outer_loop ? rec.arsc_force_ref_n : c.force_ref_n, speed,
                         rec.feed_override * feed_mm_s, rec.feed_override, gain, true_gain, rec.axis[0].position_mm,
                         rec.axis[1].position_mm});
    }
    rig->tick();
    const fw::TickRecord& now = task.last_record();
    judge.limits(now);
    judge.dac(t_s, now.axis[0].dac_code, dac_max);
    const fw::motion::PlanePoint here{now.axis[0].position_mm, now.axis[1].position_mm};
    r.travel_mm += std::hypot(here[0] - last[0], here[1] - last[1]);
    last = here;
    r.max_feed_mm_s = std::max(r.max_feed_mm_s, std::hypot(rig->machine.truth(hal::kPlaneFirst).speed_mm_s,
                                                           rig->machine.truth(hal::kPlaneSecond).speed_mm_s));
    if (task.program_running()) {
      r.override_min_seen = std::min(r.override_min_seen, now.feed_override);
      r.override_max_seen = std::max(r.override_max_seen, now.feed_override);
    }
    ++r.ticks;
    if (task.state() == fw::MotionState::faulted || (c.outer_loop && judge.pinned(study_force_n(now, firmware), full_scale_n))) {
      r.diverged = true;
      r.diverged_at_s = t_s;
      if (task.state() == fw::MotionState::faulted) r.fault = fw::to_string(task.fault().reason);
      break;
    }
    if (!task.program_running() && r.program_end_s < 0.0) r.program_end_s = t_s;
    const std::uint32_t clamped = task.feed_source().status().clamped_samples;
    if (clamped != clamped_before) {
      r.last_clamp_s = t_s;
      if (t_s >= c.settle_s) r.clamped_after_settle += clamped - clamped_before;
      clamped_before = clamped;
    }
    if (c.outer_loop) {
      const fw::arsc::OuterGains& g = task.feed_source().loop().signals().gains;
      for (double x : {g.k, g.gamma31, g.gamma32, g.gamma33}) r.max_abs_gain = std::max(r.max_abs_gain, std::fabs(x));
    }
  }
  if (tool_cut != nullptr) r.crashes = tool_cut->crashes().count();
  r.refused_segments = feeder.refused();
  if (r.refused_segments > 0 && r.error.empty())
    r.error = std::string("segment refused: ") + fw::motion::to_string(feeder.last_refusal());
  r.force_error_rms_pct = judge.scored ? std::sqrt(judge.sum_sq / static_cast<double>(judge.scored)) : 0.0;
  r.force_error_true_rms_pct = judge.scored ? std::sqrt(judge.true_sum_sq / static_cast<double>(judge.scored)) : 0.0;
  if (r.diverged) r.force_error_max_pct = std::max(r.force_error_max_pct, 100.0);
  if (r.diverged) r.force_error_true_max_pct = std::max(r.force_error_true_max_pct, 100.0);
  r.travel_x_mm = task.last_record().axis[0].position_mm - start_x;
  const fw::arsc::ArscSourceStatus& st = task.feed_source().status();
  r.samples = st.samples;
  r.clamped_samples = st.clamped_samples;
  r.refused_updates = st.refused_designs;
  return r;
}

}  // namespace tnv::hil
