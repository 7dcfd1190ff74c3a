// The identification fit on records alone (tools/tune/axis_identification.hpp):
// an exact synthetic step, and a refusal. The fit on the emulated tables is
// tests/hil/autotune_identify_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "tools/tune/axis_identification.hpp"

namespace tnv::tune {
namespace {

// The fit alone, on a synthetic exact step: tau and V come back.
TEST(AxisIdentification, StepFitRecoversTauAndSpeed) {
  const double tau = 0.0065, v = 8.5;
  std::vector<double> p;
  for (int j = 0; j <= 150; ++j) {
    const double t = j * 1e-3;
    p.push_back(1.25 + v * (t - tau * (1.0 - std::exp(-t / tau))));
  }
  const StepFit f = fit_step(p, 1e-3);
  EXPECT_NEAR(f.tau_s, tau, 1e-6) << "tau " << f.tau_s * 1e3 << " ms";
  EXPECT_NEAR(f.speed_mm_s, v, 1e-6) << "V " << f.speed_mm_s << " mm/s";
}

TEST(AxisIdentification, RefusesTooFewRecords) {
  const AxisIdentification id = identify_from_records(hal::Axis::x, {}, {}, 1e-3);
  EXPECT_FALSE(id.ok);
  EXPECT_FALSE(id.error.empty());
}

}  // namespace
}  // namespace tnv::tune
