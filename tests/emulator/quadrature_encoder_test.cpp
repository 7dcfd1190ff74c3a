#include "emulator/quadrature_encoder.hpp"

#include <gtest/gtest.h>

namespace tnv::emu {
namespace {

constexpr double kQ_mm = 10.0 / 24000.0;  // 0.41667 um

TEST(QuadratureEncoder, RoundsToTheNearestCount) {
  const QuadratureEncoder encoder(kQ_mm, 0.0);
  EXPECT_EQ(encoder.count(0.0), 0);
  EXPECT_EQ(encoder.count(0.49 * kQ_mm), 0);
  EXPECT_EQ(encoder.count(0.51 * kQ_mm), 1);
  EXPECT_EQ(encoder.count(-0.51 * kQ_mm), -1);
  EXPECT_EQ(encoder.count(6.0), 14'400) << "6 mm = 14,400 counts";
  EXPECT_EQ(encoder.count(10.0), 24'000) << "one lead = one motor revolution";
}

TEST(QuadratureEncoder, OffsetShiftsTheQuantisationPhase) {
  const QuadratureEncoder encoder(kQ_mm, 0.3);
  EXPECT_EQ(encoder.count(0.25 * kQ_mm), 1);  // 0.25 + 0.3 = 0.55
  EXPECT_EQ(encoder.count(0.15 * kQ_mm), 0);  // 0.45
}

TEST(QuadratureEncoder, RegisterWrapsAt16Bits) {
  const QuadratureEncoder encoder(kQ_mm, 0.0);
  EXPECT_EQ(encoder.register_value(-kQ_mm), 0xFFFFu) << "-1 count";
  EXPECT_EQ(QuadratureEncoder::wrap(32'768), 0x8000u);
  EXPECT_EQ(QuadratureEncoder::wrap(65'536), 0u);
  EXPECT_EQ(QuadratureEncoder::wrap(65'537), 1u);
  EXPECT_EQ(QuadratureEncoder::wrap(-65'536), 0u);
  EXPECT_EQ(encoder.register_value(30.0), static_cast<std::uint32_t>(72'000 % 65'536)) << "30 mm = 72,000 counts";
}

}  // namespace
}  // namespace tnv::emu
