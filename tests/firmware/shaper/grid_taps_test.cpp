// Issue item 2, over the whole sweep: the taps as implemented on the 1 kHz
// grid leave <= 0.5 % residual vibration at the design frequency for every
// frequency from 5 to 200 Hz in 0.5 Hz steps and zeta in {0, 0.05, 0.1},
// sum to 1, and keep a 5 % band no narrower than the continuous shaper's
// by more than 10 %; and no tap is negative. EI is designed to leave its 5 % tolerance at the
// design frequency; for it the grid may add at most 0.5 points to the
// continuous shaper's residual there.
#include "firmware/shaper/grid_taps.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "firmware/shaper/residual_vibration.hpp"
#include "firmware/shaper/shaper_design.hpp"
#include "tests/firmware/test_units.hpp"

namespace tnv::fw {
namespace {

using test_units::kPeriodS;

// One test: 391 frequencies x 3 damping ratios x 5 types, each with two
// band searches. Failures are counted and the first few reported.
TEST(GridTaps, ExactOnTheGridOverTheWholeSweep) {
  int points = 0, failures = 0;
  double worst_residual = 0.0, worst_band_ratio = 10.0, worst_sum_error = 0.0;
  for (ShaperType type : kShaperTypes) {
    for (double zeta : {0.0, 0.05, 0.1}) {
      for (int i = 0; i <= 390; ++i) {
        const double f = 5.0 + 0.5 * i;
        const ModeSpec mode{f, zeta};
        const ImpulseTrain cont = design_impulses(type, mode);
        const TapSet taps = exact_grid_taps(type, mode, kPeriodS);
        ++points;
        const double v_grid = residual_vibration(taps, kPeriodS, f, zeta);
        const double v_cont = residual_vibration(cont, f, zeta);
        const double excess = zero_at_design_point(type) ? v_grid : v_grid - v_cont;
        const double sum_error = std::fabs(taps.sum() - 1.0);
        double min_tap = 1.0;
        for (std::size_t j = 0; j < taps.count; ++j) min_tap = std::fmin(min_tap, taps.tap[j].a);
        // The band is defined for V <= 5 %; EI sits at its tolerance at the
        // design point (exactly, undamped), so allow rounding there.
        const double band_cont = insensitivity_band(cont, f, zeta, 0.05 + 1e-9).width();
        const double band_grid = insensitivity_band(taps, kPeriodS, f, zeta, 0.05 + 1e-9).width();
        worst_residual = std::fmax(worst_residual, excess);
        worst_sum_error = std::fmax(worst_sum_error, sum_error);
        worst_band_ratio = std::fmin(worst_band_ratio, band_grid / band_cont);
        const bool ok = excess <= 0.005 && sum_error <= 1e-12 && band_grid >= 0.9 * band_cont && min_tap >= 0.0;
        if (!ok && ++failures <= 5)
          ADD_FAILURE() << to_string(type) << " at " << f << " Hz, zeta " << zeta << ": residual at the design point "
                        << 100.0 * v_grid << " % (continuous " << 100.0 * v_cont << " %), taps sum to " << taps.sum()
                        << ", 5 % band " << band_grid << " of the design frequency vs continuous " << band_cont
                        << ", smallest tap " << min_tap;
      }
    }
  }
  EXPECT_EQ(points, 5 * 3 * 391);
  EXPECT_EQ(failures, 0);
  RecordProperty("worst_residual_percent", std::to_string(100.0 * worst_residual));
  RecordProperty("worst_band_ratio", std::to_string(worst_band_ratio));
  RecordProperty("worst_sum_error", std::to_string(worst_sum_error));
}

// The sweep above also checks that no tap is negative (a shaped move never
// backs up); here the same at the most damped design allowed.
TEST(GridTaps, TapsAreNonNegativeAtTheHighestDamping) {
  for (ShaperType type : kShaperTypes)
    for (double zeta : {kShaperMaxZeta})
      for (double f = 5.0; f <= 200.0; f += 0.5) {
        const TapSet taps = exact_grid_taps(type, {f, zeta}, kPeriodS);
        for (std::size_t j = 0; j < taps.count; ++j)
          ASSERT_GE(taps.tap[j].a, 0.0) << to_string(type) << " at " << f << " Hz, zeta " << zeta << ": tap "
                                        << taps.tap[j].k;
      }
}

// The two naive ways the method is measured against (issue item 2): rounding
// leaves ~15 % near 100 Hz, splitting 2-3 %, the exact taps nothing.
TEST(GridTaps, RoundingAndSplittingLeaveWhatTheIssueSays) {
  double round_max = 0.0, split_max = 0.0, exact_max = 0.0;
  for (double f = 90.0; f <= 110.0; f += 0.5) {
    const ImpulseTrain zv = design_impulses(ShaperType::zv, {f, 0.0});
    round_max = std::fmax(round_max, residual_vibration(round_to_grid(zv, kPeriodS), kPeriodS, f, 0.0));
    split_max = std::fmax(split_max, residual_vibration(split_to_grid(zv, kPeriodS), kPeriodS, f, 0.0));
    exact_max =
        std::fmax(exact_max, residual_vibration(exact_grid_taps(ShaperType::zv, {f, 0.0}, kPeriodS), kPeriodS, f, 0.0));
  }
  EXPECT_GT(round_max, 0.12) << "rounding ZV near 100 Hz";
  EXPECT_LT(round_max, 0.17) << "rounding ZV near 100 Hz";
  EXPECT_GT(split_max, 0.015) << "splitting ZV near 100 Hz";
  EXPECT_LT(split_max, 0.035) << "splitting ZV near 100 Hz";
  EXPECT_LT(exact_max, 1e-12);
}

TEST(GridTaps, OnGridImpulsesStayWhereTheyAre) {
  // 100 Hz ZV: impulses at 0 and 5 ms, already on the grid.
  const TapSet taps = exact_grid_taps(ShaperType::zv, {100.0, 0.0}, kPeriodS);
  ASSERT_EQ(taps.count, 2u);
  EXPECT_EQ(taps.tap[1].k, 5u);
  EXPECT_NEAR(taps.tap[0].a, 0.5, 1e-12);
  EXPECT_NEAR(taps.tap[1].a, 0.5, 1e-12);
}

TEST(ShaperDesign, TwoModeShaperCancelsBothModes) {
  for (ShaperType type : kShaperTypes) {
    const ShaperSpec spec{type, {30.0, 0.02}, {100.0, 0.02}};
    ASSERT_TRUE(validate(spec).ok);
    const ShaperDesign d = design_shaper(spec, kPeriodS);
    EXPECT_NEAR(d.taps.sum(), 1.0, 1e-12) << to_string(type);
    for (double f : {30.0, 100.0}) {
      const double v_grid = residual_vibration(d.taps, kPeriodS, f, 0.02);
      const double v_cont = residual_vibration(d.impulses, f, 0.02);
      if (zero_at_design_point(type)) {
        EXPECT_LT(v_grid, 1e-9) << to_string(type) << " two-mode taps at " << f << " Hz";
        EXPECT_LT(v_cont, 1e-9) << to_string(type) << " two-mode impulses at " << f << " Hz";
      } else {
        EXPECT_LT(v_grid, 0.05) << "EI two-mode taps at " << f << " Hz";
      }
    }
    // A single-mode shaper at 30 Hz leaves the 100 Hz mode largely alone.
    const ShaperDesign one = design_shaper({type, {30.0, 0.02}, {0.0, 0.0}}, kPeriodS);
    EXPECT_GT(residual_vibration(one.taps, kPeriodS, 100.0, 0.02), 0.05) << to_string(type);
    EXPECT_NEAR(d.delay_s(), one.delay_s() + design_shaper({type, {100.0, 0.02}, {0.0, 0.0}}, kPeriodS).delay_s(),
                1e-12)
        << "delays of shapers in series add";
  }
}

TEST(ShaperDesign, ValidationNamesTheField) {
  EXPECT_STREQ(validate(ShaperSpec{ShaperType::zv, {3.0, 0.0}, {0.0, 0.0}}).field, "mode.freq_hz");
  EXPECT_STREQ(validate(ShaperSpec{ShaperType::zv, {30.0, 0.5}, {0.0, 0.0}}).field, "mode.zeta");
  EXPECT_STREQ(validate(ShaperSpec{ShaperType::zv, {30.0, 0.0}, {250.0, 0.0}}).field, "second_mode.freq_hz");
  EXPECT_STREQ(validate(ShaperSpec{ShaperType::zv, {30.0, 0.0}, {std::nan(""), 0.0}}).field, "second_mode.freq_hz");
  EXPECT_STREQ(validate(ShaperSpec{ShaperType::zv, {30.0, 0.0}, {100.0, -1.0}}).field, "second_mode.zeta");
  EXPECT_STREQ(validate(ShaperSpec{static_cast<ShaperType>(9), {30.0, 0.0}, {0.0, 0.0}}).field, "type");
}

TEST(ShaperDesign, TheLongestShaperFitsTheRing) {
  const ShaperDesign d = design_shaper(
      {ShaperType::zvdd, {kShaperMinFreqHz, kShaperMaxZeta}, {kShaperMinFreqHz, kShaperMaxZeta}}, kPeriodS);
  EXPECT_LT(d.taps.span(), 1024u);
  EXPECT_GT(d.taps.span(), 600u);
  EXPECT_LE(d.taps.count, TapSet::kCapacity);
}

}  // namespace
}  // namespace tnv::fw
