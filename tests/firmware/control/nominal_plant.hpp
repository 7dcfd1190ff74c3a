#pragma once
// Test helper: the nominal discrete plant of S1 eq. (3) with matched
// disturbance, x_{k+1} = A x_k + B u_k + B d_k, and reference builders.
#include <Eigen/Core>
#include <cmath>

#include "firmware/control/axis_controller.hpp"
#include "firmware/control/axis_model.hpp"

namespace tnv::fw::test {

struct NominalPlant {
  AxisModel model;
  Eigen::Vector2d x = Eigen::Vector2d::Zero();  // [position mm, velocity mm/s]

  AxisState state() const { return {x(0), x(1)}; }
  void step(double u_mm_s, double d_mm_s) { x = model.A * x + model.B * (u_mm_s + d_mm_s); }
};

// Reference sample k and k+1 of a position/speed trajectory given as functions of time.
template <class Position, class Speed>
AxisReference reference_at(long k, double period_s, Position position_mm, Speed speed_mm_s) {
  const double t0 = static_cast<double>(k) * period_s;
  const double t1 = t0 + period_s;
  return {position_mm(t0), speed_mm_s(t0), position_mm(t1), speed_mm_s(t1)};
}

inline AxisReference resting_reference(double position_mm) { return {position_mm, 0.0, position_mm, 0.0}; }

}  // namespace tnv::fw::test
