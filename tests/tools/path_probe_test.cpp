// Programs that probe (G38.2-G38.5), run by `tnv-hil path`'s library on the
// emulated machine with a stock ([stock] on): the interpreter waits at each
// probe for the firmware's outcome, sets #5061-#5070 from it and goes on
// from where the machine rests. Judged against the stock's own faces.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {
namespace path_probe_test {
namespace {

constexpr std::size_t kX = hal::index(hal::Axis::x);
constexpr std::size_t kZ = hal::index(hal::Axis::z);
// The head powers up with the spindle nose at -25 mm and a 125 mm tool (the
// tool point at -150 mm), the table at X = 6 mm.
constexpr double kToolPointStart_mm = -150.0;
// The trip is reported within one tick's travel at the probe's feed plus an
// encoder count of the face (docs/motion.md "Probe moves"): 2.4 um at 2 mm/s.
constexpr double kProbeTolerance_mm = 2.0 * 1e-3 + 0.42e-3;
// The probe in the spindle: a stylus ball of 0.5 mm radius around the tool
// point on a 0.8 mm shank (the "tool" the machine cuts with). It trips half
// a millimetre before the tool point reaches a face, so braking after the
// trip never takes the shank into the stock (which the machine counts as a
// crash, the spindle being off). The program allows for the ball, as a real
// one must.
constexpr double kTipRadius_mm = 0.5;
constexpr double kShankDiameter_mm = 0.8;

emu::Scenario stock_scenario(double top_mm, double x_max_mm) {
  std::optional<emu::Scenario> s = emu::builtin_scenario("no-cut");
  EXPECT_TRUE(s.has_value());
  s->stock.enabled = true;
  s->stock.top_mm = top_mm;
  s->stock.x_max_mm = x_max_mm;
  s->probe.tip_radius_mm = kTipRadius_mm;
  s->tool.diameter_mm = kShankDiameter_mm;
  return *s;
}

PathRunResult run(const emu::Scenario& s, const std::string& program) {
  PathRunOptions o;
  o.keep_samples = true;
  return run_path(s, fw::default_firmware_config(), fw::ControllerKind::rdvsc, program, o);
}

TEST(PathProbe, G38_2DownOntoTheTopThenOneMillimetreAboveItFromNumber5063) {
  const emu::Scenario s = stock_scenario(kToolPointStart_mm - 5.0, 1e3);  // the top 5 mm below the tool point
  // F120 = 2 mm/s; the nose from -25 to -40 would take the tool point 10 mm into the stock.
  const PathRunResult r = run(s, "G21 G90\nG38.2 Z-40 F120\nG0 Z[#5063 - 0.5 + 1]\nM2\n");
  ASSERT_TRUE(r.completed) << r.error;
  ASSERT_FALSE(r.samples.empty());
  EXPECT_EQ(r.program.probes, 1u);
  const double tool_point_mm = r.samples.back().reference_mm[kZ] - s.tool.length_mm;
  EXPECT_NEAR(tool_point_mm, s.stock.top_mm + 1.0, kProbeTolerance_mm) << "Z[#5063 - 0.5 + 1]: 1 mm above the found top";
  EXPECT_NEAR(r.samples.back().position_mm[kZ] - s.tool.length_mm, s.stock.top_mm + 1.0, kProbeTolerance_mm + 2e-3);
  EXPECT_EQ(r.crashes, 0u);
  std::printf("G38.2 onto the top: tool point ends %.4f um from 1 mm above it\n",
              (tool_point_mm - s.stock.top_mm - 1.0) * 1e3);
}

TEST(PathProbe, G38_2SidewaysOntoASideFaceThenOneMillimetreBesideItFromNumber5061) {
  // The tool point 5 mm below the top, the stock's side face at X = 3 (the table at X = 6).
  const emu::Scenario s = stock_scenario(kToolPointStart_mm + 5.0, 3.0);
  const PathRunResult r = run(s, "G21 G90\nG38.2 X-2 F120\nG0 X[#5061 - 0.5 + 1]\nM2\n");
  ASSERT_TRUE(r.completed) << r.error;
  ASSERT_FALSE(r.samples.empty());
  EXPECT_NEAR(r.samples.back().reference_mm[kX], s.stock.x_max_mm + 1.0, kProbeTolerance_mm);
  EXPECT_EQ(r.crashes, 0u);
}

TEST(PathProbe, G38_3ThatDoesNotTripGoesOnWithNumber5070Zero) {
  const emu::Scenario s = stock_scenario(kToolPointStart_mm - 5.0, 1e3);
  // 2 mm down, 3 mm short of the top: no contact. #5063 is then the programmed end (-27), #5070 0:
  // Z ends at -27 + 2 + 10 x #5070 = -25.
  const PathRunResult r = run(s, "G21 G90\nG38.3 Z-27 F120\nG0 Z[#5063 + 2 + 10 * #5070]\nM2\n");
  ASSERT_TRUE(r.completed) << r.error;
  ASSERT_FALSE(r.samples.empty());
  EXPECT_NEAR(r.samples.back().reference_mm[kZ], -25.0, 1e-9);
  EXPECT_EQ(r.segments, 2u);
}

TEST(PathProbe, G38_2ThatDoesNotTripStopsTheProgramAtItsLineAndSendsNothingAfterIt) {
  const emu::Scenario s = stock_scenario(kToolPointStart_mm - 5.0, 1e3);
  const PathRunResult r = run(s, "G21 G90\nG38.2 Z-27 F120\nG0 Z-20\nG0 X0\nM2\n");
  EXPECT_FALSE(r.completed);
  EXPECT_NE(r.error.find("line 2"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("G38.2"), std::string::npos) << r.error;
  EXPECT_EQ(r.segments, 1u) << "only the probe was sent";
}

TEST(PathProbe, AProgramWithoutAProbeIsReadWholeAndRuns) {
  const emu::Scenario s = stock_scenario(kToolPointStart_mm - 5.0, 1e3);
  const PathRunResult r = run(s, "G21 G91\nG1 X2 F600\nG1 Y2\nM2\n");
  ASSERT_TRUE(r.completed) << r.error;
  EXPECT_EQ(r.program.probes, 0u);
  EXPECT_EQ(r.segments, 2u);
}

}  // namespace
}  // namespace path_probe_test
}  // namespace tnv::hil
