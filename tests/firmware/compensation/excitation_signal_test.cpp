// Frequency-response excitations (issue 17): the multisine's tones, its
// period and power, the log sweep's frequency law, the generator's sweep /
// multisine kinds and their validation.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "firmware/compensation/excitation.hpp"
#include "firmware/compensation/excitation_signal.hpp"

namespace tnv::fw {
namespace {

constexpr double kSignalTickS = 1e-3;

TEST(ExcitationSignal, MultisineTonesAreDistinctHarmonicsInsideTheBand) {
  const MultisineTones t = multisine_tones(1.0, 100.0, 40, kSignalTickS);
  ASSERT_EQ(t.count, 40u);
  EXPECT_EQ(t.period_ticks, 1000);  // 1 / f_min
  for (std::uint32_t i = 0; i < t.count; ++i) {
    const double f_hz = t.harmonic[i] / (static_cast<double>(t.period_ticks) * kSignalTickS);
    EXPECT_GE(f_hz, 1.0 - 1e-9) << "tone " << i;
    EXPECT_LE(f_hz, 100.0 + 1e-9) << "tone " << i;
    if (i > 0) {
      EXPECT_GT(t.harmonic[i], t.harmonic[i - 1]) << "tone " << i << " not above its predecessor";
    }
  }
  EXPECT_EQ(t.harmonic[0], 1);
  EXPECT_EQ(t.harmonic[39], 100);
  // Log spacing at the top: the last steps grow with frequency.
  EXPECT_GT(t.harmonic[39] - t.harmonic[38], t.harmonic[10] - t.harmonic[9]);
}

TEST(ExcitationSignal, TooManyTonesForTheBandGiveNone) {
  EXPECT_EQ(multisine_tone_capacity(10.0, 50.0, kSignalTickS), 5u);  // 10, 20, 30, 40, 50 Hz
  EXPECT_EQ(multisine_tones(10.0, 50.0, 6, kSignalTickS).count, 0u);
  EXPECT_EQ(multisine_tones(10.0, 50.0, 5, kSignalTickS).count, 5u);
  EXPECT_EQ(multisine_tones(1.0, 100.0, kMaxMultisineTones + 1, kSignalTickS).count, 0u);
  EXPECT_EQ(multisine_tone_capacity(50.0, 10.0, kSignalTickS), 0u);
  EXPECT_EQ(multisine_tone_capacity(std::numeric_limits<double>::quiet_NaN(), 10.0, kSignalTickS), 0u);
}

TEST(ExcitationSignal, MultisineRepeatsEveryPeriodWithTheRequestedRms) {
  Multisine m;
  const MultisineTones t = multisine_tones(5.0, 200.0, 30, kSignalTickS);
  ASSERT_EQ(t.count, 30u);
  m.start(t, 2.0);
  double sum_sq = 0.0, peak = 0.0;
  for (std::int64_t k = 0; k < t.period_ticks; ++k) {
    const double d = m.sample(k);
    EXPECT_NEAR(m.sample(k + 7 * t.period_ticks), d, 1e-9) << "tick " << k << " differs 7 periods later";
    sum_sq += d * d;
    peak = std::fmax(peak, std::fabs(d));
  }
  EXPECT_NEAR(std::sqrt(sum_sq / static_cast<double>(t.period_ticks)), 2.0, 1e-9) << "mm/s RMS";
  // Schroeder phases: a crest factor far below the sqrt(2 N) = 7.7 of aligned phases.
  EXPECT_LT(peak / 2.0, 2.5) << "crest factor";
}

TEST(ExcitationSignal, LogSweepStartsAtZeroAndSweepsItsBand) {
  LogSweep s;
  s.start(2.0, 200.0, 4.0, 3.0, kSignalTickS);
  EXPECT_EQ(s.sample(0), 0.0);
  // Zero crossings near t count half periods of the instantaneous frequency f(t) = 2 * 100^(t/4).
  auto crossings = [&](std::int64_t k0, std::int64_t k1) {
    int n = 0;
    for (std::int64_t k = k0 + 1; k < k1; ++k) n += (s.sample(k - 1) < 0.0) != (s.sample(k) < 0.0);
    return n;
  };
  const double f_at_2s = 2.0 * std::pow(100.0, 0.5);  // 20 Hz
  EXPECT_NEAR(crossings(1900, 2100), 2.0 * f_at_2s * 0.2, 1.5) << "zero crossings in 0.2 s around t = 2 s";
  double peak = 0.0;
  for (std::int64_t k = 0; k < 4000; ++k) peak = std::fmax(peak, std::fabs(s.sample(k)));
  EXPECT_LE(peak, 3.0);
  EXPECT_GT(peak, 2.9);
}

ExcitationSpec banded_spec(ExcitationKind kind) {
  ExcitationSpec s;
  s.kind = kind;
  s.level_mm_s = 2.0;
  s.duration_s = 3.0;
  s.settle_s = 0.01;
  s.f_min_hz = 1.0;
  s.f_max_hz = 100.0;
  s.tones = 40;
  return s;
}

TEST(ExcitationSignal, GeneratorRunsWholeMultisinePeriodsThenSettles) {
  ExcitationSpec spec = banded_spec(ExcitationKind::multisine);
  spec.duration_s = 2.5;  // 2 whole periods of 1 s
  ExcitationGenerator gen;
  gen.start(spec);
  EXPECT_TRUE(gen.closed_loop());
  EXPECT_EQ(gen.drive_ticks(), 2000);
  Multisine reference;
  reference.start(multisine_tones(1.0, 100.0, 40, kSignalTickS), 2.0 / std::sqrt(2.0));
  for (std::int64_t k = 0; k < 2000; ++k) ASSERT_DOUBLE_EQ(gen.next(0), reference.sample(k)) << "tick " << k;
  int zeros = 0;
  while (gen.active()) {
    ASSERT_EQ(gen.next(0), 0.0);
    ASSERT_LT(++zeros, 100);
  }
  EXPECT_EQ(zeros, 11);  // the stop tick and 10 settle ticks
  ExcitationGenerator open;
  open.start(banded_spec(ExcitationKind::multisine_open));
  EXPECT_FALSE(open.closed_loop());
}

TEST(ExcitationSignal, ValidationNamesTheOffendingField) {
  EXPECT_TRUE(validate(banded_spec(ExcitationKind::sweep)).ok);
  EXPECT_TRUE(validate(banded_spec(ExcitationKind::multisine)).ok);
  EXPECT_TRUE(validate(banded_spec(ExcitationKind::multisine_open)).ok);
  struct Bad {
    const char* field;
    ExcitationSpec spec;
  };
  auto with = [](ExcitationKind k, auto change) {
    ExcitationSpec s = banded_spec(k);
    change(s);
    return s;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Bad cases[] = {
      {"f_min_hz", with(ExcitationKind::sweep, [&](ExcitationSpec& s) { s.f_min_hz = nan; })},
      {"f_min_hz", with(ExcitationKind::sweep, [](ExcitationSpec& s) { s.f_min_hz = 0.01; })},
      {"f_max_hz", with(ExcitationKind::sweep, [](ExcitationSpec& s) { s.f_max_hz = 0.5; })},
      {"f_max_hz", with(ExcitationKind::multisine, [](ExcitationSpec& s) { s.f_max_hz = 500.0; })},
      {"duration_s", with(ExcitationKind::sweep, [](ExcitationSpec& s) { s.duration_s = 41.0; })},
      {"duration_s", with(ExcitationKind::multisine, [](ExcitationSpec& s) { s.duration_s = 1.5; })},
      {"tones", with(ExcitationKind::multisine, [](ExcitationSpec& s) { s.tones = 0; })},
      {"tones", with(ExcitationKind::multisine_open, [](ExcitationSpec& s) { s.tones = 65; })},
      {"tones", with(ExcitationKind::multisine, [](ExcitationSpec& s) {
         s.f_min_hz = 10.0;
         s.f_max_hz = 50.0;
         s.tones = 6;
       })},
      {"level_mm_s", with(ExcitationKind::multisine, [&](ExcitationSpec& s) { s.level_mm_s = nan; })},
      {"kind", with(ExcitationKind::sweep, [](ExcitationSpec& s) { s.kind = static_cast<ExcitationKind>(5); })},
  };
  for (const Bad& c : cases) {
    const ParamCheck r = validate(c.spec);
    EXPECT_FALSE(r.ok) << c.field;
    EXPECT_STREQ(r.field, c.field);
  }
}

}  // namespace
}  // namespace tnv::fw
