#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <limits>

#include "firmware/control/sliding_mode_params.hpp"

namespace tnv::fw {
namespace {

const AxisModel kModelX = paper_axis_model(hal::Axis::x);

void expect_rejected(const SlidingModeParams& p, const char* field, const char* what) {
  const ParamCheck c = validate(p, kModelX);
  EXPECT_FALSE(c.ok) << what << " was accepted";
  EXPECT_STREQ(c.field, field) << what << ": reason given: " << c.reason;
  EXPECT_GT(std::strlen(c.reason), 0u) << what;
}

TEST(SlidingModeParams, PaperTablesAreValidForBothAxesAndKinds) {
  for (hal::Axis axis : {hal::Axis::x, hal::Axis::y}) {
    for (ControllerKind kind : {ControllerKind::dvsc, ControllerKind::rdvsc}) {
      const SlidingModeParams p = paper_sliding_mode_params(axis, kind);
      const ParamCheck c = validate(p, paper_axis_model(axis));
      EXPECT_TRUE(c.ok) << hal::axis_name(axis) << " " << to_string(kind) << ": " << c.field << " " << c.reason;
      // The theorem conditions, spelled out.
      EXPECT_GT(p.phi_mm_s, p.eta_mm_s / (p.q + 1.0)) << "Theorem 2";
      if (kind == ControllerKind::rdvsc) {
        EXPECT_LT(p.gamma, std::min(1.0 - p.g, p.q)) << "Theorem 5";
      } else {
        EXPECT_EQ(p.gamma, 0.0);
      }
    }
  }
}

TEST(SlidingModeParams, PaperValuesAreTables1And2) {
  const SlidingModeParams x = paper_rdvsc_params(hal::Axis::x);
  EXPECT_EQ(x.G_position_1_s, 287.0);
  EXPECT_EQ(x.G_speed, 1.0);
  EXPECT_EQ(x.eta_mm_s, 0.1971);
  EXPECT_EQ(x.phi_mm_s, 1.273);
  EXPECT_EQ(x.q, 0.9);
  EXPECT_EQ(x.g, 0.1498);
  EXPECT_EQ(x.gamma, 0.4155);
  const SlidingModeParams y = paper_rdvsc_params(hal::Axis::y);
  EXPECT_EQ(y.G_position_1_s, 203.0);
  EXPECT_EQ(y.eta_mm_s, 0.1014);
  EXPECT_EQ(y.phi_mm_s, 1.722);
  EXPECT_EQ(y.q, 0.98);
  EXPECT_EQ(y.g, 0.3104);
  EXPECT_EQ(y.gamma, 0.3040);
  EXPECT_NEAR(x.u_max_mm_s, 166.67, 0.005) << "DAC full scale 1000 rpm x 10 mm / 60";
  EXPECT_EQ(paper_dvsc_params(hal::Axis::y).gamma, 0.0);
  const SlidingModeParams def{};
  EXPECT_EQ(def.G_position_1_s, x.G_position_1_s) << "SlidingModeParams{} defaults to X, R-DVSC";
  EXPECT_EQ(def.gamma, x.gamma);
}

TEST(SlidingModeParams, NanAndInfAreRejectedWithTheFieldNamed) {
  struct Member {
    double SlidingModeParams::*ptr;
    const char* name;
  };
  const Member members[] = {{&SlidingModeParams::G_position_1_s, "G_position_1_s"},
                            {&SlidingModeParams::G_speed, "G_speed"},
                            {&SlidingModeParams::eta_mm_s, "eta_mm_s"},
                            {&SlidingModeParams::phi_mm_s, "phi_mm_s"},
                            {&SlidingModeParams::q, "q"},
                            {&SlidingModeParams::g, "g"},
                            {&SlidingModeParams::gamma, "gamma"},
                            {&SlidingModeParams::u_max_mm_s, "u_max_mm_s"}};
  for (const Member& m : members) {
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                       -std::numeric_limits<double>::infinity()}) {
      SlidingModeParams p = paper_rdvsc_params(hal::Axis::x);
      p.*m.ptr = bad;
      expect_rejected(p, m.name, m.name);
    }
  }
}

TEST(SlidingModeParams, OutOfRangeValuesAreRejectedWithTheFieldNamed) {
  const SlidingModeParams base = paper_rdvsc_params(hal::Axis::x);
  SlidingModeParams p = base;
  p.q = 1.0;
  expect_rejected(p, "q", "q = 1");
  p.q = 1.2;
  expect_rejected(p, "q", "q = 1.2");
  p.q = 0.0;
  expect_rejected(p, "q", "q = 0");
  p = base;
  p.g = 0.0;
  expect_rejected(p, "g", "g = 0");
  p.g = -0.1;
  expect_rejected(p, "g", "g = -0.1");
  p.g = 1.0;
  expect_rejected(p, "g", "g = 1");
  p = base;
  p.eta_mm_s = 0.0;
  expect_rejected(p, "eta_mm_s", "eta = 0 mm/s");
  p = base;
  p.phi_mm_s = base.eta_mm_s / (base.q + 1.0);  // equality is not enough
  expect_rejected(p, "phi_mm_s", "phi = eta/(q+1)");
  p.phi_mm_s = 0.05;
  expect_rejected(p, "phi_mm_s", "phi = 0.05 mm/s < eta/(q+1)");
  p = base;
  p.gamma = 1.0 - base.g;  // X: min(1 - g, q) = 1 - g = 0.8502
  expect_rejected(p, "gamma", "gamma = 1 - g");
  p = base;
  p.q = 0.5;
  p.phi_mm_s = 1.273;
  p.gamma = 0.5;  // now min(1 - g, q) = q = 0.5
  expect_rejected(p, "gamma", "gamma = q");
  p.gamma = 0.49;
  EXPECT_TRUE(validate(p, kModelX).ok) << "gamma just below min(1 - g, q) is valid";
  p = base;
  p.gamma = -0.1;
  expect_rejected(p, "gamma", "gamma < 0");
  p = base;
  p.u_max_mm_s = 0.0;
  expect_rejected(p, "u_max_mm_s", "u_max = 0 mm/s");
}

TEST(SlidingModeParams, SurfaceWithGbZeroOrUnstableZeroDynamicsIsRejected) {
  SlidingModeParams p = paper_rdvsc_params(hal::Axis::x);
  p.G_position_1_s = -kModelX.B(1) / kModelX.B(0);  // GB = 0
  expect_rejected(p, "G", "GB = 0");
  p.G_position_1_s = -100.0;  // zero of G(zI-A)^-1 B at z = 1.106
  expect_rejected(p, "G", "unstable sliding-surface zero");
}

TEST(SlidingModeParams, NonFiniteModelIsRejected) {
  AxisModel m = kModelX;
  m.A(1, 1) = std::numeric_limits<double>::quiet_NaN();
  const ParamCheck c = validate(paper_rdvsc_params(hal::Axis::x), m);
  EXPECT_FALSE(c.ok);
  EXPECT_STREQ(c.field, "model");
}

}  // namespace
}  // namespace tnv::fw
