#include "firmware/control/axis_model.hpp"

#include <cmath>
#include <limits>

namespace tnv::fw {

AxisModel paper_axis_model(hal::Axis axis) noexcept {
  AxisModel m;
  // S1 eq. (31). One case per axis and no default: a new axis of TNV_AXES
  // fails the build (-Wswitch) until it has its model here.
  switch (axis) {
    case hal::Axis::x:
      m.A << 1.0, 0.0009, 0.0, 0.8298;
      m.B << 0.0001, 0.1702;
      break;
    case hal::Axis::y:
      m.A << 1.0, 0.0009, 0.0, 0.8690;
      m.B << 0.0001, 0.1310;
      break;
    case hal::Axis::z:
      // No paper has Z: the same 4-decimal zero-order hold of the reference
      // plant that eq. (31) is of X's and Y's (zoh_axis_model with tau_Z =
      // 9.0 ms, K = 1: A12 0.000946, A22 0.894839, B1 0.0000536, B2 0.105161).
      m.A << 1.0, 0.0009, 0.0, 0.8948;
      m.B << 0.0001, 0.1052;
      break;
  }
  m.period_s = kControlPeriod_s;
  return m;
}

AxisModel zoh_axis_model(double tau_s, double gain, double period_s) noexcept {
  AxisModel m;
  m.period_s = period_s;
  if (!(tau_s > 0.0) || !(period_s > 0.0) || !std::isfinite(tau_s) || !std::isfinite(period_s)) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    m.A.setConstant(nan);
    m.B.setConstant(nan);
    return m;
  }
  // expm1 keeps 1 - e^{-T/tau} accurate when T << tau.
  const double one_minus_a22 = -std::expm1(-period_s / tau_s);
  const double a12 = tau_s * one_minus_a22;
  m.A << 1.0, a12, 0.0, 1.0 - one_minus_a22;
  m.B << gain * (period_s - a12), gain * one_minus_a22;
  return m;
}

bool is_finite(const AxisModel& model) noexcept {
  return model.A.allFinite() && model.B.allFinite() && std::isfinite(model.period_s) && model.period_s > 0.0;
}

}  // namespace tnv::fw
