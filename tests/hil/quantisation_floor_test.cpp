// Reference plant, "What the numbers can and cannot be": perfect tracking
// of the circle read through a rounding encoder gives mean ~0.10 um and max
// ~0.29 um of contour error. A simulated mean below that means
// quantisation is missing from the chain.
#include <gtest/gtest.h>

#include "emulator/quadrature_encoder.hpp"
#include "firmware/timing/encoder_position.hpp"
#include "firmware/trajectory/circle_trajectory.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/seeded_scenario.hpp"
#include "tools/score/contour_stats.hpp"

namespace tnv::hil {
namespace {

constexpr double kCountMm = 10.0 / 24000.0;

// The table sits exactly on the reference every tick; the firmware sees it
// only through the emulated encoder register and its own counter extension.
ContourStats perfect_tracking(const emu::Scenario& scenario) {
  const fw::CircleTrajectory circle(fw::CircleSpec{});
  const emu::QuadratureEncoder enc_x(kCountMm, scenario.encoder.axis_offset_counts[0]);
  const emu::QuadratureEncoder enc_y(kCountMm, scenario.encoder.axis_offset_counts[1]);
  const fw::PlaneSample start = circle.start();
  // Homed as the HIL rig homes the firmware.
  const double home_x = homed_position_mm(scenario, hal::Axis::x, start.axis[0].position_mm);
  const double home_y = homed_position_mm(scenario, hal::Axis::y, start.axis[1].position_mm);
  fw::EncoderPosition ext_x(16), ext_y(16);
  ext_x.reset(enc_x.register_value(start.axis[0].position_mm));
  ext_y.reset(enc_y.register_value(start.axis[1].position_mm));
  ContourAccumulator acc;
  const auto ticks = static_cast<int>(std::ceil(circle.duration_s() / 1e-3));
  for (int k = 0; k <= ticks; ++k) {
    const fw::PlaneSample ref = circle.at(k * 1e-3);
    ext_x.update(enc_x.register_value(ref.axis[0].position_mm));
    ext_y.update(enc_y.register_value(ref.axis[1].position_mm));
    const double x = home_x + static_cast<double>(ext_x.counts()) * kCountMm;
    const double y = home_y + static_cast<double>(ext_y.counts()) * kCountMm;
    acc.add(contour_error_mm(ref.axis[0].position_mm, ref.axis[1].position_mm, x, y));
  }
  return acc.stats();
}

TEST(QuantisationFloor, PerfectTrackingGivesAbout0p10UmMeanAnd0p29UmMax) {
  std::vector<ContourStats> runs;
  const emu::Scenario base;
  for (int seed = 0; seed < 8; ++seed) runs.push_back(perfect_tracking(seeded(base, seed)));
  const ContourStats avg = average(runs);
  EXPECT_NEAR(avg.mean_um, 0.10, 0.01) << "mean contour error of perfect tracking, um";
  EXPECT_GT(avg.max_um, 0.25) << "max contour error of perfect tracking, um";
  EXPECT_LE(avg.max_um, 0.30) << "max contour error of perfect tracking, um (q/sqrt(2) = 0.295)";
  for (const ContourStats& r : runs) EXPECT_LE(r.max_um, 0.295 + 1e-6) << "no sample can exceed q/sqrt(2)";
}

}  // namespace
}  // namespace tnv::hil
