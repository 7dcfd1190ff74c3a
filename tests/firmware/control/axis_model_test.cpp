#include <gtest/gtest.h>

#include <cmath>

#include "firmware/control/axis_model.hpp"

namespace tnv::fw {
namespace {

struct ReferencePlantNumbers {
  hal::Axis axis;
  double tau_s;
  double a12, b1, a22;  // reference-plant.md, printed digits
};

constexpr ReferencePlantNumbers kNumbers[] = {{hal::Axis::x, 5.360e-3, 0.0009123, 0.0000877, 0.8298},
                                              {hal::Axis::y, 7.122e-3, 0.0009330, 0.0000670, 0.8690}};

TEST(AxisModel, ZohOfFirstOrderSpeedLoopMatchesReferencePlantToPrintedDigits) {
  for (const auto& n : kNumbers) {
    const AxisModel m = zoh_axis_model(n.tau_s, 1.0, 1e-3);
    const char name = hal::axis_name(n.axis);
    EXPECT_NEAR(m.A(0, 0), 1.0, 1e-15) << name;
    EXPECT_NEAR(m.A(1, 0), 0.0, 1e-15) << name;
    EXPECT_NEAR(m.A(0, 1), n.a12, 0.5e-7) << name << ": A12 = " << m.A(0, 1) << " s, printed " << n.a12;
    EXPECT_NEAR(m.B(0), n.b1, 0.5e-7) << name << ": B1 = " << m.B(0) << " s, printed " << n.b1;
    EXPECT_NEAR(m.A(1, 1), n.a22, 0.5e-4) << name << ": A22 = " << m.A(1, 1) << ", printed " << n.a22;
    EXPECT_NEAR(m.B(1), 1.0 - m.A(1, 1), 1e-15) << name << ": B2 must be 1 - A22 for K = 1";
    EXPECT_DOUBLE_EQ(m.period_s, 1e-3);
  }
}

TEST(AxisModel, ZohGainScalesOnlyTheInputColumn) {
  const AxisModel m1 = zoh_axis_model(5.360e-3, 1.0, 1e-3);
  const AxisModel m2 = zoh_axis_model(5.360e-3, 2.5, 1e-3);
  EXPECT_EQ(m1.A, m2.A);
  EXPECT_NEAR(m2.B(0), 2.5 * m1.B(0), 1e-18);
  EXPECT_NEAR(m2.B(1), 2.5 * m1.B(1), 1e-15);
}

TEST(AxisModel, PaperModelIsTheZohRoundedToFourDecimals) {
  for (const auto& n : kNumbers) {
    const AxisModel paper = paper_axis_model(n.axis);
    const AxisModel zoh = zoh_axis_model(n.tau_s, 1.0, 1e-3);
    for (int i = 0; i < 2; ++i) {
      for (int j = 0; j < 2; ++j)
        EXPECT_NEAR(paper.A(i, j), zoh.A(i, j), 0.5e-4) << hal::axis_name(n.axis) << " A(" << i << "," << j << ")";
      EXPECT_NEAR(paper.B(i), zoh.B(i), 0.5e-4) << hal::axis_name(n.axis) << " B(" << i << ")";
    }
  }
}

TEST(AxisModel, PaperModelHasThePrintedEq31Values) {
  const AxisModel x = paper_axis_model(hal::Axis::x);
  const AxisModel y = paper_axis_model(hal::Axis::y);
  EXPECT_EQ(x.A(0, 1), 0.0009);
  EXPECT_EQ(x.A(1, 1), 0.8298);
  EXPECT_EQ(x.B(0), 0.0001);
  EXPECT_EQ(x.B(1), 0.1702);
  EXPECT_EQ(y.A(0, 1), 0.0009);
  EXPECT_EQ(y.A(1, 1), 0.8690);
  EXPECT_EQ(y.B(0), 0.0001);
  EXPECT_EQ(y.B(1), 0.1310);
  const AxisModel def{};
  EXPECT_EQ(def.A, x.A) << "AxisModel{} defaults to the paper's X axis";
  EXPECT_EQ(def.B, x.B);
}

TEST(AxisModel, ZohWithNonPositiveTimeConstantIsRejectedAsNonFinite) {
  EXPECT_FALSE(is_finite(zoh_axis_model(0.0, 1.0, 1e-3)));
  EXPECT_FALSE(is_finite(zoh_axis_model(-1e-3, 1.0, 1e-3)));
  EXPECT_FALSE(is_finite(zoh_axis_model(5e-3, 1.0, 0.0)));
  EXPECT_TRUE(is_finite(zoh_axis_model(5e-3, 1.0, 1e-3)));
}

}  // namespace
}  // namespace tnv::fw
