// The lead-error fit (tools/tune/screw_fit.hpp): exact on a known screw,
// refusals for what cannot determine it. The measurement on the bench
// table is tests/hil/screw_map_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "tests/tune/known_screw.hpp"
#include "tools/tune/screw_fit.hpp"

namespace tnv::tune {
namespace {

using test::known_error_um;
using test::known_points;

TEST(ScrewFit, RecoversAKnownScrewExactly) {
  std::string error;
  const std::optional<ScrewFit> fit = fit_screw(known_points(), 10.0, error);
  ASSERT_TRUE(fit) << error;
  EXPECT_NEAR(fit->backlash_um, 8.0, 1e-6);
  EXPECT_NEAR(fit->lead_um_per_m, -45.0, 1e-6);
  EXPECT_LT(fit->residual_max_um, 1e-6);
  for (std::size_t j = 0; j < fit->turn_error_um.size(); ++j) {
    const double phase = 2.0 * std::numbers::pi * static_cast<double>(j) / 16.0;
    EXPECT_NEAR(fit->turn_error_um[j], 3.0 * std::sin(phase) + std::cos(2.0 * phase), 1e-6) << j;
  }
  // The firmware's interpolated table reproduces the readings to within its interpolation.
  for (const GaugePoint& p : known_points())
    EXPECT_NEAR(fitted_error_um(*fit, p.position_mm, p.direction) + 7.0, known_error_um(p.position_mm, p.direction),
                0.12);
}

TEST(ScrewFit, RefusesWhatCannotDetermineTheModel) {
  std::vector<GaugePoint> forward_only;
  for (const GaugePoint& p : known_points())
    if (p.direction > 0) forward_only.push_back(p);
  std::string error;
  EXPECT_FALSE(fit_screw(forward_only, 10.0, error));
  EXPECT_NE(error.find("each direction"), std::string::npos) << error;
  std::vector<GaugePoint> short_span;
  for (const GaugePoint& p : known_points())
    if (p.position_mm < -14.0) short_span.push_back(p);
  EXPECT_FALSE(fit_screw(short_span, 10.0, error));
  EXPECT_NE(error.find("less than one turn"), std::string::npos) << error;
  EXPECT_FALSE(fit_screw(known_points(), std::nan(""), error));
}

}  // namespace
}  // namespace tnv::tune
