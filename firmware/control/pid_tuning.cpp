#include "firmware/control/pid_tuning.hpp"

#include <cmath>
#include <complex>
#include <numbers>

#include "firmware/control/linear_controller.hpp"
#include "firmware/control/loop_analysis.hpp"

namespace tnv::fw {

namespace {
constexpr const char* kRule =
    "equal loop crossover with DVSC+DDC on the nominal model: DVSC+DDC linearised in the boundary layer, "
    "loop broken at the plant input; PID on position (Ti = 4 Td) with the same gain-crossover frequency and "
    "the same phase margin, capped at max_phase_margin_deg (default 60 deg)";

constexpr int kTdGridPoints = 600;
constexpr int kPidBisections = 80;

double hz(double rad_s) noexcept { return rad_s / (2.0 * std::numbers::pi); }

struct PidShape {
  const AxisModel& model;
  const PidTuningOptions& options;
  double wc_rad_s;

  double tf_s(double td_s) const noexcept {
    return options.derivative_filter_n > 0.0 ? td_s / options.derivative_filter_n : 0.0;
  }
  // L(w_c) of the PID with kp = 1 and the given Td.
  std::complex<double> unit_loop(double td_s) const noexcept {
    const double ti_s = options.ti_over_td * td_s;
    return loop_gain(model, linear_pid(model, 1.0, 1.0 / ti_s, td_s, tf_s(td_s)), wc_rad_s);
  }
  double phase_margin_deg(double td_s) const noexcept {
    double pm = 180.0 + std::arg(unit_loop(td_s)) * 180.0 / std::numbers::pi;
    if (pm > 180.0) pm -= 360.0;
    return pm;
  }
};

bool valid_options(const PidTuningOptions& o) noexcept {
  return std::isfinite(o.ti_over_td) && o.ti_over_td > 0.0 && std::isfinite(o.derivative_filter_n) &&
         o.derivative_filter_n >= 0.0 && std::isfinite(o.max_phase_margin_deg) && o.max_phase_margin_deg > 0.0 &&
         o.max_phase_margin_deg < 90.0;
}
}  // namespace

PidTuningReport tune_pid_equal_crossover(const AxisModel& nominal, const SlidingModeParams& dvsc_params,
                                         const PidTuningOptions& options) noexcept {
  PidTuningReport rep;
  rep.rule = kRule;
  const ParamCheck check = validate(dvsc_params, nominal);
  if (!check.ok) {
    rep.note = "sliding-mode parameters or model invalid (see validate())";
    return rep;
  }
  if (!valid_options(options)) {
    rep.note = "invalid options: need ti_over_td > 0, filter N >= 0, 0 < PM cap < 90 deg";
    return rep;
  }

  // 1-2. DVSC+DDC loop
  const LinearController smc = linearised_sliding_mode(nominal, dvsc_params);
  const LoopMargins smc_m = loop_margins(nominal, smc);
  rep.dvsc_crossover_rad_s = smc_m.crossover_rad_s;
  rep.dvsc_crossover_hz = hz(smc_m.crossover_rad_s);
  rep.dvsc_phase_margin_deg = smc_m.phase_margin_deg;
  rep.dvsc_gain_margin_db = smc_m.gain_margin_db;
  rep.dvsc_closed_loop_spectral_radius = spectral_radius(closed_loop_poles(nominal, smc));
  if (!smc_m.crossover_found || !(smc_m.phase_margin_deg > 0.0)) {
    rep.note = "DVSC+DDC loop has no gain crossover with positive phase margin";
    return rep;
  }

  // 3. target phase margin
  rep.phase_margin_capped = smc_m.phase_margin_deg > options.max_phase_margin_deg;
  rep.target_phase_margin_deg = rep.phase_margin_capped ? options.max_phase_margin_deg : smc_m.phase_margin_deg;

  // 4. Td from the phase condition (smallest Td on the rising branch), kp from |L| = 1
  const PidShape shape{nominal, options, smc_m.crossover_rad_s};
  const double target = rep.target_phase_margin_deg;
  const double log_lo = std::log(0.01 * nominal.period_s);
  const double log_hi = std::log(1.0);
  auto td_at = [&](int i) { return std::exp(log_lo + (log_hi - log_lo) * i / kTdGridPoints); };
  double td_s = 0.0;
  double best_td_s = td_at(0);
  double best_pm = shape.phase_margin_deg(best_td_s);
  double pm0 = best_pm;
  for (int i = 1; i <= kTdGridPoints && td_s == 0.0; ++i) {
    const double td1 = td_at(i);
    const double pm1 = shape.phase_margin_deg(td1);
    if (pm1 > best_pm) {
      best_pm = pm1;
      best_td_s = td1;
    }
    if (pm0 < target && pm1 >= target && pm1 - pm0 < 90.0) {
      double a = td_at(i - 1), b = td1;
      for (int it = 0; it < kPidBisections; ++it) {
        const double mid = std::sqrt(a * b);
        (shape.phase_margin_deg(mid) < target ? a : b) = mid;
      }
      td_s = std::sqrt(a * b);
    }
    pm0 = pm1;
  }
  rep.phase_margin_reached = td_s > 0.0;
  if (!rep.phase_margin_reached) td_s = best_td_s;

  rep.td_s = td_s;
  rep.ti_s = options.ti_over_td * td_s;
  rep.derivative_filter_tf_s = shape.tf_s(td_s);
  rep.kp = 1.0 / std::abs(shape.unit_loop(td_s));
  rep.ki = rep.kp / rep.ti_s;
  rep.kd = rep.kp * td_s;

  // 5. verify the PID loop
  const LinearController pid = linear_pid(nominal, rep.kp, rep.ki, rep.kd, rep.derivative_filter_tf_s);
  const LoopMargins pid_m = loop_margins(nominal, pid);
  rep.pid_crossover_rad_s = pid_m.crossover_rad_s;
  rep.pid_crossover_hz = hz(pid_m.crossover_rad_s);
  rep.pid_phase_margin_deg = pid_m.phase_margin_deg;
  rep.pid_gain_margin_db = pid_m.gain_margin_db;
  rep.pid_gain_reduction_margin_db = pid_m.gain_reduction_margin_db;
  rep.pid_closed_loop_spectral_radius = spectral_radius(closed_loop_poles(nominal, pid));
  rep.pid_closed_loop_stable = rep.pid_closed_loop_spectral_radius < 1.0;

  const bool gains_ok = std::isfinite(rep.kp) && std::isfinite(rep.ki) && std::isfinite(rep.kd) && rep.kp > 0.0 &&
                        rep.ki > 0.0 && rep.kd > 0.0;
  rep.ok = gains_ok && rep.phase_margin_reached && rep.pid_closed_loop_stable && pid_m.crossover_found;
  if (!gains_ok)
    rep.note = "gains not finite and positive";
  else if (!rep.pid_closed_loop_stable)
    rep.note = "PID closed loop on the nominal model is NOT stable";
  else if (!rep.phase_margin_reached)
    rep.note = "target phase margin not reachable with this PID shape; Td maximises the phase margin at w_c";
  else if (rep.phase_margin_capped)
    rep.note = "DVSC+DDC phase margin above the cap: PID phase margin set to the cap";
  else
    rep.note = "PID phase margin equals the DVSC+DDC phase margin";
  return rep;
}

PidParams pid_params_from(const PidTuningReport& report, double u_max_mm_s) noexcept {
  PidParams p;
  p.kp = report.kp;
  p.ki = report.ki;
  p.kd = report.kd;
  p.derivative_filter_tf_s = report.derivative_filter_tf_s;
  p.u_max_mm_s = u_max_mm_s;
  p.feedforward = true;
  return p;
}

PidTuningReport paper_pid_tuning(hal::Axis axis) noexcept {
  return tune_pid_equal_crossover(paper_axis_model(axis), paper_dvsc_params(axis));
}

PidParams paper_pid_params(hal::Axis axis, double u_max_mm_s) noexcept {
  // paper_pid_tuning(axis): kp, ki, kd, derivative filter (printed to round-trip).
  PidTuningReport r;
  // One case per axis and no default: a new axis of TNV_AXES fails the
  // build (-Wswitch) until its gains are printed here.
  switch (axis) {
    case hal::Axis::x:
      r.kp = 560.8273280856934;
      r.ki = 33695.64484971097;
      r.kd = 2.333590092507429;
      break;
    case hal::Axis::y:
      r.kp = 662.7543577500362;
      r.ki = 40766.365494139354;
      r.kd = 2.693662614955271;
      break;
    case hal::Axis::z:
      r.kp = 1342.1240215543035;
      r.ki = 98933.918004762774;
      r.kd = 4.5517678000642317;
      break;
  }
  r.derivative_filter_tf_s = 0.0;
  return pid_params_from(r, u_max_mm_s);
}

}  // namespace tnv::fw
