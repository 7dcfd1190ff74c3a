// `tnv-hil shaper design --json`: the keys the issue specifies, consistent
// with the firmware's design.
#include <gtest/gtest.h>

#include <cmath>

#include "firmware/shaper/residual_vibration.hpp"
#include "tools/hil/shaper_design_report.hpp"

namespace tnv::hil {
namespace {

TEST(ShaperDesignReport, JsonHasTheIssueKeysAndTheFirmwareNumbers) {
  const fw::ShaperSpec spec{fw::ShaperType::zvdd, {30.0, 0.02}, {0.0, 0.0}};
  const nlohmann::json j = shaper_design_json(spec);
  for (const char* key : {"impulses", "taps", "delay_s", "residual", "band_5pct"}) ASSERT_TRUE(j.contains(key)) << key;
  const fw::ShaperDesign d = fw::design_shaper(spec, kShaperPeriodS);
  ASSERT_EQ(j["impulses"].size(), 4u);
  EXPECT_DOUBLE_EQ(j["impulses"][1]["t_s"].get<double>(), d.impulses.impulse[1].t_s);
  EXPECT_DOUBLE_EQ(j["impulses"][1]["a"].get<double>(), d.impulses.impulse[1].a);
  ASSERT_EQ(j["taps"].size(), d.taps.count);
  double sum = 0.0;
  for (const auto& t : j["taps"]) sum += t["a"].get<double>();
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_DOUBLE_EQ(j["delay_s"].get<double>(), d.delay_s());
  const auto& residual = j["residual"];
  ASSERT_EQ(residual.size(), 21u) << "ratios 0.5 .. 1.5 in 0.05 steps";
  EXPECT_DOUBLE_EQ(residual[0]["ratio"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(residual[20]["ratio"].get<double>(), 1.5);
  EXPECT_LT(residual[10]["percent"].get<double>(), 1e-9) << "design point";
  EXPECT_NEAR(residual[6]["percent"].get<double>(),
              100.0 * fw::residual_vibration(d.taps, kShaperPeriodS, 0.8 * 30.0, 0.02), 1e-9);
  const double band = j["band_5pct"].get<double>();
  EXPECT_GT(band, 0.4);
  EXPECT_LT(band, 0.6);
  EXPECT_TRUE(j["freq2_hz"].is_null());
  EXPECT_FALSE(j.contains("residual_second_mode"));
}

TEST(ShaperDesignReport, TwoModesReportTheSecondMode) {
  const nlohmann::json j = shaper_design_json({fw::ShaperType::zv, {30.0, 0.0}, {100.0, 0.0}});
  EXPECT_EQ(j["freq2_hz"].get<double>(), 100.0);
  ASSERT_TRUE(j.contains("residual_second_mode"));
  EXPECT_LT(j["residual_second_mode"][10]["percent"].get<double>(), 1e-9);
  EXPECT_LT(j["residual"][10]["percent"].get<double>(), 1e-9);
  EXPECT_EQ(j["impulses"].size(), 4u);
}

TEST(ShaperDesignReport, TextNamesTheShaper) {
  const std::string text = shaper_design_text({fw::ShaperType::mzv, {45.0, 0.05}, {0.0, 0.0}});
  EXPECT_NE(text.find("mzv shaper, 45 Hz, zeta 0.05"), std::string::npos) << text;
  EXPECT_NE(text.find("5% band"), std::string::npos);
}

}  // namespace
}  // namespace tnv::hil
