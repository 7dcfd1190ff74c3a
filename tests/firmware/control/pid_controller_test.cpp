#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <random>

#include "firmware/control/linear_controller.hpp"
#include "firmware/control/pid_controller.hpp"
#include "firmware/control/pid_tuning.hpp"
#include "tests/firmware/control/nominal_plant.hpp"
#include "tests/firmware/test_units.hpp"

namespace tnv::fw {
namespace {

using test::NominalPlant;
using test_units::kPeriodS;

PidParams tuned(hal::Axis axis) { return pid_params_from(paper_pid_tuning(axis)); }

TEST(PidController, FeedForwardAloneTracksAFeasibleRampExactly) {
  const AxisModel model = paper_axis_model(hal::Axis::x);
  PidController ctl(model, tuned(hal::Axis::x));
  NominalPlant plant{model, Eigen::Vector2d(0.0, 2.0)};  // already moving at 2 mm/s
  for (int k = 0; k < 1000; ++k) {
    const AxisReference ref = test::reference_at(k, kPeriodS, [](double t) { return 2.0 * t; }, [](double) { return 2.0; });
    ASSERT_NEAR(ref.position_mm - plant.x(0), 0.0, 1e-12) << "tick " << k;
    const double u = ctl.update(plant.state(), ref);
    ASSERT_NEAR(u, 2.0, 1e-6) << "tick " << k << ": u_ff for a 2 mm/s ramp must be 2 mm/s";
    plant.step(u, 0.0);
  }
}

// 2 mm/s feed reached from rest with a 0.1 s raised-cosine speed ramp (as the circle's feed ramps).
constexpr double kRampUp_s = 0.1;
double ramp_speed_mm_s(double t) {
  return t <= 0.0 ? 0.0 : (t < kRampUp_s ? 1.0 - std::cos(std::numbers::pi * t / kRampUp_s) : 2.0);
}
double ramp_position_mm(double t) {
  return t <= 0.0 ? 0.0 : (t < kRampUp_s ? t - kRampUp_s / std::numbers::pi * std::sin(std::numbers::pi * t / kRampUp_s) : 2.0 * t - kRampUp_s);
}

TEST(PidController, TunedPidWithFeedForwardTracksARampFromRestWithNearZeroSteadyError) {
  for (hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    const AxisModel model = paper_axis_model(axis);
    double peak_um[2] = {0.0, 0.0};
    for (int with_ff = 0; with_ff < 2; ++with_ff) {
      PidParams p = tuned(axis);
      p.feedforward = with_ff == 1;
      PidController ctl(model, p);
      NominalPlant plant{model, Eigen::Vector2d::Zero()};
      double late_um = 0.0;
      for (int k = 0; k < 3000; ++k) {
        const AxisReference ref = test::reference_at(k, kPeriodS, ramp_position_mm, ramp_speed_mm_s);
        const double e_um = (ref.position_mm - plant.x(0)) * 1e3;
        peak_um[with_ff] = std::max(peak_um[with_ff], std::fabs(e_um));
        if (k >= 1000) late_um = std::max(late_um, std::fabs(e_um));
        plant.step(ctl.update(plant.state(), ref), 0.0);
      }
      EXPECT_LT(late_um, 1e-6) << hal::axis_name(axis) << (with_ff ? " with" : " without")
                               << " feed-forward: steady ramp error " << late_um << " um";
    }
    EXPECT_LT(peak_um[1], 0.1 * peak_um[0]) << hal::axis_name(axis) << ": feed-forward " << peak_um[1]
                                            << " um vs none " << peak_um[0] << " um during the speed ramp-up";
  }
}

// Overshoot after a position step of step_mm from rest; with_anti_windup =
// false runs a textbook PID that integrates through the clamp, for contrast.
double step_overshoot_mm(hal::Axis axis, double step_mm, bool with_anti_windup, int* saturated_ticks = nullptr) {
  const AxisModel model = paper_axis_model(axis);
  const PidParams p = tuned(axis);
  PidController ctl(model, p);
  NominalPlant plant{model, Eigen::Vector2d::Zero()};
  double integral = 0.0, e_prev = step_mm, overshoot_mm = 0.0;
  for (int k = 0; k < 3000; ++k) {
    double u = 0.0;
    if (with_anti_windup) {
      u = ctl.update(plant.state(), test::resting_reference(step_mm));
      EXPECT_LE(std::fabs(u), p.u_max_mm_s) << "tick " << k << ": |u| = " << std::fabs(u) << " mm/s";
      if (saturated_ticks && ctl.signals().saturated) ++*saturated_ticks;
    } else {
      const double e = step_mm - plant.x(0);
      integral += p.ki * kPeriodS * e;
      u = std::clamp(p.kp * e + integral + p.kd * (e - e_prev) / kPeriodS, -p.u_max_mm_s, p.u_max_mm_s);
      e_prev = e;
    }
    overshoot_mm = std::max(overshoot_mm, plant.x(0) - step_mm);
    plant.step(u, 0.0);
  }
  EXPECT_NEAR(plant.x(0), step_mm, 1e-6) << "final error " << (plant.x(0) - step_mm) * 1e3 << " um";
  return overshoot_mm;
}

TEST(PidController, ClampHoldsAndAntiWindupRecoversWithoutBigOvershoot) {
  for (hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    const char name = hal::axis_name(axis);
    // Linear (unsaturated) step overshoot of this PID: about 21-23 %, the price of PM = 60 deg in a type-2 loop.
    const double linear = step_overshoot_mm(axis, 0.01, true) / 0.01;
    int saturated_ticks = 0;
    const double aw5 = step_overshoot_mm(axis, 5.0, true, &saturated_ticks);
    const double aw20 = step_overshoot_mm(axis, 20.0, true);
    const double naive5 = step_overshoot_mm(axis, 5.0, false);
    EXPECT_GT(saturated_ticks, 20) << name << ": the 5 mm step must saturate the command";
    EXPECT_LT(aw5 / 5.0, 0.05) << name << ": overshoot " << aw5 * 1e3 << " um after a saturated 5 mm step";
    EXPECT_LT(aw5 / 5.0, linear) << name << ": saturated step overshoots more (relative) than a linear one";
    EXPECT_LT(aw5, 0.1 * naive5) << name << ": anti-windup " << aw5 * 1e3 << " um vs integrating through the clamp "
                                 << naive5 * 1e3 << " um";
    EXPECT_LT(aw20, 1.1 * aw5) << name << ": overshoot grows with the step (" << aw5 * 1e3 << " um at 5 mm, "
                               << aw20 * 1e3 << " um at 20 mm): wind-up";
  }
}

TEST(PidController, FirstTickHasNoDerivativeKick) {
  const PidParams p = tuned(hal::Axis::x);
  PidController ctl(paper_axis_model(hal::Axis::x), p);
  const double e = 0.01;
  const double u = ctl.update({1.0 - e, 0.0}, test::resting_reference(1.0));
  EXPECT_NEAR(u, p.kp * e + p.ki * kPeriodS * e, 1e-12);
}

TEST(PidController, RejectedParameterSetLeavesTheOldOneInForce) {
  const AxisModel model = paper_axis_model(hal::Axis::y);
  PidController ctl(model, tuned(hal::Axis::y));
  const PidParams before = ctl.params();
  struct Bad {
    double PidParams::*ptr;
    double value;
    const char* field;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Bad bads[] = {{&PidParams::kp, nan, "kp"},
                      {&PidParams::kp, 0.0, "kp"},
                      {&PidParams::ki, -1.0, "ki"},
                      {&PidParams::kd, inf, "kd"},
                      {&PidParams::derivative_filter_tf_s, -1e-3, "derivative_filter_tf_s"},
                      {&PidParams::u_max_mm_s, 0.0, "u_max_mm_s"}};
  for (const Bad& b : bads) {
    PidParams p = before;
    p.ki = 1.0;  // a valid change riding along: must not be applied either
    p.*b.ptr = b.value;
    const ParamCheck c = ctl.set_params(p);
    EXPECT_FALSE(c.ok) << b.field;
    EXPECT_STREQ(c.field, b.field);
    EXPECT_EQ(ctl.params().ki, before.ki) << b.field << ": half-applied";
    EXPECT_EQ(ctl.params().kp, before.kp) << b.field << ": half-applied";
  }
  AxisModel no_b2 = model;
  no_b2.B(1) = 0.0;
  PidController ff_impossible(no_b2, tuned(hal::Axis::y));
  EXPECT_FALSE(ff_impossible.configured());
  EXPECT_STREQ(ff_impossible.config_status().field, "feedforward");
  EXPECT_EQ(ff_impossible.update({0.1, 0.0}, test::resting_reference(0.0)), 0.0);
}

TEST(PidController, GainChangeIsBumpless) {
  const AxisModel model = paper_axis_model(hal::Axis::x);
  PidController ctl(model, tuned(hal::Axis::x));
  NominalPlant plant{model, Eigen::Vector2d::Zero()};
  double u_prev = 0.0;
  for (int k = 0; k < 400; ++k) {
    const AxisReference ref = test::reference_at(k, kPeriodS, [](double t) { return 0.5 * t * t; }, [](double t) { return t; });
    if (k == 200) {
      PidParams p = ctl.params();
      p.kp *= 0.5;
      p.kd *= 2.0;
      ASSERT_TRUE(ctl.set_params(p).ok);
    }
    const double u = ctl.update(plant.state(), ref);
    if (k == 200) {
      EXPECT_NEAR(u, u_prev, 0.05) << "command jumped by " << u - u_prev << " mm/s at the gain change";
    }
    u_prev = u;
    plant.step(u, 0.3);
  }
}

// The linear model used by the tuner is this controller (no clamp, no feed-forward).
TEST(PidController, LinearModelReproducesTheController) {
  const AxisModel model = paper_axis_model(hal::Axis::x);
  for (double tf : {0.0, 0.4e-3}) {
    PidParams p = tuned(hal::Axis::x);
    p.feedforward = false;
    p.derivative_filter_tf_s = tf;
    p.u_max_mm_s = 1e9;
    PidController ctl(model, p);
    const LinearController lin = linear_pid(model, p.kp, p.ki, p.kd, tf);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> pos(-1e-3, 1e-3);
    Eigen::Vector3d xi = Eigen::Vector3d::Zero();
    for (int k = 0; k < 300; ++k) {
      const Eigen::Vector2d x(pos(rng), 0.0);
      if (k == 0) xi(2) = -x(0);  // e_{-1} := e_0: no derivative kick
      const double u = ctl.update({x(0), x(1)}, test::resting_reference(0.0));
      const double u_lin = (lin.Cc * xi + lin.Dc * x).value();
      xi = lin.Ac * xi + lin.Bc * x;
      ASSERT_NEAR(u, u_lin, 1e-9) << "tf " << tf << " s, tick " << k;
    }
  }
}

}  // namespace
}  // namespace tnv::fw
