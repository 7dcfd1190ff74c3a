// The realism keys ([plant] ball screw and current limit, [noise], [io]):
// every key read, every range refused with its reason, NaN refused, off by
// default, and the bench profiles valid.
#include <gtest/gtest.h>

#include <string>

#include "emulator/scenario_file.hpp"
#include "emulator/scenario_validation.hpp"

namespace tnv::emu {
namespace {

constexpr std::string_view kEveryRealismKey = R"(
[plant.x]
backlash_um = 12
lead_error_um_per_m = -40
pitch_error_um = 3
pitch_period_mm = 5
accel_limit_mm_s2 = 9800

[plant.y]
backlash_um = 0.5
lead_error_um_per_m = 60.5
pitch_error_um = 0
pitch_period_mm = 20
accel_limit_mm_s2 = 0

[noise]
seed = 4294967295
force_adc_v_rms = 0.004
accel_g_rms = 0.0006
accel_bias_g = -0.025
dac_offset_v = 0.005
dac_gain_error = -0.002
encoder_glitch_per_s = 0.5
encoder_glitch_counts = 2
bore_gauge_um_rms = 1.5
bore_gauge_resolution_um = 0.5

[io]
read_latency_us = 100
write_latency_us = 50.5
jitter_us = 30
)";

TEST(RealismKeys, EveryKeyIsRead) {
  const ScenarioResult r = parse_scenario_text(kEveryRealismKey, "real.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  const Scenario& s = *r.scenario;
  EXPECT_EQ(s.plant[0].backlash_um, 12.0);
  EXPECT_EQ(s.plant[0].lead_error_um_per_m, -40.0);
  EXPECT_EQ(s.plant[0].pitch_error_um, 3.0);
  EXPECT_EQ(s.plant[0].pitch_period_mm, 5.0);
  EXPECT_EQ(s.plant[0].accel_limit_mm_s2, 9800.0);
  EXPECT_EQ(s.plant[1].backlash_um, 0.5);
  EXPECT_EQ(s.plant[1].lead_error_um_per_m, 60.5);
  EXPECT_EQ(s.plant[1].pitch_period_mm, 20.0);
  EXPECT_EQ(s.plant[1].accel_limit_mm_s2, 0.0);
  EXPECT_EQ(s.noise.seed, 4294967295u);
  EXPECT_EQ(s.noise.force_adc_v_rms, 0.004);
  EXPECT_EQ(s.noise.accel_g_rms, 0.0006);
  EXPECT_EQ(s.noise.accel_bias_g, -0.025);
  EXPECT_EQ(s.noise.dac_offset_v, 0.005);
  EXPECT_EQ(s.noise.dac_gain_error, -0.002);
  EXPECT_EQ(s.noise.encoder_glitch_per_s, 0.5);
  EXPECT_EQ(s.noise.encoder_glitch_counts, 2);
  EXPECT_EQ(s.noise.bore_gauge_um_rms, 1.5);
  EXPECT_EQ(s.noise.bore_gauge_resolution_um, 0.5);
  EXPECT_EQ(s.io.read_latency_us, 100.0);
  EXPECT_EQ(s.io.write_latency_us, 50.5);
  EXPECT_EQ(s.io.jitter_us, 30.0);
  EXPECT_TRUE(s.io.enabled());
  EXPECT_TRUE(s.noise.any_sample_noise());
}

TEST(RealismKeys, AllOffByDefault) {
  const Scenario s;
  for (const AxisPlantParams& p : s.plant) {
    EXPECT_EQ(p.backlash_um, 0.0);
    EXPECT_EQ(p.lead_error_um_per_m, 0.0);
    EXPECT_EQ(p.pitch_error_um, 0.0);
    EXPECT_EQ(p.accel_limit_mm_s2, 0.0);
  }
  EXPECT_FALSE(s.noise.any_sample_noise());
  EXPECT_EQ(s.noise.dac_offset_v, 0.0);
  EXPECT_EQ(s.noise.dac_gain_error, 0.0);
  EXPECT_EQ(s.noise.bore_gauge_um_rms, 0.0);
  EXPECT_EQ(s.noise.bore_gauge_resolution_um, 0.0);
  EXPECT_FALSE(s.io.enabled());
}

struct BadKey {
  const char* text;
  const char* expected;  // the whole line after "scen.toml:"
};

void PrintTo(const BadKey& c, std::ostream* os) { *os << c.text; }

class RealismKeyErrors : public ::testing::TestWithParam<BadKey> {};

TEST_P(RealismKeyErrors, RefusedWithItsReason) {
  const BadKey& c = GetParam();
  const ScenarioResult r = parse_scenario_text(c.text, "scen.toml");
  EXPECT_FALSE(r.scenario) << c.text << ": accepted";
  EXPECT_EQ(r.error, std::string("scen.toml:") + c.expected);
}

INSTANTIATE_TEST_SUITE_P(
    EveryKey, RealismKeyErrors,
    ::testing::Values(
        BadKey{"[plant.x]\nbacklash_um = -1\n",
               "2:1: plant.x.backlash_um: must be 0..500: a ball screw's lost motion: 0-5 um new, 10-50 um worn; past "
               "0.5 mm the nut is broken (got -1)"},
        BadKey{"[plant.y]\nbacklash_um = nan\n",
               "2:1: plant.y.backlash_um: must be 0..500: a ball screw's lost motion: 0-5 um new, 10-50 um worn; past "
               "0.5 mm the nut is broken (got nan)"},
        BadKey{"[plant.x]\nlead_error_um_per_m = 2000\n",
               "2:1: plant.x.lead_error_um_per_m: must be -1000..1000: a ball screw's cumulative lead error (ISO 3408-3 "
               "class C10 allows 700 um/m) (got 2000)"},
        BadKey{"[plant.x]\nlead_error_um_per_m = -inf\n",
               "2:1: plant.x.lead_error_um_per_m: must be -1000..1000: a ball screw's cumulative lead error (ISO 3408-3 "
               "class C10 allows 700 um/m) (got -inf)"},
        BadKey{"[plant.y]\npitch_error_um = -3\n",
               "2:1: plant.y.pitch_error_um: must be 0..100: a ball screw's periodic lead error amplitude (C5 varies 8 "
               "um within a turn) (got -3)"},
        BadKey{"[plant.x]\npitch_period_mm = 0\n",
               "2:1: plant.x.pitch_period_mm: must be 0.1..1000: a screw lead or a multiple of it (got 0)"},
        BadKey{"[plant.x]\naccel_limit_mm_s2 = 50\n",
               "2:1: plant.x.accel_limit_mm_s2: must be 0 (none) or 100..1e+06: a servo axis' current-limited "
               "acceleration, 0.01 to 100 g (got 50)"},
        BadKey{"[plant.y]\naccel_limit_mm_s2 = nan\n",
               "2:1: plant.y.accel_limit_mm_s2: must be 0 (none) or 100..1e+06: a servo axis' current-limited "
               "acceleration, 0.01 to 100 g (got nan)"},
        BadKey{"[plant.x]\naccel_limit_mm_s2 = -9800\n",
               "2:1: plant.x.accel_limit_mm_s2: must be 0 (none) or 100..1e+06: a servo axis' current-limited "
               "acceleration, 0.01 to 100 g (got -9800)"},
        BadKey{"[noise]\nseed = -1\n", "2:1: noise.seed: must be in 0..4294967295 (got -1)"},
        BadKey{"[noise]\nseed = 1.5\n", "2:1: noise.seed: expected an integer, got a float"},
        BadKey{"[noise]\nforce_adc_v_rms = 2\n",
               "2:1: noise.force_adc_v_rms: must be 0..1: noise at the force ADC's input (its 0-10 V range has a 2.4 "
               "mV LSB) (got 2)"},
        BadKey{"[noise]\nforce_adc_v_rms = nan\n",
               "2:1: noise.force_adc_v_rms: must be 0..1: noise at the force ADC's input (its 0-10 V range has a 2.4 "
               "mV LSB) (got nan)"},
        BadKey{"[noise]\naccel_g_rms = -0.1\n",
               "2:1: noise.accel_g_rms: must be 0..1: a MEMS accelerometer's noise over the tick bandwidth (mg class) "
               "(got -0.1)"},
        BadKey{"[noise]\naccel_bias_g = 1.5\n",
               "2:1: noise.accel_bias_g: must be -1..1: an accelerometer's zero-g offset (tens of mg) (got 1.5)"},
        BadKey{"[noise]\ndac_offset_v = inf\n",
               "2:1: noise.dac_offset_v: must be -1..1: a speed DAC's offset (mV class; 1 V is a tenth of full scale) "
               "(got inf)"},
        BadKey{"[noise]\ndac_gain_error = 0.5\n",
               "2:1: noise.dac_gain_error: must be -0.1..0.1: a DAC's relative gain error (0.1-1 % class) (got 0.5)"},
        BadKey{"[noise]\nencoder_glitch_per_s = 5000\n",
               "2:1: noise.encoder_glitch_per_s: must be 0..1000: miscounts per second (a thousand a second is a "
               "broken cable) (got 5000)"},
        BadKey{"[noise]\nencoder_glitch_counts = 0\n", "2:1: noise.encoder_glitch_counts: must be in 1..1000 (got 0)"},
        BadKey{"[noise]\nencoder_glitch_counts = 2.0\n",
               "2:1: noise.encoder_glitch_counts: expected an integer, got a float"},
        BadKey{"[noise]\nbore_gauge_um_rms = -1\n",
               "2:1: noise.bore_gauge_um_rms: must be 0..50: a bore gauge's repeatability (um class; 50 um is a tenth "
               "of a millimetre band) (got -1)"},
        BadKey{"[noise]\nbore_gauge_resolution_um = 200\n",
               "2:1: noise.bore_gauge_resolution_um: must be 0..100: a bore gauge's reading step (0.1-10 um) (got 200)"},
        BadKey{"[noise]\nencoder_noise = 1\n", "2:1: noise.encoder_noise: unknown key"},
        BadKey{"[io]\nread_latency_us = 600\n",
               "2:1: io.read_latency_us: must be 0..500: a register transport's read after the latch (SPI or "
               "Ethernet: tens to hundreds of us) (got 600)"},
        BadKey{"[io]\nwrite_latency_us = nan\n",
               "2:1: io.write_latency_us: must be 0..500: a register transport's write (SPI or Ethernet: tens to "
               "hundreds of us) (got nan)"},
        BadKey{"[io]\njitter_us = -5\n",
               "2:1: io.jitter_us: must be 0..200: a Linux board's transfer jitter (tens of us) (got -5)"},
        BadKey{"[io]\nread_latency_us = 400\nwrite_latency_us = 400\njitter_us = 60\n",
               "4:1: io.jitter_us: the transfers must leave the firmware room in the 1 ms tick: read_latency_us + "
               "write_latency_us + 2 jitter_us = 920 us > 900 us"},
        BadKey{"[io]\nread_latency_us = 450\nwrite_latency_us = 451\n",
               "3:1: io.write_latency_us: the transfers must leave the firmware room in the 1 ms tick: "
               "read_latency_us + write_latency_us + 2 jitter_us = 901 us > 900 us"},
        BadKey{"[io]\nlatency_us = 1\n", "2:1: io.latency_us: unknown key"},
        BadKey{"[io.spi]\nrate = 1\n", "1:5: io.spi: unknown section"},
        BadKey{"io = 3\n", "1:1: io: expected a table, got an integer"}));

TEST(RealismKeys, BenchProfilesAreValidAndStateTheirMagnitudes) {
  for (const char* name : {"bench-no-cut", "bench-cut-1200"}) {
    const auto s = builtin_scenario(name);
    ASSERT_TRUE(s) << name;
    EXPECT_EQ(validate_scenario(*s), "") << name;
    EXPECT_TRUE(s->io.enabled()) << name;
    EXPECT_TRUE(s->noise.any_sample_noise()) << name;
    EXPECT_EQ(s->plant[0].backlash_um, 10.0) << name;
    EXPECT_EQ(s->plant[0].lead_error_um_per_m, 60.0) << name;
    EXPECT_EQ(s->plant[1].lead_error_um_per_m, -60.0) << name;
    EXPECT_EQ(s->noise.bore_gauge_um_rms, 1.0) << name;
    EXPECT_EQ(s->noise.bore_gauge_resolution_um, 1.0) << name;
    // The reference table underneath: the plant's own constants untouched.
    EXPECT_EQ(s->plant[0].tau_s, Scenario{}.plant[0].tau_s) << name;
    EXPECT_EQ(s->plant[1].tau_s, Scenario{}.plant[1].tau_s) << name;
  }
  EXPECT_FALSE(builtin_scenario("bench-no-cut")->cutting.enabled);
  EXPECT_TRUE(builtin_scenario("bench-cut-1200")->cutting.enabled);
  EXPECT_EQ(builtin_scenario("bench-cut-1200")->cutting.spindle_rpm, 1200.0);
}

}  // namespace
}  // namespace tnv::emu
