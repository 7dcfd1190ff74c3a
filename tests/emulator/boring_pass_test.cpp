// S4 on real axes: the boring bar's overhang and infeed from the Z motion
// and the spindle, its deflection (S4 eq. 2), the bore's radius error, the
// gauge at two depths.
#include "emulator/boring_pass.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "emulator/cutting_at_tool.hpp"
#include "emulator/spindle_drive.hpp"
#include "emulator/substep_timing.hpp"
#include "emulator/z_axis_plant.hpp"

namespace tnv::emu {
namespace {

TEST(BoringPass, OverhangAndInfeedPerRevolution) {
  const Scenario s;
  BoringPass pass(s.boring, s.stock, boring_process_config(s));
  EXPECT_EQ(pass.overhang_mm(-150.0), 40.0) << "L0 at the stock top";
  EXPECT_EQ(pass.overhang_mm(-250.0), 140.0);
  EXPECT_NEAR(BoringPass::infeed_mm_rev(-1.0, 600.0), 0.1, 1e-15) << "1 mm/s at 10 rev/s";
  EXPECT_NEAR(BoringPass::infeed_mm_rev(-5.0, -6000.0), 0.05, 1e-15);
  EXPECT_EQ(BoringPass::infeed_mm_rev(1.0, 600.0), 0.0) << "retracting is no infeed";
  EXPECT_EQ(BoringPass::infeed_mm_rev(-1.0, 0.0), 0.0);
}

TEST(BoringPass, DeflectionIsS4EquationTwoAtTheCurrentDepth) {
  const Scenario s;
  BoringPass pass(s.boring, s.stock, boring_process_config(s));
  // Table 1 (parts 1-10): C = 0.0871 mm, alpha 0.5025, beta 0.2676.
  const double S = 0.05, L = 140.0;
  pass.advance(-250.0, -5.0, 6000.0);
  EXPECT_TRUE(pass.cutting());
  EXPECT_NEAR(pass.last_deflection_mm(), 0.0871 * std::pow(S, 0.5025) * std::pow(L, 0.2676), 1e-12);
  EXPECT_NEAR(pass.radius_error_mm(S, L), pass.last_deflection_mm() - 0.1165, 1e-15) << "d - d0";
  pass.advance(-140.0, -5.0, 6000.0);
  EXPECT_FALSE(pass.cutting()) << "above the stock top";
  // The second parameter set from part 11 (S4 section 5).
  pass.begin_part(11);
  pass.advance(-250.0, -5.0, 6000.0);
  EXPECT_NEAR(pass.last_deflection_mm(), 0.15 * std::pow(S, 0.7) * std::pow(L, 0.4), 1e-12);
}

// A pass on the real Z plant with the spindle at 6000 rpm: the gauge
// depths see the infeed the plant's speed and the spindle's speed give.
TEST(BoringPass, RealZMotionSetsTheBoreAtTheGaugeDepths) {
  Scenario s;
  s.boring.sigma_d_um = 0.0;  // the true bore, read by an exact gauge
  ZAxisPlant z(s.z_axis, s.plant[hal::index(hal::Axis::z)]);
  SpindleDrive spindle(s.spindle);
  BoringPass pass(s.boring, s.stock, boring_process_config(s));
  spindle.set_command_code(spindle.code_for_rpm(6000.0));
  for (int i = 0; i < 500'000; ++i) spindle.step();  // 5 s: at speed
  // Tool point 5 mm above the stock top; down at u = -21: v -> -21 - 1 + f_c = -20 mm/s.
  z.set_state(s.stock.top_mm + 5.0 + s.tool.length_mm, 0.0, true);
  pass.begin_part(1);
  while (tool_point_z_mm(z.position_mm(), s.tool) > s.stock.top_mm - 272.0) {
    z.step(-21.0);
    spindle.step();
    pass.advance(tool_point_z_mm(z.position_mm(), s.tool), z.speed_mm_s(), spindle.speed_rpm());
  }
  const auto gauge = pass.read_gauge();
  ASSERT_TRUE(gauge[0].cut);
  ASSERT_TRUE(gauge[1].cut);
  EXPECT_NEAR(gauge[0].overhang_mm, 40.0, 1e-3);  // within one sub-step's travel
  EXPECT_NEAR(gauge[1].overhang_mm, 310.0, 1e-3);
  // 20 mm/s at 100 rev/s (the head has settled: 5 mm is 28 tau_Z at this speed).
  EXPECT_NEAR(gauge[0].infeed_mm_rev, 0.2, 1e-6);
  EXPECT_NEAR(gauge[1].infeed_mm_rev, 0.2, 1e-6);
  const BoringProcess truth(boring_process_config(s));
  const double cos_phi = std::cos(60.0 * std::numbers::pi / 180.0);
  for (const GaugeDepthReading& g : gauge) {
    const double error_mm = truth.deflection_mm(1, g.infeed_mm_rev, g.overhang_mm) - 0.1165;
    EXPECT_NEAR(g.radius_error_mm, error_mm, 1e-12);
    EXPECT_NEAR(g.reading_mm, 2.0 * cos_phi * error_mm, 1e-12) << "S4 eq. (11): the diametral reading";
  }
  // The bar bends more as it goes deeper: the largest error at the bottom.
  EXPECT_NEAR(pass.max_radius_error_mm(), truth.deflection_mm(1, 0.2, 312.0) - 0.1165, 1e-6);
  EXPECT_LT(gauge[0].radius_error_mm, gauge[1].radius_error_mm);
}

TEST(BoringPass, GaugeAddsTheProcessNoiseAndItsOwnResolution) {
  Scenario s;
  s.noise.seed = 7;
  s.noise.bore_gauge_resolution_um = 1.0;
  s.noise.bore_gauge_um_rms = 1.0;
  BoringPass pass(s.boring, s.stock, boring_process_config(s));
  BoringProcess same(boring_process_config(s));  // the same seeds, the same draws
  pass.begin_part(3);
  for (double z = -149.0; z > -150.0 - 280.0; z -= 0.01) pass.advance(z, -1.0, 1200.0);  // 0.05 mm/rev
  const auto gauge = pass.read_gauge();
  for (const GaugeDepthReading& g : gauge) {
    ASSERT_TRUE(g.cut);
    const BoreSample expected = same.sample_bore(3, g.infeed_mm_rev, g.overhang_mm);
    EXPECT_EQ(g.reading_mm, expected.reading_mm);
    EXPECT_EQ(g.radius_error_mm, expected.radius_error_mm);
    EXPECT_NE(g.radius_error_mm, pass.radius_error_mm(g.infeed_mm_rev, g.overhang_mm)) << "sigma_d is on";
    const double steps = g.reading_mm / 0.001;
    EXPECT_NEAR(steps, std::round(steps), 1e-6) << "read in 1 um steps";
  }
}

TEST(BoringPass, AGaugeDepthTheBarNeverReachedHasNoReading) {
  const Scenario s;
  BoringPass pass(s.boring, s.stock, boring_process_config(s));
  for (double z = -149.0; z > -200.0; z -= 0.01) pass.advance(z, -1.0, 1200.0);
  const auto gauge = pass.read_gauge();
  EXPECT_TRUE(gauge[0].cut);
  EXPECT_FALSE(gauge[1].cut) << "270 mm deep was never bored";
  EXPECT_EQ(gauge[1].reading_mm, 0.0);
}

TEST(BoringProcess, SampleBoreIsTheMeasurementWithItsRadiusError) {
  BoringProcess a(paper_boring_process(0.016231, 5));
  BoringProcess b(paper_boring_process(0.016231, 5));
  for (int part = 1; part <= 30; ++part) {
    const BoreSample sample = a.sample_bore(part, 0.05, 310.0);
    EXPECT_EQ(sample.reading_mm, b.measure_bore_error_mm(part, 0.05, 310.0));
    EXPECT_NEAR(sample.reading_mm, 2.0 * 0.5 * sample.radius_error_mm, 1e-15);
  }
}

}  // namespace
}  // namespace tnv::emu
