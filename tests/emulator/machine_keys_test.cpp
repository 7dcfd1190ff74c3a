// Scenario keys of the machining centre beyond the table ([plant.z],
// [spindle], [tool], [stock], [tool_cut], [boring], [probe]): each parsed,
// each range refused with file, line and key, nothing half-applied.
#include <gtest/gtest.h>

#include <cmath>

#include "emulator/scenario_file.hpp"
#include "emulator/scenario_validation.hpp"
#include "tests/emulator/scenario_error_cases.hpp"

namespace tnv::emu {
namespace {

constexpr std::size_t kZ = hal::index(hal::Axis::z);

constexpr std::string_view kMachineKeys = R"([plant.z]
tau_s = 0.01
gain = 1.05
coulomb_mm_s = 1.5
stiction_mm_s = 3.5
stribeck_mm_s = 0.2
accel_limit_mm_s2 = 2000
gravity_mm_s = -0.5
travel_top_mm = 10
travel_bottom_mm = -350
overtravel_mm = 3
start_mm = -8

[spindle]
tau_s = 0.3
dac_bits = 16
full_scale_v = 5
rpm_at_full_scale = 8000
accel_limit_rpm_s = 4000
droop_rpm_per_n = 0.1
encoder_counts_per_rev = 1024
index_deg = 45

[tool]
diameter_mm = 12
flutes = 3
flute_length_mm = 30
length_mm = 90

[stock]
top_mm = -120
x_min_mm = -50
x_max_mm = 50
y_min_mm = -inf
y_max_mm = 20

[tool_cut]
k_c_n_mm2 = 1500
time_constant_s = 0.1
stiffness_n_per_mm_s = 250
crash_speed_fraction = 0.8
max_feed_per_tooth_mm = 0.5

[boring]
overhang_at_top_mm = 50
gauge_top_depth_mm = 5
gauge_bottom_depth_mm = 200
sigma_d_um = 10
change_at_1 = 8
change_at_2 = 16

[probe]
tip_radius_mm = 1.5
)";

TEST(MachineKeys, EveryKeyIsParsed) {
  const ScenarioResult r = parse_scenario_text(kMachineKeys, "machine.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  const Scenario& s = *r.scenario;
  EXPECT_EQ(s.plant[kZ].tau_s, 0.01);
  EXPECT_EQ(s.plant[kZ].gain, 1.05);
  EXPECT_EQ(s.plant[kZ].coulomb_mm_s, 1.5);
  EXPECT_EQ(s.plant[kZ].stiction_mm_s, 3.5);
  EXPECT_EQ(s.plant[kZ].stribeck_mm_s, 0.2);
  EXPECT_EQ(s.plant[kZ].accel_limit_mm_s2, 2000.0);
  EXPECT_EQ(s.z_axis.gravity_mm_s, -0.5);
  EXPECT_EQ(s.z_axis.travel_top_mm, 10.0);
  EXPECT_EQ(s.z_axis.travel_bottom_mm, -350.0);
  EXPECT_EQ(s.z_axis.overtravel_mm, 3.0);
  EXPECT_EQ(s.z_axis.start_mm, -8.0);
  EXPECT_EQ(s.spindle.tau_s, 0.3);
  EXPECT_EQ(s.spindle.dac_bits, 16);
  EXPECT_EQ(s.spindle.full_scale_v, 5.0);
  EXPECT_EQ(s.spindle.rpm_at_full_scale, 8000.0);
  EXPECT_EQ(s.spindle.accel_limit_rpm_s, 4000.0);
  EXPECT_EQ(s.spindle.droop_rpm_per_n, 0.1);
  EXPECT_EQ(s.spindle.encoder_counts_per_rev, 1024);
  EXPECT_EQ(s.spindle.index_deg, 45.0);
  EXPECT_EQ(s.tool.diameter_mm, 12.0);
  EXPECT_EQ(s.tool.flutes, 3);
  EXPECT_EQ(s.tool.flute_length_mm, 30.0);
  EXPECT_EQ(s.tool.length_mm, 90.0);
  EXPECT_EQ(s.stock.top_mm, -120.0);
  EXPECT_EQ(s.stock.x_min_mm, -50.0);
  EXPECT_EQ(s.stock.x_max_mm, 50.0);
  EXPECT_TRUE(std::isinf(s.stock.y_min_mm) && s.stock.y_min_mm < 0.0);
  EXPECT_EQ(s.stock.y_max_mm, 20.0);
  EXPECT_EQ(s.tool_cut.k_c_n_mm2, 1500.0);
  EXPECT_EQ(s.tool_cut.time_constant_s, 0.1);
  EXPECT_EQ(s.tool_cut.stiffness_n_per_mm_s, 250.0);
  EXPECT_EQ(s.tool_cut.crash_speed_fraction, 0.8);
  EXPECT_EQ(s.tool_cut.max_feed_per_tooth_mm, 0.5);
  EXPECT_EQ(s.boring.overhang_at_top_mm, 50.0);
  EXPECT_EQ(s.boring.gauge_top_depth_mm, 5.0);
  EXPECT_EQ(s.boring.gauge_bottom_depth_mm, 200.0);
  EXPECT_EQ(s.boring.sigma_d_um, 10.0);
  EXPECT_EQ(s.boring.change_at_1, 8);
  EXPECT_EQ(s.boring.change_at_2, 16);
  EXPECT_EQ(s.probe.tip_radius_mm, 1.5);
}

TEST(MachineKeys, DefaultsAreTheReferencePlantAndValid) {
  const Scenario s;
  EXPECT_EQ(validate_scenario(s), "");
  EXPECT_EQ(s.stock.top_mm, -150.0);
  EXPECT_TRUE(std::isinf(s.stock.x_min_mm) && std::isinf(s.stock.x_max_mm)) << "the whole table";
  EXPECT_EQ(s.spindle.tau_s, 0.2);
  EXPECT_EQ(s.spindle.rpm_at_full_scale, 12'000.0);
  EXPECT_EQ(s.spindle.full_scale_v, 10.0);
  EXPECT_EQ(s.spindle.dac_bits, 12);
  EXPECT_EQ(s.spindle.accel_limit_rpm_s, 6'000.0);
  EXPECT_EQ(s.spindle.droop_rpm_per_n, 0.2);
  EXPECT_EQ(s.spindle.encoder_counts_per_rev, 4096);
  EXPECT_EQ(s.tool_cut.time_constant_s, 0.2);
  EXPECT_EQ(s.tool_cut.stiffness_n_per_mm_s, 100.0);
  EXPECT_EQ(s.tool_cut.crash_speed_fraction, 0.5);
  EXPECT_EQ(s.boring.overhang_at_top_mm, 40.0);
  // The S1 experiment's section is untouched by the machine's.
  EXPECT_FALSE(s.cutting.enabled);
  EXPECT_EQ(s.cutting.spindle_rpm, 900.0);
}

// The boring gauge's depths are the bar's: with [boring] off a stock takes
// a tool too short to reach them (the same keys with it on: refused, below).
TEST(MachineKeys, AShortToolOnAStockIsValidWithBoringOff) {
  const ScenarioResult r =
      parse_scenario_text("[stock]\nenabled = true\n[tool]\nlength_mm = 100\n[boring]\ngauge_bottom_depth_mm = 400\n",
                          "scen.toml");
  ASSERT_TRUE(r.scenario) << r.error;
  EXPECT_TRUE(r.scenario->stock.enabled);
  EXPECT_FALSE(r.scenario->boring.enabled);
  EXPECT_EQ(r.scenario->tool.length_mm, 100.0);
  EXPECT_EQ(validate_scenario(*r.scenario), "");
}

// Refused like every scenario error (scenario_file_test.cpp: one line, file, line, column, key).
using test::ScenarioErrorCase;
using test::ScenarioFileErrors;

INSTANTIATE_TEST_SUITE_P(
    MachineSections, ScenarioFileErrors,
    ::testing::Values(
        ScenarioErrorCase{"z tau", "[plant.z]\ntau_s = 0\n", "2:1: plant.z.tau_s: must be > 0 and finite (got 0)"},
        ScenarioErrorCase{"z stiction below coulomb", "[plant.z]\nstiction_mm_s = 1\n",
                   "2:1: plant.z.stiction_mm_s: must be >= coulomb_mm_s = 2 (got 1)"},
        ScenarioErrorCase{"z structural mode beyond nyquist", "[plant.z]\nmode_hz = 1e9\n",
                   "2:1: plant.z.mode_hz: must be >= 0 and below the sub-step Nyquist frequency 50000 Hz (got 1e+09)"},
        ScenarioErrorCase{"z gravity", "[plant.z]\ngravity_mm_s = -500\n",
                   "2:1: plant.z.gravity_mm_s: must be -100..100: what the counterbalance leaves of the head's weight, "
                   "as a table speed (got -500)"},
        ScenarioErrorCase{"z travel upside down", "[plant.z]\ntravel_bottom_mm = 10\n",
                   "2:1: plant.z.travel_bottom_mm: must be <= travel_top_mm = 0 (got 10)"},
        ScenarioErrorCase{"z start off the travel", "\n[plant.z]\nstart_mm = 50\n",
                   "3:1: plant.z.start_mm: must be -300..0: a power-up position on the travel (got 50)"},
        ScenarioErrorCase{"spindle tau", "[spindle]\ntau_s = -0.2\n",
                   "2:1: spindle.tau_s: must be 0.001..10: a spindle drive's speed loop settles in 1 ms to 10 s (got -0.2)"},
        ScenarioErrorCase{"spindle ramp", "[spindle]\naccel_limit_rpm_s = 0\n",
                   "2:1: spindle.accel_limit_rpm_s: must be 1..1e+06: a spindle drive's current-limited acceleration "
                   "(thousands of rpm/s) (got 0)"},
        ScenarioErrorCase{"spindle droop nan", "[spindle]\ndroop_rpm_per_n = nan\n",
                   "2:1: spindle.droop_rpm_per_n: must be 0..100: speed lost per newton of cutting load (got nan)"},
        ScenarioErrorCase{"spindle encoder not x4", "[spindle]\nencoder_counts_per_rev = 4097\n",
                   "2:1: spindle.encoder_counts_per_rev: must be a positive multiple of 4 (x4 decoding) (got 4097)"},
        ScenarioErrorCase{"spindle dac bits", "[spindle]\ndac_bits = 20\n", "2:1: spindle.dac_bits: must be in 8..16 (got 20)"},
        ScenarioErrorCase{"spindle dac as float", "[spindle]\ndac_bits = 12.5\n",
                   "2:1: spindle.dac_bits: expected an integer, got a float"},
        ScenarioErrorCase{"tool flutes", "[tool]\nflutes = 0\n", "2:1: tool.flutes: must be in 1..20 (got 0)"},
        ScenarioErrorCase{"tool diameter", "[tool]\ndiameter_mm = 0\n",
                   "2:1: tool.diameter_mm: must be 0.1..100: an end mill's diameter (got 0)"},
        ScenarioErrorCase{"stock top", "[stock]\ntop_mm = 5000\n", "2:1: stock.top_mm: must be -1000..1000: machine coordinates (got 5000)"},
        ScenarioErrorCase{"stock side nan", "[stock]\nx_min_mm = nan\n",
                   "2:1: stock.x_min_mm: must be -1000..1000 (machine coordinates) or +-inf (unbounded) (got nan)"},
        ScenarioErrorCase{"stock rectangle upside down", "[stock]\nx_min_mm = 10\nx_max_mm = -10\n",
                   "3:1: stock.x_max_mm: must be >= x_min_mm = 10 (got -10)"},
        ScenarioErrorCase{"stock unknown key", "[stock]\nheight_mm = 10\n", "2:1: stock.height_mm: unknown key"},
        ScenarioErrorCase{"k_c", "[tool_cut]\nk_c_n_mm2 = -1\n",
                   "2:1: tool_cut.k_c_n_mm2: must be 1..20000: a specific cutting force (aluminium ~700, steel ~2000 "
                   "N/mm^2) (got -1)"},
        ScenarioErrorCase{"crash fraction", "[tool_cut]\ncrash_speed_fraction = 1.5\n",
                   "2:1: tool_cut.crash_speed_fraction: must be 0..1: a fraction of the commanded spindle speed (got 1.5)"},
        ScenarioErrorCase{"stiffness", "[tool_cut]\nstiffness_n_per_mm_s = 0\n",
                   "2:1: tool_cut.stiffness_n_per_mm_s: must be 0.1..1e+06: a drive's stiffness against a load, newtons "
                   "per mm/s (got 0)"},
        ScenarioErrorCase{"overhang", "[boring]\noverhang_at_top_mm = 0\n",
                   "2:1: boring.overhang_at_top_mm: must be 1..2000: a boring bar's overhang (got 0)"},
        ScenarioErrorCase{"gauge depths upside down", "[boring]\ngauge_top_depth_mm = 300\n",
                   "2:1: boring.gauge_top_depth_mm: must be <= gauge_bottom_depth_mm = 270 (got 300)"},
        ScenarioErrorCase{"gauge out of reach",
                   "[stock]\nenabled = true\n[boring]\nenabled = true\ngauge_bottom_depth_mm = 400\n",
                   "5:1: boring.gauge_bottom_depth_mm: the bottom gauge depth must be within reach: stock.top_mm - "
                   "boring.gauge_bottom_depth_mm = -550 mm < plant.z.travel_bottom_mm - tool.length_mm = -425 mm"},
        ScenarioErrorCase{"a shorter tool is what cannot reach",
                   "[stock]\nenabled = true\n[boring]\nenabled = true\n[tool]\nlength_mm = 100\n",
                   "6:1: tool.length_mm: the bottom gauge depth must be within reach: stock.top_mm - "
                   "boring.gauge_bottom_depth_mm = -420 mm < plant.z.travel_bottom_mm - tool.length_mm = -400 mm"},
        ScenarioErrorCase{"change part", "[boring]\nchange_at_1 = -3\n", "2:1: boring.change_at_1: must be in 0..1000000 (got -3)"},
        ScenarioErrorCase{"probe", "[probe]\ntip_radius_mm = -1\n",
                   "2:1: probe.tip_radius_mm: must be 0..10: a touch probe's stylus ball radius (got -1)"}),
    test::scenario_error_case_name);

}  // namespace
}  // namespace tnv::emu
