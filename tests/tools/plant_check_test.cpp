#include "tools/hil/plant_check.hpp"

#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "tools/hil/report.hpp"

namespace tnv::hil {
namespace {

TEST(PlantCheck, SubSteppedPlantEqualsTheExactZohModelTo1eMinus6) {
  const auto axes = plant_check(*emu::builtin_scenario("no-cut"));
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_LT(axes[i].max_abs_diff_exact, 1e-6) << "axis " << i;
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) EXPECT_NEAR(axes[i].identified.A(r, c), axes[i].exact.A(r, c), 1e-6);
      EXPECT_NEAR(axes[i].identified.B(r), axes[i].exact.B(r), 1e-6);
    }
  }
  // Reference plant's printed values; the paper's eq. (31) is these rounded.
  EXPECT_NEAR(axes[0].identified.A(0, 1), 0.0009123, 5e-8);
  EXPECT_NEAR(axes[1].identified.A(0, 1), 0.0009330, 5e-8);
  EXPECT_NEAR(axes[0].identified.A(1, 1), 0.8298, 5e-5);
  EXPECT_NEAR(axes[1].identified.A(1, 1), 0.8690, 5e-5);
  EXPECT_NEAR(axes[0].identified.B(0), 0.0000877, 5e-8);
  EXPECT_NEAR(axes[1].identified.B(0), 0.0000670, 5e-8);
  EXPECT_NEAR(axes[0].paper.A(1, 1), axes[0].identified.A(1, 1), 5e-5);
}

TEST(PlantCheck, FollowsTheScenarioNotAHardCodedPlant) {
  emu::Scenario s = *emu::builtin_scenario("no-cut");
  s.plant[0].tau_s = 0.010;
  s.plant[0].gain = 0.8;
  const auto axes = plant_check(s);
  EXPECT_NEAR(axes[0].identified.A(1, 1), std::exp(-0.1), 1e-9);
  EXPECT_NEAR(axes[0].identified.B(1), 0.8 * (1.0 - std::exp(-0.1)), 1e-9);
  EXPECT_LT(axes[0].max_abs_diff_exact, 1e-6);
}

TEST(PlantCheck, JsonHasTheDocumentedShape) {
  const nlohmann::json j = plant_check_json(plant_check(*emu::builtin_scenario("no-cut")));
  for (const char* axis : {"x", "y"}) {
    ASSERT_TRUE(j.contains(axis));
    EXPECT_EQ(j[axis]["A"].size(), 2u);
    EXPECT_EQ(j[axis]["A"][0].size(), 2u);
    EXPECT_EQ(j[axis]["B"].size(), 2u);
    EXPECT_TRUE(j[axis]["exact"].contains("A"));
    EXPECT_TRUE(j[axis]["paper"].contains("B"));
  }
  EXPECT_NEAR(j["y"]["A"][1][1].get<double>(), 0.8690, 5e-5);
}

}  // namespace
}  // namespace tnv::hil
