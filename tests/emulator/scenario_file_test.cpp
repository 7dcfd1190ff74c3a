// Scenario files: every key, every error class, the built-ins.
#include "emulator/scenario_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>


#include <filesystem>
#include <fstream>

#include "emulator/scenario_validation.hpp"
#include "tests/emulator/scenario_error_cases.hpp"
#include "tests/tools/unique_temp_dir.hpp"

namespace tnv::emu {
namespace {

using ::testing::HasSubstr;

constexpr std::string_view kEveryKey = R"(name = "everything"

[plant.x]
tau_s = 0.006
gain = 1.1
coulomb_mm_s = 1.0
stiction_mm_s = 2.0
stribeck_mm_s = 0.2
mode_hz = 30
mode_zeta = 0.02

[plant.y]
tau_s = 0.008
gain = 0.9
coulomb_mm_s = 0.5
stiction_mm_s = 0.7
stribeck_mm_s = 0.05
mode_hz = 100.5
mode_zeta = 0.1

[cutting]
enabled = true
spindle_rpm = 1200
flutes = 3
mean_mm_s = 0.4
amplitude_mm_s = 0.3
exponent = 0.8
phase_rad = 1.25

[encoder]
counts_per_rev = 8000
lead_mm = 5
offset_counts_x = 0.25
offset_counts_y = -0.5

[dac]
bits = 16
full_scale_v = 5.0
rpm_at_full_scale = 2000

[force_sensor]
volts_per_mm_s = 2.5

[board]
clock_start = 4294967295

[circle]
radius_mm = 10
feed_mm_s = 3
ramp_s = 0.2
dwell_s = 0.25
)";

TEST(ScenarioFile, EveryKeyIsParsed) {
  const ScenarioResult r = parse_scenario_text(kEveryKey, "every.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  EXPECT_TRUE(r.error.empty());
  const Scenario& s = *r.scenario;
  EXPECT_EQ(s.name, "everything");
  EXPECT_EQ(s.plant[0].tau_s, 0.006);
  EXPECT_EQ(s.plant[0].gain, 1.1);
  EXPECT_EQ(s.plant[0].coulomb_mm_s, 1.0);
  EXPECT_EQ(s.plant[0].stiction_mm_s, 2.0);
  EXPECT_EQ(s.plant[0].stribeck_mm_s, 0.2);
  EXPECT_EQ(s.plant[0].mode_hz, 30.0);
  EXPECT_EQ(s.plant[0].mode_zeta, 0.02);
  EXPECT_EQ(s.plant[1].tau_s, 0.008);
  EXPECT_EQ(s.plant[1].gain, 0.9);
  EXPECT_EQ(s.plant[1].coulomb_mm_s, 0.5);
  EXPECT_EQ(s.plant[1].stiction_mm_s, 0.7);
  EXPECT_EQ(s.plant[1].stribeck_mm_s, 0.05);
  EXPECT_EQ(s.plant[1].mode_hz, 100.5);
  EXPECT_EQ(s.plant[1].mode_zeta, 0.1);
  EXPECT_TRUE(s.cutting.enabled);
  EXPECT_EQ(s.cutting.spindle_rpm, 1200.0);
  EXPECT_EQ(s.cutting.flutes, 3);
  EXPECT_EQ(s.cutting.mean_mm_s, 0.4);
  EXPECT_EQ(s.cutting.amplitude_mm_s, 0.3);
  EXPECT_EQ(s.cutting.exponent, 0.8);
  EXPECT_EQ(s.cutting.phase_rad, 1.25);
  EXPECT_EQ(s.encoder.counts_per_rev, 8000);
  EXPECT_EQ(s.encoder.lead_mm, 5.0);
  EXPECT_EQ(s.encoder.axis_offset_counts[0], 0.25);
  EXPECT_EQ(s.encoder.axis_offset_counts[1], -0.5);
  EXPECT_EQ(s.dac.bits, 16);
  EXPECT_EQ(s.dac.full_scale_v, 5.0);
  EXPECT_EQ(s.dac.rpm_at_full_scale, 2000.0);
  EXPECT_EQ(s.force_sensor.volts_per_mm_s, 2.5);
  EXPECT_EQ(s.board.clock_start, 4294967295u);
  EXPECT_EQ(s.circle.radius_mm, 10.0);
  EXPECT_EQ(s.circle.feed_mm_s, 3.0);
  EXPECT_EQ(s.circle.ramp_s, 0.2);
  EXPECT_EQ(s.circle.dwell_s, 0.25);
}

TEST(ScenarioFile, EmptyFileGivesTheReferencePlant) {
  const ScenarioResult r = parse_scenario_text("", "empty.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  EXPECT_EQ(r.scenario->plant[0].tau_s, 0.005360);
  EXPECT_EQ(r.scenario->plant[1].tau_s, 0.007122);
  EXPECT_EQ(r.scenario->circle.radius_mm, 6.0);
}

TEST(ScenarioFile, PartialSectionKeepsOtherDefaults) {
  const ScenarioResult r = parse_scenario_text("[plant.y]\ngain = 2\n", "p.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  EXPECT_EQ(r.scenario->plant[1].gain, 2.0);
  EXPECT_EQ(r.scenario->plant[1].tau_s, 0.007122);
  EXPECT_EQ(r.scenario->plant[0].gain, 1.0);
}

TEST(ScenarioFile, LoadsFromDisk) {
  const tnv::test::UniqueTempDir dir("tnv-scenario");
  const auto path = dir / "disk.toml";
  {
    std::ofstream out(path);
    out << "name = \"disk\"\n[cutting]\nenabled = true\n";
  }
  const ScenarioResult r = load_scenario_file(path.string());
  ASSERT_TRUE(r.scenario) << r.error;
  EXPECT_EQ(r.scenario->name, "disk");
  EXPECT_TRUE(r.scenario->cutting.enabled);
}

using test::ScenarioErrorCase;
using test::ScenarioFileErrors;

TEST_P(ScenarioFileErrors, OneLineNamingFileLineAndKey) {
  const ScenarioErrorCase& c = GetParam();
  const ScenarioResult r = parse_scenario_text(c.text, "scen.toml");
  EXPECT_FALSE(r.scenario) << c.what << ": accepted";
  EXPECT_EQ(r.error, std::string("scen.toml:") + c.expected) << c.what;
  EXPECT_EQ(r.error.find('\n'), std::string::npos) << c.what << ": not one line";
}

INSTANTIATE_TEST_SUITE_P(
    EveryErrorClass, ScenarioFileErrors,
    ::testing::Values(
        ScenarioErrorCase{"out of range", "# comment\n[plant.x]\n\n\n\n\ntau_s = -1\n", "7:1: plant.x.tau_s: must be > 0 and finite (got -1)"},
        ScenarioErrorCase{"unknown section", "[plant.w]\ntau_s = 1\n", "1:8: plant.w: unknown section"},
        ScenarioErrorCase{"absurd tau", "[plant.x]\ntau_s = 1e-300\n",
                "2:1: plant.x.tau_s: must be 1e-04..1: a servo axis' speed loop settles in 0.1 ms to 1 s (got 1e-300)"},
        ScenarioErrorCase{"absurd dac volts", "[dac]\nfull_scale_v = 1e-30\n",
                "2:1: dac.full_scale_v: must be 0.5..50: a servo's analogue speed reference (10 V class) (got 1e-30)"},
        ScenarioErrorCase{"absurd radius", "[circle]\nradius_mm = 1e30\n",
                "2:1: circle.radius_mm: must be 0.001..500: a circle the table's travel can hold (got 1e+30)"},
        ScenarioErrorCase{"absurd gain", "[plant.y]\ngain = 1e4\n",
                "2:1: plant.y.gain: must be 0.1..10: the drive's speed per commanded speed (got 10000)"},
        ScenarioErrorCase{"absurd feed", "[circle]\nfeed_mm_s = 5000\n",
                "2:1: circle.feed_mm_s: must be 0.001..1000: a contouring feed up to 60 m/min (got 5000)"},
        ScenarioErrorCase{"absurd friction", "[plant.x]\nstiction_mm_s = 5000\ncoulomb_mm_s = 2\n",
                "2:1: plant.x.stiction_mm_s: must be 0..1000: friction above 1000 mm/s is no moving table (a jam is 200) (got 5000)"},
        ScenarioErrorCase{"unknown top section", "[turret]\nrpm = 1\n", "1:2: turret: unknown section"},
        ScenarioErrorCase{"unknown key", "[cutting]\nspindle = 900\n", "2:1: cutting.spindle: unknown key"},
        ScenarioErrorCase{"unknown top key", "speed = 2\n", "1:1: speed: unknown key"},
        ScenarioErrorCase{"wrong type", "[circle]\nradius_mm = \"six\"\n", "2:1: circle.radius_mm: expected a number, got a string"},
        ScenarioErrorCase{"float for integer", "[dac]\nbits = 12.0\n", "2:1: dac.bits: expected an integer, got a float"},
        ScenarioErrorCase{"wrong bool type", "[cutting]\nenabled = 1\n", "2:1: cutting.enabled: expected a boolean, got an integer"},
        ScenarioErrorCase{"section not a table", "cutting = 3\n", "1:1: cutting: expected a table, got an integer"},
        ScenarioErrorCase{"name not a string", "name = 3\n", "1:1: name: expected a string, got an integer"},
        ScenarioErrorCase{"nan", "[plant.y]\ngain = nan\n", "2:1: plant.y.gain: must be > 0 and finite (got nan)"},
        ScenarioErrorCase{"inf", "[encoder]\noffset_counts_x = -inf\n", "2:1: encoder.offset_counts_x: must be finite (got -inf)"},
        ScenarioErrorCase{"stiction below coulomb", "[plant.x]\ncoulomb_mm_s = 2\nstiction_mm_s = 1.5\n",
                "3:1: plant.x.stiction_mm_s: must be >= coulomb_mm_s = 2 (got 1.5)"},
        ScenarioErrorCase{"coulomb above default stiction", "[plant.y]\ncoulomb_mm_s = 4\n",
                "2:1: plant.y.coulomb_mm_s: must be <= stiction_mm_s = 3 (got 4)"},
        ScenarioErrorCase{"negative friction", "[plant.x]\ncoulomb_mm_s = -0.1\n",
                "2:1: plant.x.coulomb_mm_s: must be >= 0 and finite (got -0.1)"},
        ScenarioErrorCase{"stribeck zero", "[plant.x]\nstribeck_mm_s = 0\n", "2:1: plant.x.stribeck_mm_s: must be > 0 and finite (got 0)"},
        ScenarioErrorCase{"mode above nyquist", "[plant.x]\nmode_hz = 50000\n",
                "2:1: plant.x.mode_hz: must be >= 0 and below the sub-step Nyquist frequency 50000 Hz (got 50000)"},
        ScenarioErrorCase{"zeta one", "[plant.y]\nmode_zeta = 1\n", "2:1: plant.y.mode_zeta: must be >= 0 and below 1 (got 1)"},
        ScenarioErrorCase{"spindle zero", "[cutting]\nspindle_rpm = 0\n", "2:1: cutting.spindle_rpm: must be > 0 and finite (got 0)"},
        ScenarioErrorCase{"no flutes", "[cutting]\nflutes = 0\n", "2:1: cutting.flutes: must be >= 1 (got 0)"},
        ScenarioErrorCase{"huge flutes", "[cutting]\nflutes = 9999999999\n", "2:1: cutting.flutes: out of range (got 9999999999)"},
        ScenarioErrorCase{"negative amplitude", "[cutting]\namplitude_mm_s = -1\n",
                "2:1: cutting.amplitude_mm_s: must be >= 0 and finite (got -1)"},
        ScenarioErrorCase{"counts not x4", "[encoder]\ncounts_per_rev = 1001\n",
                "2:1: encoder.counts_per_rev: must be a positive multiple of 4 (x4 decoding) (got 1001)"},
        ScenarioErrorCase{"lead zero", "[encoder]\nlead_mm = 0\n", "2:1: encoder.lead_mm: must be > 0 and finite (got 0)"},
        ScenarioErrorCase{"dac bits", "[dac]\nbits = 17\n", "2:1: dac.bits: must be in 8..16 (got 17)"},
        ScenarioErrorCase{"dac volts", "[dac]\nfull_scale_v = 0\n", "2:1: dac.full_scale_v: must be > 0 and finite (got 0)"},
        ScenarioErrorCase{"dac rpm", "[dac]\nrpm_at_full_scale = -5\n", "2:1: dac.rpm_at_full_scale: must be > 0 and finite (got -5)"},
        ScenarioErrorCase{"force volts", "[force_sensor]\nvolts_per_mm_s = -1\n",
                "2:1: force_sensor.volts_per_mm_s: must be >= 0 and finite (got -1)"},
        ScenarioErrorCase{"clock negative", "[board]\nclock_start = -1\n", "2:1: board.clock_start: must be in 0..4294967295 (got -1)"},
        ScenarioErrorCase{"clock too big", "[board]\nclock_start = 4294967296\n",
                "2:1: board.clock_start: must be in 0..4294967295 (got 4294967296)"},
        ScenarioErrorCase{"radius", "[circle]\nradius_mm = 0\n", "2:1: circle.radius_mm: must be > 0 and finite (got 0)"},
        ScenarioErrorCase{"feed", "[circle]\nfeed_mm_s = -2\n", "2:1: circle.feed_mm_s: must be > 0 and finite (got -2)"},
        ScenarioErrorCase{"dwell", "[circle]\ndwell_s = -0.5\n", "2:1: circle.dwell_s: must be >= 0 and finite (got -0.5)"},
        ScenarioErrorCase{"ramps too long", "[circle]\nramp_s = 20\n",
                "2:1: circle.ramp_s: both ramps must fit in the circle: feed_mm_s * ramp_s = 40 mm > 2 pi radius_mm = "
                "37.69911184307752 mm"}),
    test::scenario_error_case_name);

TEST(ScenarioFile, SyntaxErrorUsesTheTomlSourceRegion) {
  const ScenarioResult r = parse_scenario_text("[plant.x]\ntau_s = = 1\n", "scen.toml");
  EXPECT_FALSE(r.scenario);
  EXPECT_EQ(r.error.rfind("scen.toml:2:", 0), 0u) << r.error;
  EXPECT_THAT(r.error, HasSubstr("TOML syntax error"));
  EXPECT_EQ(r.error.find('\n'), std::string::npos);
}

TEST(ScenarioFile, DuplicateKeyIsASyntaxError) {
  const ScenarioResult r = parse_scenario_text("[plant.x]\ntau_s = 0.005\ntau_s = 1\n", "scen.toml");
  EXPECT_FALSE(r.scenario);
  EXPECT_EQ(r.error.rfind("scen.toml:3:", 0), 0u) << r.error;
}

TEST(ScenarioFile, UnreadableFileIsNamed) {
  const ScenarioResult r = load_scenario_file("/nonexistent/dir/scen.toml");
  EXPECT_FALSE(r.scenario);
  EXPECT_EQ(r.error, "/nonexistent/dir/scen.toml: cannot read file: No such file or directory");
  const ScenarioResult dir = load_scenario_file(std::filesystem::temp_directory_path().string());
  EXPECT_FALSE(dir.scenario);
  EXPECT_THAT(dir.error, HasSubstr("is a directory"));
}

TEST(ScenarioFile, AFifoOrADeviceIsRefusedAtOnceAndTheSizeIsCapped) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("tnv_scen_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string fifo = (dir / "scen.fifo").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THAT(load_scenario_file(fifo).error, HasSubstr("not a regular file")) << "must not hang";
  EXPECT_THAT(load_scenario_file("/dev/zero").error, HasSubstr("/dev/zero: cannot read file: not a regular file"));
  const std::string big = (dir / "big.toml").string();
  std::ofstream(big) << "# " << std::string(kMaxScenarioBytes, 'x') << "\n";
  EXPECT_THAT(load_scenario_file(big).error, HasSubstr("allowed"));
  std::filesystem::remove_all(dir);
}

TEST(ScenarioFile, IntegersAcceptedForNumbers) {
  const ScenarioResult r = parse_scenario_text("[circle]\nradius_mm = 7\n[plant.x]\ngain = 2\n", "i.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  EXPECT_EQ(r.scenario->circle.radius_mm, 7.0);
}

TEST(BuiltinScenarios, AllExistAreValidAndDiffer) {
  const std::vector<std::string> names = builtin_scenario_names();
  EXPECT_EQ(names, (std::vector<std::string>{"no-cut", "cut-900", "cut-1200", "cut-1500", "flex-30", "flex-100",
                                             "bench-no-cut", "bench-cut-1200"}));
  for (const std::string& name : names) {
    const auto s = builtin_scenario(name);
    ASSERT_TRUE(s) << name;
    EXPECT_EQ(s->name, name);
    EXPECT_EQ(validate_scenario(*s), "") << name;
  }
  EXPECT_FALSE(builtin_scenario("cut-1000"));
  EXPECT_FALSE(builtin_scenario("no-cut")->cutting.enabled);
  EXPECT_TRUE(builtin_scenario("cut-1200")->cutting.enabled);
  EXPECT_EQ(builtin_scenario("cut-1500")->cutting.spindle_rpm, 1500.0);
  EXPECT_EQ(builtin_scenario("flex-30")->plant[0].mode_hz, 30.0);
  EXPECT_EQ(builtin_scenario("flex-100")->plant[0].mode_hz, 100.0);
  EXPECT_EQ(builtin_scenario("flex-100")->plant[0].mode_zeta, 0.02);
  EXPECT_EQ(builtin_scenario("flex-100")->plant[1].mode_hz, 0.0);
}

TEST(BuiltinScenarios, ResolveTakesANameOrAPath) {
  EXPECT_EQ(resolve_scenario("cut-900").scenario->cutting.spindle_rpm, 900.0);
  EXPECT_THAT(resolve_scenario("no-such.toml").error, HasSubstr("no-such.toml: cannot read file"));
}

TEST(ScenarioValidation, DefaultsAreValid) { EXPECT_EQ(validate_scenario(Scenario{}), ""); }

}  // namespace
}  // namespace tnv::emu
