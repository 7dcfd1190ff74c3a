// The S1 circle with the realism keys: off, nothing moves (the Table 3
// runs bit for bit as before); on, the encoder-measured score and the truth
// (table, tool point) part where the encoder cannot see the ball screw.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "firmware/tick/work_meter.hpp"
#include "tests/sanitized_build.hpp"
#include "tools/hil/circle_run.hpp"
#include "tools/hil/hil_firmware_config.hpp"
#include "tools/hil/hil_rig.hpp"

namespace tnv::hil {
namespace {

using fw::ControllerKind;

CircleRunResult circle(const emu::Scenario& s, ControllerKind kind = ControllerKind::rdvsc) {
  CircleRunResult r = run_circle(s, fw::default_firmware_config(), kind);
  EXPECT_TRUE(r.completed) << s.name << ": " << r.error;
  return r;
}

emu::Scenario builtin(const char* name) { return *emu::builtin_scenario(name); }

void expect_same(const ContourStats& a, const ContourStats& b, const std::string& what) {
  EXPECT_EQ(a.max_um, b.max_um) << what;
  EXPECT_EQ(a.mean_um, b.mean_um) << what;
  EXPECT_EQ(a.std_um, b.std_um) << what;
  EXPECT_EQ(a.samples, b.samples) << what;
}

// Seed-0 results of `tnv-hil circle` before the realism keys existed
// (x86-64 release build, the numbers behind docs/reproduction-s1.md's runs).
struct Golden {
  const char* scenario;
  ControllerKind controller;
  double max_um, mean_um, std_um;
};
constexpr Golden kBefore[] = {
    {"no-cut", ControllerKind::pid, 3.479344189594613, 0.19176104531178803, 0.2618750186992259},
    {"no-cut", ControllerKind::dvsc, 2.99440615079849, 0.18628266548412353, 0.24708722155061363},
    {"no-cut", ControllerKind::rdvsc, 2.443382698414709, 0.16294513632958563, 0.16976770694676097},
    {"cut-1200", ControllerKind::pid, 2.6003624355261934, 0.3623338636679964, 0.2880156564124821},
    {"cut-1200", ControllerKind::dvsc, 2.2808454138685264, 0.35920365744078353, 0.2849216432113848},
    {"cut-1200", ControllerKind::rdvsc, 2.446839044520921, 0.24614459980895492, 0.20627876518662144},
};

TEST(RealismCircle, AllOffTheScoresHaveNotMoved) {
  for (const Golden& g : kBefore) {
    const CircleRunResult r = circle(builtin(g.scenario), g.controller);
    const std::string what = std::string(g.scenario) + " " + fw::to_string(g.controller);
#if defined(__x86_64__)
    EXPECT_EQ(r.stats.max_um, g.max_um) << what;
    EXPECT_EQ(r.stats.mean_um, g.mean_um) << what;
    EXPECT_EQ(r.stats.std_um, g.std_um) << what;
#else  // another instruction set may contract multiply-adds differently
    EXPECT_NEAR(r.stats.max_um, g.max_um, 1e-6) << what;
    EXPECT_NEAR(r.stats.mean_um, g.mean_um, 1e-6) << what;
    EXPECT_NEAR(r.stats.std_um, g.std_um, 1e-6) << what;
#endif
  }
}

TEST(RealismCircle, EveryKeyWrittenAsOffIsTheDefaultRun) {
  const emu::ScenarioResult written = emu::parse_scenario_text(R"(
[cutting]
enabled = true
spindle_rpm = 1200
[plant.x]
backlash_um = 0
lead_error_um_per_m = 0
pitch_error_um = 0
pitch_period_mm = 7
accel_limit_mm_s2 = 0
[plant.y]
backlash_um = 0
[noise]
seed = 99
force_adc_v_rms = 0
accel_g_rms = 0
accel_bias_g = 0
dac_offset_v = 0
dac_gain_error = 0
encoder_glitch_per_s = 0
encoder_glitch_counts = 5
[io]
read_latency_us = 0
write_latency_us = 0
jitter_us = 0
)",
                                                              "off.toml");
  ASSERT_TRUE(written.scenario) << written.error;
  const CircleRunResult off = circle(*written.scenario);
  const CircleRunResult reference = circle(builtin("cut-1200"));
  expect_same(off.stats, reference.stats, "encoder-measured");
  expect_same(off.true_table_stats, reference.true_table_stats, "table truth");
}

TEST(RealismCircle, WithoutScrewErrorsTheTruthIsTheTableAndTheToolIsTheTable) {
  const CircleRunResult r = circle(builtin("no-cut"));
  expect_same(r.true_tool_stats, r.true_table_stats, "no structural mode: tool point = table");
  // The encoder quantises (mean ~0.10 um floor); the truth does not, and the two stay within a count.
  EXPECT_NEAR(r.true_table_stats.max_um, r.stats.max_um, 0.5);
  EXPECT_LT(r.true_table_stats.mean_um, r.stats.mean_um);
}

TEST(RealismCircle, LeadErrorIsInvisibleToTheEncoderAndScalesTheTrueCircle) {
  emu::Scenario s = builtin("no-cut");
  s.plant[0].lead_error_um_per_m = s.plant[1].lead_error_um_per_m = 1000.0;  // 1 um per mm of travel
  const CircleRunResult r = circle(s);
  const CircleRunResult reference = circle(builtin("no-cut"));
  expect_same(r.stats, reference.stats, "the encoder, on the motor, scores the same run");
  // The table runs the circle 1e-3 larger: 6 um radius error on R = 6 mm, plus the tracking error.
  EXPECT_NEAR(r.true_table_stats.mean_um, 6.0, 0.3) << "true mean contour error";
  EXPECT_GT(r.true_table_stats.mean_um, 5.0 * r.stats.mean_um);
}

TEST(RealismCircle, BacklashShowsInTheTruthOnly) {
  emu::Scenario s = builtin("no-cut");
  s.plant[0].backlash_um = s.plant[1].backlash_um = 10.0;
  const CircleRunResult r = circle(s);
  const CircleRunResult reference = circle(builtin("no-cut"));
  // The motor's motion is the same (no load reflects through the lash), up to rounding.
  EXPECT_NEAR(r.stats.max_um, reference.stats.max_um, 1e-6);
  EXPECT_NEAR(r.stats.mean_um, reference.stats.mean_um, 1e-6);
  // Each axis trails by b/2 = 5 um against its motion; radially that is up to b/sqrt(2) = 7.1 um.
  EXPECT_GT(r.true_table_stats.max_um, 5.0) << "true max contour error";
  EXPECT_LT(r.true_table_stats.max_um, 7.1 + reference.true_table_stats.max_um) << "true max contour error";
  EXPECT_GT(r.true_table_stats.mean_um, 1.0);
}

TEST(RealismCircle, ToolPointTruthSeesTheStructuralMode) {
  const CircleRunResult flex = circle(builtin("flex-30"));
  const CircleRunResult rigid = circle(builtin("no-cut"));
  expect_same(flex.stats, rigid.stats, "the mode is past the encoder");
  // The table too (stepped sub-step by sub-step here, in closed form there: equal to rounding).
  EXPECT_NEAR(flex.true_table_stats.max_um, rigid.true_table_stats.max_um, 1e-6);
  EXPECT_NEAR(flex.true_table_stats.mean_um, rigid.true_table_stats.mean_um, 1e-6);
  EXPECT_NE(flex.true_tool_stats.max_um, flex.true_table_stats.max_um) << "the tool point moves on the mode";
}

TEST(RealismCircle, BenchScenariosRunTheCircleDeterministically) {
  // Each scenario is judged alone: a sanitizer build runs the first.
  for (const char* name : {"bench-no-cut", "bench-cut-1200"}) {
    if (tnv::test::kSanitizedBuild && std::string(name) != "bench-no-cut") continue;
    for (ControllerKind kind : {ControllerKind::pid, ControllerKind::dvsc, ControllerKind::rdvsc}) {
      const CircleRunResult r = circle(builtin(name), kind);
      const std::string what = std::string(name) + " " + fw::to_string(kind);
      EXPECT_GT(r.stats.samples, 9000u) << what;
      EXPECT_LT(r.stats.max_um, 10.0) << what << ": encoder-measured max";
      // 10 um of lash and C5 lead error are past the encoder: the truth is several um worse.
      EXPECT_GT(r.true_table_stats.mean_um, r.stats.mean_um + 2.0) << what;
      EXPECT_LT(r.true_table_stats.max_um, 15.0) << what;
    }
    const CircleRunResult a = circle(builtin(name));
    const CircleRunResult b = circle(builtin(name));
    expect_same(a.stats, b.stats, std::string(name) + " twice");
    expect_same(a.true_table_stats, b.true_table_stats, std::string(name) + " twice");
    emu::Scenario reseeded = builtin(name);
    ++reseeded.noise.seed;
    EXPECT_NE(circle(reseeded).stats.mean_um, a.stats.mean_um) << name << ": another noise seed, another run";
  }
}

// On the rig, the tick's output lands read latency + the firmware's metered
// work + write latency after the latch: 100 + ~1 + 50 us -> the 160 us sub-step.
TEST(RealismCircle, RigOutputLandsAfterReadWorkAndWrite) {
  if (!fw::work_meter_enabled()) GTEST_SKIP() << "built with TNV_WORK_METER=OFF: the tick's work is not metered";
  emu::Scenario s = builtin("no-cut");
  s.io = emu::IoParams{.read_latency_us = 100.0, .write_latency_us = 50.0, .jitter_us = 0.0};
  std::string error;
  std::unique_ptr<HilRig> rig = HilRig::create(s, fw::default_firmware_config(), ControllerKind::rdvsc, error);
  ASSERT_TRUE(rig) << error;
  rig->home();
  ASSERT_EQ(rig->task.start_circle(circle_spec_for(s)), fw::CommandStatus::ok);
  int measured = 0;
  for (int k = 0; k < 2000 && measured < 20; ++k) {
    rig->tick();
    const emu::BoardOutputs out = rig->machine.board_outputs();
    if (out.dac_register[0] == out.dac_output[0]) continue;  // the code did not change this tick
    const std::int64_t work_ns = rig->charged().last_call_ns;
    ASSERT_GT(work_ns, 0);
    ASSERT_LT(work_ns, 10'000) << "a tick is about 1 us of modelled board time";
    int substeps = 0;
    while (rig->machine.board_outputs().dac_output[0] != out.dac_register[0] && substeps < 50) {
      rig->machine.advance_clocks(100);
      ++substeps;
    }
    EXPECT_EQ(substeps, 16) << "landed " << substeps * 10 << " us after the latch, work " << work_ns << " ns";
    ++measured;
  }
  EXPECT_EQ(measured, 20) << "too few ticks changed the X code";
}

}  // namespace
}  // namespace tnv::hil
