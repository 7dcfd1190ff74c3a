// Issue 3, HIL on flex-30 (30 Hz, zeta 0.02 structural mode on X): the real
// firmware with the shaper in its reference path, scored at the tool point
// the firmware never sees. A rapid on X (100 mm/s, 20 ms raised-cosine
// ramps) over 5, 10 and 20 mm, each at 5 encoder phases (seeds):
//  - ZV/ZVD/ZVDD designed at the mode leave <= 5 % of the unshaped
//    residual vibration, in every run;
//  - ZVDD designed 30 % off (actual / design frequency 1.3 and 0.7) still
//    leaves <= 12 %, in every run;
//  - settling to +-1 um is at least 3x shorter than unshaped (median over
//    the runs: at standstill the loop stick-slips by about a count now and
//    then and each slip rings the mode at ~1 um, see shaper_move_compare.hpp).
#include <gtest/gtest.h>

#include <algorithm>

#include "emulator/scenario_file.hpp"
#include "tests/sanitized_build.hpp"
#include "tools/hil/shaper_jog_run.hpp"
#include "tools/hil/shaper_move_compare.hpp"

namespace tnv::hil {
namespace {

// Every run is judged alone but the settling median: a sanitizer build runs one seed and leaves the median out.
constexpr int kFlexSeeds = tnv::test::kSanitizedBuild ? 1 : 5;
constexpr double kDistancesMm[] = {5.0, 10.0, 20.0};

struct Case {
  fw::ShaperType type;
  double design_hz;
  double max_residual_ratio;
  bool settling_checked;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// One test: 5 shapers x 3 distances x 5 seeds x (shaped + unshaped) runs.
TEST(ShaperFlex30, ShapedMovesCancelTheModeAndSettleFaster) {
  const emu::Scenario flex = *emu::builtin_scenario("flex-30");
  ASSERT_EQ(flex.plant[0].mode_hz, 30.0);
  ASSERT_EQ(flex.plant[0].mode_zeta, 0.02);
  const double zeta = flex.plant[0].mode_zeta;
  const Case cases[] = {{fw::ShaperType::zv, 30.0, 0.05, true},
                        {fw::ShaperType::zvd, 30.0, 0.05, true},
                        {fw::ShaperType::zvdd, 30.0, 0.05, true},
                        {fw::ShaperType::zvdd, 30.0 / 1.3, 0.12, false},
                        {fw::ShaperType::zvdd, 30.0 / 0.7, 0.12, false}};
  for (const Case& c : cases) {
    std::vector<double> settling_ratios;
    double worst_ratio = 0.0;
    for (double distance_mm : kDistancesMm) {
      MoveRunRequest request;
      request.scenario = flex;
      request.move = {hal::Axis::x, distance_mm, 100.0, 0.02, 0.0};
      request.shaper = fw::ShaperSpec{c.type, {c.design_hz, zeta}, {0.0, 0.0}};
      const MoveComparison cmp = compare_move(request, fw::default_firmware_config(), kFlexSeeds);
      ASSERT_TRUE(cmp.error.empty()) << cmp.error;
      for (const MovePair& p : cmp.pairs) {
        const std::string where = std::string(fw::to_string(c.type)) + " designed at " + std::to_string(c.design_hz) +
                                  " Hz, " + std::to_string(distance_mm) + " mm, seed " + std::to_string(p.seed);
        ASSERT_GT(p.unshaped.residual_pp_um, 100.0) << where << ": the unshaped move must excite the mode (um p-p)";
        EXPECT_LE(p.residual_ratio(), c.max_residual_ratio)
            << where << ": tool residual " << p.shaped.residual_pp_um << " um p-p shaped vs "
            << p.unshaped.residual_pp_um << " um unshaped";
        EXPECT_LT(p.shaped.max_following_error_um, 50.0) << where << ": following error (um)";
        worst_ratio = std::max(worst_ratio, p.residual_ratio());
        settling_ratios.push_back(p.settling_ratio().value_or(0.0));
      }
    }
    const double settling = median(settling_ratios);
    if (c.settling_checked && !tnv::test::kSanitizedBuild) {
      EXPECT_GE(settling, 3.0) << fw::to_string(c.type) << ": median unshaped / shaped settling time to +-1 um over "
                               << settling_ratios.size() << " runs";
    }
    RecordProperty(
        std::string(fw::to_string(c.type)) + "_" + std::to_string(static_cast<int>(c.design_hz * 10)) + "_worst_ratio",
        std::to_string(worst_ratio));
    RecordProperty(
        std::string(fw::to_string(c.type)) + "_" + std::to_string(static_cast<int>(c.design_hz * 10)) + "_settling_x",
        std::to_string(settling));
  }
}

// An operator jog stream (held rows, then silence: the dead man stops the
// last jog) through the real-time shaper: it ends exactly where the
// unshaped stream does, and leaves much less vibration at the tool.
TEST(ShaperFlex30, JogStreamEndsWhereItWouldAndRingsLess) {
  std::string error;
  const auto commands =
      parse_jog_csv("t_s,x_mm_s,y_mm_s,z_mm_s\n0,40,0,0\n0.3,0,0,0\n0.5,-25,0,0\n0.75,0,10,0\n0.9,0,0,0\n1.2,20,0,0\n", error);
  ASSERT_TRUE(commands) << error;
  JogRunRequest request;
  request.scenario = *emu::builtin_scenario("flex-30");
  request.commands = *commands;
  // A stiff jog: 1000 mm/s^2 along the path and a jerk limit high enough
  // that the planner's jerk filter is a single tap, so the jog's speed
  // ramps are as sharp as a pendant's without a planner and ring the mode.
  fw::FirmwareConfig config = fw::default_firmware_config();
  for (fw::AxisConfig& a : config.axis) a.path = {100.0, 2000.0, 4e6};
  const JogRunResult unshaped = run_jog(request, config);
  request.shaper[0] = fw::ShaperSpec{fw::ShaperType::zvd, {30.0, 0.02}, {0.0, 0.0}};
  const JogRunResult shaped = run_jog(request, config);
  ASSERT_TRUE(unshaped.completed) << unshaped.error;
  ASSERT_TRUE(shaped.completed) << shaped.error;
  EXPECT_EQ(shaped.deadman_stops, 1u) << "the last row is stopped by the dead man";
  EXPECT_EQ(shaped.refused_commands, 0u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(shaped.axis[i].end_mm, unshaped.axis[i].end_mm) << "axis " << i << ": end point (mm)";
    EXPECT_EQ(shaped.axis[i].end_mm, shaped.axis[i].unshaped_end_mm);
  }
  EXPECT_GT(shaped.axis[0].shaper_delay_s, 0.0);
  EXPECT_EQ(shaped.axis[1].shaper_delay_s, shaped.axis[0].shaper_delay_s) << "y runs x's shaper: in step";
  EXPECT_GT(unshaped.axis[0].residual_pp_um, 20.0) << "um p-p: the unshaped jog rings the mode";
  EXPECT_LT(shaped.axis[0].residual_pp_um, 0.2 * unshaped.axis[0].residual_pp_um)
      << "tool residual after the stop, um p-p: shaped " << shaped.axis[0].residual_pp_um << " vs unshaped "
      << unshaped.axis[0].residual_pp_um;
}

TEST(ShaperJogCsv, RefusesBadFilesWithTheLineAndField) {
  std::string error;
  EXPECT_FALSE(parse_jog_csv("", error));
  EXPECT_FALSE(parse_jog_csv("t,x,y\n0,1,2\n", error));
  EXPECT_EQ(error, "line 1: header must be " + jog_csv_header());
  EXPECT_FALSE(parse_jog_csv("t_s,x_mm_s,y_mm_s,z_mm_s\n0,1,2,0\n0.5,nan,0,0\n", error));
  EXPECT_EQ(error, "line 3: x_mm_s is not a finite number");
  EXPECT_FALSE(parse_jog_csv("t_s,x_mm_s,y_mm_s,z_mm_s\n0.5,1,2,0\n0.5,0,0,0\n", error));
  EXPECT_NE(error.find("line 3: t_s must increase"), std::string::npos) << error;
  EXPECT_FALSE(parse_jog_csv("t_s,x_mm_s,y_mm_s,z_mm_s\n0,1\n", error));
  EXPECT_NE(error.find("expected 4 fields"), std::string::npos) << error;
  const auto ok = parse_jog_csv("# comment\nt_s,x_mm_s,y_mm_s,z_mm_s\r\n0,1.5,-2,0\r\n\n1,0,0,0\n", error);
  ASSERT_TRUE(ok) << error;
  ASSERT_EQ(ok->size(), 2u);
  EXPECT_EQ((*ok)[0].speed_mm_s[1], -2.0);
}

}  // namespace
}  // namespace tnv::hil
