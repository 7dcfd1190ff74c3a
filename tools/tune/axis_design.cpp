#include "tools/tune/axis_design.hpp"

#include <algorithm>

#include "firmware/control/linear_controller.hpp"
#include "firmware/control/loop_analysis.hpp"

namespace tnv::tune {

namespace {
constexpr double kPeriodS = 1e-3;
constexpr double kSurfaceTimesTau = 1.5;  // G_p tau
constexpr double kQ = 0.9;
constexpr double kSurfaceGainG = 0.3;
constexpr double kEtaReference_mm_s = 0.4;
constexpr double kPhiOverBound = 10.0;
constexpr double kGammaShare = 0.5;

double gb(const fw::AxisModel& m, const fw::SlidingModeParams& p) {
  return p.G_position_1_s * m.B(0) + p.G_speed * m.B(1);
}
}  // namespace

double sliding_loop_spectral_radius(const fw::AxisModel& model, const fw::SlidingModeParams& params) {
  return fw::spectral_radius(fw::closed_loop_poles(model, fw::linearised_sliding_mode(model, params)));
}

AxisDesign design_axis(const AxisIdentification& id) {
  AxisDesign d;
  if (!id.ok) {
    d.error = "identification failed: " + id.error;
    return d;
  }
  d.model = fw::zoh_axis_model(id.tau_s, id.gain, kPeriodS);
  fw::SlidingModeParams& p = d.sliding;
  p.G_position_1_s = kSurfaceTimesTau / id.tau_s;  // S1 eq. (5)
  p.G_speed = 1.0;
  p.q = kQ;  // S1 eq. (4)
  p.g = kSurfaceGainG;  // S1 eq. (7)
  // Theorem 2 needs eta > |GB d~|: the same reaching step in command terms on every table.
  const fw::AxisModel reference = fw::zoh_axis_model(0.005360, 1.0, kPeriodS);
  fw::SlidingModeParams reference_p = p;
  reference_p.G_position_1_s = kSurfaceTimesTau / 0.005360;
  p.eta_mm_s = kEtaReference_mm_s * gb(d.model, p) / gb(reference, reference_p);
  p.phi_mm_s = kPhiOverBound * p.eta_mm_s / (p.q + 1.0);        // Theorem 2: phi > eta / (q + 1)
  p.gamma = kGammaShare * std::min(1.0 - p.g, p.q);              // Theorem 5: 0 < gamma < min(1 - g, q)
  if (const fw::ParamCheck c = fw::validate(p, d.model); !c.ok) {
    d.error = std::string("designed sliding-mode set refused: ") + c.field + ": " + c.reason;
    return d;
  }
  fw::SlidingModeParams dvsc = p;
  dvsc.gamma = 0.0;
  d.pid_report = fw::tune_pid_equal_crossover(d.model, dvsc);
  if (!d.pid_report.ok) {
    d.error = std::string("PID rule failed: ") + d.pid_report.note;
    return d;
  }
  d.pid = fw::pid_params_from(d.pid_report, p.u_max_mm_s);
  d.friction = friction_feedforward_from(id);
  d.shaper = shaper_for_mode(id.mode_found, id.mode_hz, id.mode_zeta);
  d.rdvsc_spectral_radius = sliding_loop_spectral_radius(d.model, p);
  d.dvsc_spectral_radius = sliding_loop_spectral_radius(d.model, dvsc);
  d.pid_spectral_radius = d.pid_report.pid_closed_loop_spectral_radius;
  if (!(d.rdvsc_spectral_radius < 1.0) || !(d.dvsc_spectral_radius < 1.0) || !(d.pid_spectral_radius < 1.0)) {
    d.error = "a designed loop is not stable on the identified model";
    return d;
  }
  d.observer_noise = {kObserverSpeedNoise_mm_s, kObserverDisturbanceNoise_mm_s, 10.0 / 24000.0};
  const fw::ObserverDesign obs = design_observer(d.model, d.observer_noise);
  if (!obs.ok) {
    d.error = "observer design: the Riccati iteration gave no stable observer";
    return d;
  }
  d.observer = obs.params;
  d.observer.friction_mm_s = id.coulomb_mm_s / id.gain;  // the identified Coulomb friction, command terms
  d.observer.friction_deadband_mm_s = kObserverFrictionDeadband_mm_s;
  d.observer.enabled = true;
  d.ok = true;
  return d;
}

fw::ObserverDesign design_observer(const fw::AxisModel& model, const fw::ObserverNoise& noise) {
  return fw::steady_state_kalman_gain(model, noise);
}

fw::FirmwareConfig apply_designs(const fw::FirmwareConfig& base, const AxisDesign& x, const AxisDesign& y) {
  fw::FirmwareConfig config = base;
  const AxisDesign* designs[] = {&x, &y};
  for (std::size_t i = 0; i < 2; ++i) {
    fw::AxisConfig& a = config.axis[i];
    a.model = designs[i]->model;
    a.sliding = designs[i]->sliding;
    a.pid = designs[i]->pid;
    a.friction = designs[i]->friction;
    a.observer = designs[i]->observer;
  }
  return config;
}

}  // namespace tnv::tune
