// `tnv-hil shaper` as a script sees it: the JSON keys, the taps
// implemented on the grid, and refusal of bad input with exit code 2.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/tools/cli_runner.hpp"

namespace tnv {
namespace {

TEST(ShaperCli, DesignPrintsImpulsesTapsDelayResidualAndBand) {
  const test::CliRun r = test::run_tnv_hil("shaper design --type zvd --freq-hz 30 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"impulses", "taps", "delay_s", "residual", "band_5pct"}) EXPECT_TRUE(j.contains(key)) << key;
  ASSERT_EQ(j["impulses"].size(), 3u) << "ZVD has three impulses";
  EXPECT_NEAR(j["impulses"][1]["t_s"].get<double>(), 1.0 / 60.0, 1e-12) << "half the 30 Hz period";
  double tap_sum = 0.0;
  for (const auto& tap : j["taps"]) tap_sum += tap["a"].get<double>();
  EXPECT_NEAR(tap_sum, 1.0, 1e-12) << "the taps keep the move length";
  EXPECT_NEAR(j["delay_s"].get<double>(), 1.0 / 60.0, 1e-3) << "ZVD delay is half a period, s";
  bool saw_design_point = false;
  for (const auto& row : j["residual"]) {
    if (std::abs(row["ratio"].get<double>() - 1.0) < 1e-9) {
      saw_design_point = true;
      EXPECT_LT(row["percent"].get<double>(), 0.5) << "residual of the grid taps at the design frequency, %";
    }
  }
  EXPECT_TRUE(saw_design_point);
  EXPECT_GT(j["band_5pct"].get<double>(), 0.2);
}

TEST(ShaperCli, BadFrequencyOrTypeIsRefusedWithExitCode2) {
  for (const char* args : {"shaper design --type zvd --freq-hz -5", "shaper design --type zvd --freq-hz nan",
                           "shaper design --type zzz --freq-hz 30"}) {
    const test::CliRun r = test::run_tnv_hil(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_TRUE(r.out.empty()) << args << ": " << r.out;
    EXPECT_FALSE(r.err.empty()) << args;
  }
}

}  // namespace
}  // namespace tnv
