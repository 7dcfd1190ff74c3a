#include "firmware/io/dac_code.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace tnv::fw {
namespace {

TEST(DacCode, ReferencePlantScaleIs0p08138MmPerSecondPerLsb) {
  const DacScale scale;
  EXPECT_NEAR(scale.lsb_mm_s(), 0.08138, 5e-6);
  EXPECT_EQ(scale.mid_code(), 2048);
  EXPECT_EQ(scale.max_code(), 4095);
}

TEST(DacCode, ZeroSpeedIsMidScaleAndCodesRoundToNearest) {
  const DacScale scale;
  EXPECT_EQ(speed_to_dac_code(0.0, scale), 2048);
  EXPECT_EQ(speed_to_dac_code(0.49 * scale.lsb_mm_s(), scale), 2048);
  EXPECT_EQ(speed_to_dac_code(0.51 * scale.lsb_mm_s(), scale), 2049);
  EXPECT_EQ(speed_to_dac_code(-1.51 * scale.lsb_mm_s(), scale), 2046);
  EXPECT_NEAR(dac_code_to_speed_mm_s(speed_to_dac_code(2.0, scale), scale), 2.0, scale.lsb_mm_s() / 2);
}

TEST(DacCode, SaturatesAtBothEnds) {
  const DacScale scale;
  EXPECT_EQ(speed_to_dac_code(1e6, scale), 4095);
  EXPECT_EQ(speed_to_dac_code(-1e6, scale), 0);
  EXPECT_EQ(speed_to_dac_code(-scale.full_scale_mm_s, scale), 0);  // -10 V is code 0
  EXPECT_EQ(speed_to_dac_code(scale.full_scale_mm_s, scale), 4095);  // +10 V is one LSB beyond the top
  EXPECT_NEAR(dac_code_to_speed_mm_s(0, scale), -166.6667, 1e-3);
}

TEST(DacCode, NonFiniteCommandGivesZeroVolts) {
  const DacScale scale;
  EXPECT_EQ(speed_to_dac_code(std::numeric_limits<double>::quiet_NaN(), scale), 2048);
  EXPECT_EQ(speed_to_dac_code(std::numeric_limits<double>::infinity(), scale), 2048);
}

}  // namespace
}  // namespace tnv::fw
