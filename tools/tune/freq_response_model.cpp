#include "tools/tune/freq_response_model.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <numbers>

#include "firmware/control/loop_analysis.hpp"

namespace tnv::tune {

namespace {

using cplx = std::complex<double>;

constexpr double kGridLowHz = 0.05;
constexpr int kGridPoints = 4000;

cplx z_at(const fw::AxisModel& m, double freq_hz) noexcept {
  return std::polar(1.0, 2.0 * std::numbers::pi * freq_hz * m.period_s);
}

Eigen::RowVector2cd controller_row(const fw::LinearController& c, cplx z) {
  return c.Cc.cast<cplx>() * (z * Eigen::Matrix3cd::Identity() - c.Ac.cast<cplx>()).inverse() * c.Bc.cast<cplx>() +
         c.Dc.cast<cplx>();
}

cplx open_loop(const LoopModel& m, double freq_hz) {
  if (!m.measured_speed) return fw::loop_gain(m.plant, m.controller, 2.0 * std::numbers::pi * freq_hz);
  const cplx z = z_at(m.plant, freq_hz);
  const cplx p = plant_response(m.plant, freq_hz);
  // The M-method speed of an encoder position: (1 - z^-1) / T times it.
  const Eigen::Vector2cd measured(p, p * (1.0 - 1.0 / z) / m.plant.period_s);
  return -(controller_row(m.controller, z) * measured).value();
}

}  // namespace

fw::LinearController active_linear_controller(const fw::AxisConfig& a) {
  switch (a.controller) {
    case fw::ControllerKind::pid:
      return fw::linear_pid(a.model, a.pid.kp, a.pid.ki, a.pid.kd, a.pid.derivative_filter_tf_s);
    case fw::ControllerKind::dvsc: {
      fw::SlidingModeParams p = a.sliding;
      p.gamma = 0.0;
      return fw::linearised_sliding_mode(a.model, p);
    }
    case fw::ControllerKind::rdvsc: break;
  }
  return fw::linearised_sliding_mode(a.model, a.sliding);
}

cplx plant_response(const fw::AxisModel& plant, double freq_hz) noexcept {
  const cplx z = z_at(plant, freq_hz);
  const Eigen::Vector2cd x = (z * Eigen::Matrix2cd::Identity() - plant.A.cast<cplx>()).inverse() * plant.B.cast<cplx>();
  return x(0);
}

cplx model_response(const LoopModel& m, LoopKind kind, double freq_hz) noexcept {
  switch (kind) {
    case LoopKind::plant: return plant_response(m.plant, freq_hz);
    case LoopKind::open: return open_loop(m, freq_hz);
    case LoopKind::closed: {
      const cplx l = open_loop(m, freq_hz);
      return l / (1.0 + l);
    }
  }
  return {};
}

std::vector<ResponsePoint> model_points(const LoopModel& m, LoopKind kind, const std::vector<double>& freqs_hz) {
  std::vector<ResponsePoint> out;
  out.reserve(freqs_hz.size());
  for (const double f : freqs_hz) out.push_back({f, model_response(m, kind, f), 1.0});
  return out;
}

ModelMargins model_margins(const LoopModel& m) {
  const double nyquist_hz = 0.5 / m.plant.period_s;
  std::vector<double> grid;
  grid.reserve(kGridPoints + 1);
  for (int i = 0; i <= kGridPoints; ++i)
    grid.push_back(kGridLowHz * std::pow(nyquist_hz * (1.0 - 1e-6) / kGridLowHz, static_cast<double>(i) / kGridPoints));
  ModelMargins out;
  out.margins = margins_from_points(model_points(m, LoopKind::open, grid));
  out.bandwidth_hz = bandwidth_hz(model_points(m, LoopKind::closed, grid));
  return out;
}

}  // namespace tnv::tune
