// RdvscController behaviour beyond the closed-loop identities: reset and
// first tick, clamp and anti-windup of the DDC, atomic set_params, kinds.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "firmware/control/linear_controller.hpp"
#include "firmware/control/rdvsc_controller.hpp"
#include "tests/firmware/control/nominal_plant.hpp"

namespace tnv::fw {
namespace {

using test::NominalPlant;

TEST(RdvscController, FirstCommandOnARestingReferenceIsZero) {
  for (ControllerKind kind : {ControllerKind::dvsc, ControllerKind::rdvsc}) {
    RdvscController ctl(kind, hal::Axis::x);
    const double u = ctl.update({12.5, 0.0}, test::resting_reference(12.5));
    EXPECT_EQ(u, 0.0) << to_string(kind) << ": servo-on bump " << u << " mm/s";
    EXPECT_EQ(ctl.signals().s, 0.0);
    EXPECT_EQ(ctl.signals().d_hat_mm_s, 0.0);
  }
}

TEST(RdvscController, FirstTickAfterResetSkipsTheDdcUpdate) {
  RdvscController ctl(ControllerKind::rdvsc, hal::Axis::x);
  // 10 um error: eq. (7) at k = 0 would give d^_0 = g G e_0 / GB = 0.216 mm/s.
  ctl.update({1.010, 0.0}, test::resting_reference(1.0));
  EXPECT_EQ(ctl.signals().d_hat_mm_s, 0.0) << "d^_0 must stay at d^_{-1} = 0";
  EXPECT_NEAR(ctl.signals().s, 287.0 * 0.010, 1e-12) << "s_0 = G e_0 + gamma s_{-1}, s_{-1} = 0";
  ctl.update({1.010, 0.0}, test::resting_reference(1.0));
  EXPECT_NE(ctl.signals().d_hat_mm_s, 0.0) << "the DDC runs from the second tick";
  ctl.reset();
  ctl.update({1.010, 0.0}, test::resting_reference(1.0));
  EXPECT_EQ(ctl.signals().d_hat_mm_s, 0.0) << "reset() re-arms the first-tick rule";
}

TEST(RdvscController, DvscKindForcesGammaToZero) {
  RdvscController ctl(ControllerKind::dvsc, paper_axis_model(hal::Axis::x), paper_rdvsc_params(hal::Axis::x));
  ASSERT_TRUE(ctl.configured());
  EXPECT_EQ(ctl.params().gamma, 0.0);
  ctl.update({1.01, 0.0}, test::resting_reference(1.0));
  ctl.update({1.01, 0.0}, test::resting_reference(1.0));
  EXPECT_NEAR(ctl.signals().s, 287.0 * 0.01, 1e-12) << "DVSC: s_k = G e_k, no memory";
}

TEST(RdvscController, PidKindOrInvalidParametersLeaveItUnconfiguredAndSilent) {
  RdvscController pid_kind(ControllerKind::pid, paper_axis_model(hal::Axis::x), paper_rdvsc_params(hal::Axis::x));
  EXPECT_FALSE(pid_kind.configured());
  EXPECT_STREQ(pid_kind.config_status().field, "kind");
  EXPECT_EQ(pid_kind.update({1.5, 0.0}, test::resting_reference(1.0)), 0.0);

  SlidingModeParams bad = paper_rdvsc_params(hal::Axis::x);
  bad.q = 1.5;
  RdvscController ctl(ControllerKind::rdvsc, paper_axis_model(hal::Axis::x), bad);
  EXPECT_FALSE(ctl.configured());
  EXPECT_STREQ(ctl.config_status().field, "q");
  EXPECT_EQ(ctl.update({1.5, 0.0}, test::resting_reference(1.0)), 0.0);
  EXPECT_TRUE(ctl.set_params(paper_rdvsc_params(hal::Axis::x)).ok);
  EXPECT_TRUE(ctl.configured());
  EXPECT_NE(ctl.update({1.5, 0.0}, test::resting_reference(1.0)), 0.0);
}

TEST(RdvscController, NonFiniteMeasurementGivesZeroCommand) {
  RdvscController ctl(ControllerKind::rdvsc, hal::Axis::y);
  ctl.update({1.01, 0.0}, test::resting_reference(1.0));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(ctl.update({nan, 0.0}, test::resting_reference(1.0)), 0.0);
  EXPECT_EQ(ctl.signals().d_hat_mm_s, 0.0);
  EXPECT_TRUE(std::isfinite(ctl.update({1.01, 0.0}, test::resting_reference(1.0))));
}

TEST(RdvscController, RejectedParameterSetLeavesTheOldOneInForce) {
  const AxisModel model = paper_axis_model(hal::Axis::x);
  RdvscController ctl(ControllerKind::rdvsc, hal::Axis::x);
  RdvscController twin(ControllerKind::rdvsc, hal::Axis::x);
  NominalPlant plant{model, Eigen::Vector2d(0.02, 0.0)};
  SlidingModeParams bad = paper_rdvsc_params(hal::Axis::x);
  bad.G_position_1_s = 500.0;  // valid on its own ...
  bad.gamma = 0.9;             // ... but gamma >= min(1 - g, q): the whole set must be refused
  for (int k = 0; k < 200; ++k) {
    if (k == 100) {
      const ParamCheck c = ctl.set_params(bad);
      EXPECT_FALSE(c.ok);
      EXPECT_STREQ(c.field, "gamma");
      EXPECT_EQ(ctl.params().G_position_1_s, 287.0) << "half-applied: G changed";
      EXPECT_EQ(ctl.params().gamma, 0.4155);
    }
    const AxisReference ref = test::resting_reference(0.0);
    const double u = ctl.update(plant.state(), ref);
    const double u_twin = twin.update(plant.state(), ref);
    ASSERT_EQ(u, u_twin) << "tick " << k << ": command differs from the untouched twin by " << u - u_twin
                         << " mm/s";
    plant.step(u, 0.5);
  }
}

TEST(RdvscController, AcceptedParameterChangeKeepsTheDisturbanceEstimate) {
  const AxisModel model = paper_axis_model(hal::Axis::x);
  RdvscController ctl(ControllerKind::rdvsc, hal::Axis::x);
  NominalPlant plant{model, Eigen::Vector2d::Zero()};
  const double d = 2.0;
  double u_before = 0.0;
  for (int k = 0; k < 1000; ++k) {
    if (k == 500) {
      SlidingModeParams p = paper_rdvsc_params(hal::Axis::x);
      p.G_position_1_s = 250.0;
      p.q = 0.85;
      ASSERT_TRUE(ctl.set_params(p).ok);
      EXPECT_NEAR(ctl.d_hat_mm_s(), d, 1e-6) << "d^ must survive a gain change";
    }
    const double u = ctl.update(plant.state(), test::resting_reference(0.0));
    if (k == 500) {
      EXPECT_NEAR(u, u_before, 1e-6) << "command jumped by " << u - u_before << " mm/s at the gain change";
    }
    u_before = u;
    plant.step(u, d);
  }
  EXPECT_NEAR(ctl.d_hat_mm_s(), d, 1e-6);
  EXPECT_LT(std::fabs(plant.x(0)), 1e-9) << "position error " << plant.x(0) * 1e3 << " um";
}

TEST(RdvscController, CommandIsClampedAndTheDdcDoesNotWindUp) {
  for (hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    for (ControllerKind kind : {ControllerKind::dvsc, ControllerKind::rdvsc}) {
      const AxisModel model = paper_axis_model(axis);
      RdvscController ctl(kind, axis);
      const double u_max = ctl.params().u_max_mm_s;
      NominalPlant plant{model, Eigen::Vector2d::Zero()};
      const double target_mm = 20.0;  // a step: 120 ms at full speed
      int saturated_ticks = 0;
      double overshoot_mm = 0.0;
      double worst_d_hat = 0.0;
      for (int k = 0; k < 3000; ++k) {
        const double u = ctl.update(plant.state(), test::resting_reference(target_mm));
        ASSERT_LE(std::fabs(u), u_max) << "tick " << k << ": |u| = " << std::fabs(u) << " mm/s";
        if (ctl.signals().saturated) ++saturated_ticks;
        worst_d_hat = std::max(worst_d_hat, std::fabs(ctl.signals().d_hat_mm_s));
        overshoot_mm = std::max(overshoot_mm, plant.x(0) - target_mm);
        plant.step(u, 0.0);
      }
      const std::string name = std::string(1, hal::axis_name(axis)) + " " + to_string(kind);
      EXPECT_GT(saturated_ticks, 20) << name << ": the step must saturate the command";
      EXPECT_LT(worst_d_hat, 1e-9) << name << ": DDC wound up to " << worst_d_hat << " mm/s with no disturbance";
      EXPECT_LT(overshoot_mm * 1e3, 1.0) << name << ": overshoot "
                                         << overshoot_mm * 1e3 << " um";
      EXPECT_NEAR(plant.x(0), target_mm, 1e-6) << name << ": final error " << (plant.x(0) - target_mm) * 1e3 << " um";
    }
  }
}

// The linearisation used for PID tuning is the controller itself inside the
// boundary layer (after the first tick, whose DDC update is skipped).
TEST(RdvscController, LinearisedModelReproducesTheControllerInsideTheBoundaryLayer) {
  for (hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    for (ControllerKind kind : {ControllerKind::dvsc, ControllerKind::rdvsc}) {
      const AxisModel model = paper_axis_model(axis);
      const SlidingModeParams p = paper_sliding_mode_params(axis, kind);
      RdvscController ctl(kind, model, p);
      const LinearController lin = linearised_sliding_mode(model, p);
      std::mt19937 rng(7);
      std::uniform_real_distribution<double> pos_um(-1.0, 1.0), spd(-0.2, 0.2);
      Eigen::Vector3d xi = Eigen::Vector3d::Zero();
      for (int k = 0; k < 500; ++k) {
        const Eigen::Vector2d x(pos_um(rng) * 1e-3, spd(rng));
        const double u = ctl.update({x(0), x(1)}, test::resting_reference(0.0));
        ASSERT_LT(std::fabs(ctl.signals().s), p.phi_mm_s);
        if (k == 0) {
          xi << ctl.signals().s, ctl.signals().d_hat_mm_s, 0.0;  // start the model at k = 1
          continue;
        }
        const double u_lin = (lin.Cc * xi + lin.Dc * x).value();
        xi = lin.Ac * xi + lin.Bc * x;
        ASSERT_NEAR(u, u_lin, 1e-9) << to_string(kind) << " tick " << k << ": linear model off by " << u - u_lin
                                    << " mm/s";
      }
    }
  }
}

}  // namespace
}  // namespace tnv::fw
