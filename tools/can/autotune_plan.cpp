#include "tools/can/autotune_plan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "firmware/control/pid_params.hpp"
#include "firmware/control/sliding_mode_params.hpp"
#include "tools/can/tune_json.hpp"

namespace tnv::can_host {

namespace {

const can::ParamDef& axis_param(hal::Axis axis, const char* suffix) {
  std::string name = std::string(hal::axis_label(axis)) + ".";
  name += suffix;
  const can::ParamDef* p = can::find_param(name.c_str());
  if (p == nullptr) throw std::logic_error("no parameter " + name);
  return *p;
}

double value_of(const std::vector<ParamChange>& changes, const std::string& suffix, bool old) {
  for (const ParamChange& c : changes) {
    const std::string name = c.param->name;
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
        name[name.size() - suffix.size() - 1] == '.')
      return old ? c.old_value : c.new_value;
  }
  throw std::logic_error("no change for " + suffix);
}

// The gains a set of changes describes (old or new values).
fw::SlidingModeParams sliding_of(const std::vector<ParamChange>& c, bool old) {
  fw::SlidingModeParams p;
  p.G_position_1_s = value_of(c, "sliding.G_position_1_s", old);
  p.G_speed = value_of(c, "sliding.G_speed", old);
  p.eta_mm_s = value_of(c, "sliding.eta_mm_s", old);
  p.phi_mm_s = value_of(c, "sliding.phi_mm_s", old);
  p.q = value_of(c, "sliding.q", old);
  p.g = value_of(c, "sliding.g", old);
  p.gamma = value_of(c, "sliding.gamma", old);
  return p;
}

fw::PidParams pid_of(const std::vector<ParamChange>& c, bool old) {
  fw::PidParams p;
  p.kp = value_of(c, "pid.kp", old);
  p.ki = value_of(c, "pid.ki", old);
  p.kd = value_of(c, "pid.kd", old);
  p.derivative_filter_tf_s = value_of(c, "pid.derivative_filter_tf_s", old);
  return p;
}

}  // namespace

std::vector<ParamChange> design_changes(const tune::AxisDesign& d, hal::Axis axis) {
  if (!d.ok) throw std::logic_error("design_changes: the design failed: " + d.error);
  const fw::SlidingModeParams& s = d.sliding;
  const fw::FrictionFeedForward& f = d.friction;
  const std::pair<const char*, double> values[] = {
      {"model.a11", d.model.A(0, 0)},
      {"model.a12", d.model.A(0, 1)},
      {"model.a21", d.model.A(1, 0)},
      {"model.a22", d.model.A(1, 1)},
      {"model.b1", d.model.B(0)},
      {"model.b2", d.model.B(1)},
      {"sliding.G_position_1_s", s.G_position_1_s},
      {"sliding.G_speed", s.G_speed},
      {"sliding.eta_mm_s", s.eta_mm_s},
      {"sliding.phi_mm_s", s.phi_mm_s},
      {"sliding.q", s.q},
      {"sliding.g", s.g},
      {"sliding.gamma", s.gamma},
      {"pid.kp", d.pid.kp},
      {"pid.ki", d.pid.ki},
      {"pid.kd", d.pid.kd},
      {"pid.derivative_filter_tf_s", d.pid.derivative_filter_tf_s},
      {"friction.enable", f.enabled ? 1.0 : 0.0},
      {"friction.coulomb_mm_s", f.coulomb_mm_s},
      {"friction.stiction_mm_s", f.stiction_mm_s},
      {"friction.stribeck_mm_s", f.stribeck_mm_s},
      {"friction.gain", f.gain},
      {"friction.fraction", f.fraction},
      {"observer.enable", d.observer.enabled ? 1.0 : 0.0},
      {"observer.use_position", d.observer.use_position ? 1.0 : 0.0},
      {"observer.gain_position", d.observer.gain_position},
      {"observer.gain_speed_1_s", d.observer.gain_speed_1_s},
      {"observer.gain_disturbance_1_s", d.observer.gain_disturbance_1_s},
  };
  std::vector<ParamChange> out;
  for (const auto& [suffix, value] : values) out.push_back({&axis_param(axis, suffix), 0.0, value});
  return out;
}

std::vector<ParamChange> shaper_changes(const tune::AxisDesign& design, hal::Axis axis) {
  if (!design.shaper.enabled) return {};
  // The node's own encoding of the spec, through the parameters' accessors.
  can::NodeSettings wanted;
  wanted.shaper[hal::index(axis)].spec = design.shaper.spec;
  wanted.shaper[hal::index(axis)].enabled = true;
  std::vector<ParamChange> out;
  for (const char* suffix : {"shaper.type", "shaper.freq_hz", "shaper.zeta", "shaper.enable"}) {
    const can::ParamDef& p = axis_param(axis, suffix);
    out.push_back({&p, 0.0, p.get(wanted)});
  }
  return out;
}

namespace {

fw::SpeedObserverParams observer_of(const std::vector<ParamChange>& c, bool old) {
  fw::SpeedObserverParams p;
  p.enabled = value_of(c, "observer.enable", old) != 0.0;
  p.use_position = value_of(c, "observer.use_position", old) != 0.0;
  p.gain_position = value_of(c, "observer.gain_position", old);
  p.gain_speed_1_s = value_of(c, "observer.gain_speed_1_s", old);
  p.gain_disturbance_1_s = value_of(c, "observer.gain_disturbance_1_s", old);
  return p;
}

}  // namespace

AxisPlan plan_autotune(NodeClient& client, const tune::AxisIdentification& id, const tune::AxisDesign& design) {
  AxisPlan plan;
  plan.axis = id.axis;
  plan.id = id;
  plan.design = design;
  plan.changes = design_changes(design, id.axis);
  for (ParamChange& c : shaper_changes(design, id.axis)) plan.changes.push_back(c);
  for (ParamChange& c : plan.changes) c.old_value = client.get(*c.param);
  // Both on the identified model: what the old and the new gains would do on the table as measured.
  const fw::AxisModel& m = id.model;
  fw::SlidingModeParams old_s = sliding_of(plan.changes, true);
  fw::SlidingModeParams new_s = sliding_of(plan.changes, false);
  plan.prediction.rdvsc_old = tune::predict_sliding(m, old_s);
  plan.prediction.rdvsc_new = tune::predict_sliding(m, new_s);
  old_s.gamma = 0.0;
  new_s.gamma = 0.0;
  plan.prediction.dvsc_old = tune::predict_sliding(m, old_s);
  plan.prediction.dvsc_new = tune::predict_sliding(m, new_s);
  plan.prediction.pid_old = tune::predict_pid(m, pid_of(plan.changes, true));
  plan.prediction.pid_new = tune::predict_pid(m, pid_of(plan.changes, false));
  plan.prediction.observer_old = tune::predict_observer(m, observer_of(plan.changes, true));
  plan.prediction.observer_new = tune::predict_observer(m, observer_of(plan.changes, false));
  return plan;
}

std::vector<double> apply_changes(NodeClient& client, const std::vector<ParamChange>& changes) {
  try {
    for (const ParamChange& c : changes) client.stage(*c.param, c.new_value);
    client.commit();
  } catch (const RequestError& e) {
    if (e.kind() == RequestError::Kind::refused) {
      try {
        client.discard();  // a refused commit keeps the staged set: drop it
      } catch (const std::exception&) {
        // The refusal is what matters.
      }
    }
    throw;
  }
  std::vector<double> read_back;
  for (const ParamChange& c : changes) read_back.push_back(client.get(*c.param));
  return read_back;
}

std::string poles_text(const std::vector<std::complex<double>>& poles) {
  std::vector<std::complex<double>> sorted(poles.begin(), poles.end());
  std::sort(sorted.begin(), sorted.end(), [](auto a, auto b) { return std::abs(a) > std::abs(b); });
  std::string out;
  char buf[64];
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const std::complex<double> z = sorted[i];
    if (z.imag() < -1e-9) continue;  // its conjugate is printed as ±
    const double re = std::fabs(z.real()) < 5e-5 ? 0.0 : z.real();  // no "-0.0000"
    if (std::fabs(z.imag()) <= 1e-9)
      std::snprintf(buf, sizeof buf, "%.4f", re);
    else
      std::snprintf(buf, sizeof buf, "%.4f±%.4fi", re, z.imag());
    if (!out.empty()) out += ", ";
    out += buf;
  }
  return out;
}

nlohmann::json prediction_json(const LoopPrediction& p) {
  if (!p.ok) return {{"ok", false}, {"why", p.why}};
  nlohmann::json poles = nlohmann::json::array();
  for (const std::complex<double>& z : p.poles) poles.push_back({z.real(), z.imag()});
  return {{"ok", true}, {"spectral_radius", p.spectral_radius}, {"poles", poles}};
}

nlohmann::json plan_json(const AxisPlan& plan) {
  nlohmann::json changes = nlohmann::json::array();
  for (const ParamChange& c : plan.changes)
    changes.push_back({{"name", c.param->name}, {"old", c.old_value}, {"new", c.new_value}});
  const AxisPrediction& p = plan.prediction;
  return {{"axis", hal::axis_label(plan.axis)},
          {"identified", identification_json(plan.id)},
          {"design", design_json(plan.design)},
          {"changes", changes},
          {"predicted",
           {{"rdvsc", {{"old", prediction_json(p.rdvsc_old)}, {"new", prediction_json(p.rdvsc_new)}}},
            {"dvsc", {{"old", prediction_json(p.dvsc_old)}, {"new", prediction_json(p.dvsc_new)}}},
            {"pid", {{"old", prediction_json(p.pid_old)}, {"new", prediction_json(p.pid_new)}}},
            {"observer", {{"old", prediction_json(p.observer_old)}, {"new", prediction_json(p.observer_new)}}}}}};
}

}  // namespace tnv::can_host
