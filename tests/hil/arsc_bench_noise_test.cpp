// The S3 study under a scenario's measurement noise (tnv-hil arsc compare
// --scenario): the force the loop reads carries the force ADC's noise,
// referred to the normalised force through the sensor's volts per N and
// f* = 150 N. The robust ARSC must keep the paper's 10 % on the four pole
// sets at the bench's noise; a scenario without noise must leave the study
// bit for bit as it was.
#include <gtest/gtest.h>

#include <cmath>

#include "emulator/scenario_file.hpp"
#include "tools/hil/arsc_run.hpp"

namespace tnv::hil {
namespace {

using fw::arsc::PoleSet;

constexpr PoleSet kSets[] = {PoleSet::case1, PoleSet::case2, PoleSet::case3, PoleSet::case4};

ArscForceNoise bench_noise() {
  const ArscScenarioNoise n = arsc_force_noise(*emu::builtin_scenario("bench-no-cut"));
  EXPECT_TRUE(n.error.empty()) << n.error;
  return n.noise;
}

TEST(ArscBenchNoise, TheBenchForceNoiseIsTheAdcNoiseOverTheSensorScaleAndTheReference) {
  // 0.004 V rms at the ADC / (1/30 V per N) = 0.12 N; f* = 1 is 150 N.
  EXPECT_NEAR(bench_noise().rms, 0.004 * 30.0 / 150.0, 1e-15);
  EXPECT_EQ(bench_noise().seed, 1u);
  emu::Scenario s = *emu::builtin_scenario("bench-no-cut");
  s.force_sensor.volts_per_n = 2.0 / 30.0;  // a sensor twice as sensitive: half the noise in N
  EXPECT_NEAR(arsc_force_noise(s).noise.rms, 0.5 * 0.004 * 30.0 / 150.0, 1e-15);
  s.force_sensor.volts_per_n = 0.0;
  EXPECT_FALSE(arsc_force_noise(s).error.empty()) << "a sensor of 0 V/N reads only noise";
  EXPECT_EQ(arsc_force_noise(*emu::builtin_scenario("no-cut")).noise.rms, 0.0);
}

TEST(ArscBenchNoise, RobustVariantHoldsTenPercentOnAllFourPoleSetsAtTheBenchNoise) {
  for (PoleSet set : kSets) {
    ArscRunConfig c;
    c.poles = set;
    c.variant = ArscVariant::robust;
    c.force_noise = bench_noise();
    const ArscSeedSweep s = run_arsc_seeds(c, 8);
    EXPECT_EQ(s.diverged_runs, 0) << fw::arsc::to_string(set);
    EXPECT_LT(s.force_error_max_pct_worst, 10.0)
        << fw::arsc::to_string(set) << ": worst peak-force error after 3 s over 8 noise seeds, % of f*";
  }
}

void expect_same_run(const ArscRunResult& a, const ArscRunResult& b, const char* what) {
  ASSERT_EQ(a.trace.size(), b.trace.size()) << what;
  for (std::size_t i = 0; i < a.trace.size(); ++i) {
    ASSERT_EQ(a.trace[i].force, b.trace[i].force) << what << " sample " << i;
    ASSERT_EQ(a.trace[i].force_measured, b.trace[i].force_measured) << what << " sample " << i;
    ASSERT_EQ(a.trace[i].u, b.trace[i].u) << what << " sample " << i;
    ASSERT_EQ(a.trace[i].gains.k, b.trace[i].gains.k) << what << " sample " << i;
    ASSERT_EQ(a.trace[i].cutting_gain, b.trace[i].cutting_gain) << what << " sample " << i;
  }
  EXPECT_EQ(a.force_error_max_pct, b.force_error_max_pct) << what;
  EXPECT_EQ(a.force_error_rms_pct, b.force_error_rms_pct) << what;
}

TEST(ArscBenchNoise, AScenarioWithoutNoiseGivesTheNoiselessRunBitForBit) {
  const ArscScenarioNoise quiet = arsc_force_noise(*emu::builtin_scenario("no-cut"));
  ASSERT_TRUE(quiet.error.empty());
  for (ArscVariant variant : {ArscVariant::robust, ArscVariant::faithful}) {
    ArscRunConfig plain;
    plain.poles = PoleSet::case3;
    plain.variant = variant;
    ArscRunConfig scenario = plain;
    scenario.force_noise = quiet.noise;
    const ArscRunResult a = run_arsc(plain), b = run_arsc(scenario);
    expect_same_run(a, b, to_string(variant));
    for (const ArscTracePoint& p : b.trace) ASSERT_EQ(p.force, p.force_measured);
  }
}

TEST(ArscBenchNoise, TheBenchNoiseReachesTheLoopAndIsSeeded) {
  ArscRunConfig c;
  c.poles = PoleSet::case1;
  c.force_noise = bench_noise();
  const ArscRunResult a = run_arsc(c), again = run_arsc(c);
  expect_same_run(a, again, "the same seed");
  double sum_sq = 0.0;
  for (const ArscTracePoint& p : a.trace) sum_sq += (p.force_measured - p.force) * (p.force_measured - p.force);
  const double rms = std::sqrt(sum_sq / static_cast<double>(a.trace.size()));
  EXPECT_NEAR(rms, c.force_noise.rms, 0.15 * c.force_noise.rms) << "measured minus process force, normalised";
  ArscRunConfig quiet = c;
  quiet.force_noise.rms = 0.0;
  const ArscRunResult q = run_arsc(quiet);
  EXPECT_NE(a.trace.back().cutting_gain, q.trace.back().cutting_gain) << "the estimator saw the noise";
  EXPECT_NE(a.force_error_rms_pct, q.force_error_rms_pct);
  ArscRunConfig other = c;
  other.force_noise.seed += 1;
  EXPECT_NE(run_arsc(other).force_error_rms_pct, a.force_error_rms_pct) << "another seed, another realisation";
}

}  // namespace
}  // namespace tnv::hil
