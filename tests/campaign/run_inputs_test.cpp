#include "tools/campaign/run_inputs.hpp"

#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"

namespace tnv::campaign {
namespace {

TEST(CampaignRunInputs, ScenarioKeysGoOnTheBaseScenarioAndParametersOnTheFirmware) {
  const emu::Scenario base = *emu::builtin_scenario("cut-1200");
  nlohmann::ordered_json values = {{"plant.x.gain", 1.1}, {"x.sliding.gamma", 0.4}, {"cutting.flutes", 4}};
  const RunSetup s = resolve_run_inputs(base, {{"plant.x.gain", false}, {"x.sliding.gamma", true}, {"cutting.flutes", false}},
                                        values);
  ASSERT_TRUE(s.scenario) << s.error;
  EXPECT_DOUBLE_EQ(s.scenario->plant[0].gain, 1.1);
  EXPECT_EQ(s.scenario->cutting.flutes, 4);
  EXPECT_TRUE(s.scenario->cutting.enabled);                                      // the base's, kept
  EXPECT_DOUBLE_EQ(s.scenario->cutting.spindle_rpm, base.cutting.spindle_rpm);  // likewise
  EXPECT_NEAR(s.config->axis[0].sliding.gamma, 0.4, 1e-6);
  EXPECT_NE(s.config->axis[1].sliding.gamma, s.config->axis[0].sliding.gamma);  // only x was set
}

TEST(CampaignRunInputs, ABadValueNamesItsInputAndGivesNoSetup) {
  const emu::Scenario base = *emu::builtin_scenario("no-cut");
  RunSetup s = resolve_run_inputs(base, {{"plant.y.tau_s", false}}, {{"plant.y.tau_s", -0.1}});
  EXPECT_FALSE(s.scenario);
  EXPECT_FALSE(s.config);
  EXPECT_EQ(s.bad_input, "plant.y.tau_s");
  EXPECT_EQ(s.error.rfind("plant.y.tau_s: must be > 0", 0), 0u) << s.error;

  s = resolve_run_inputs(base, {{"x.sliding.gamma", true}}, {{"x.sliding.gamma", 7.0}});
  EXPECT_FALSE(s.config);
  EXPECT_EQ(s.bad_input, "x.sliding.gamma");

  s = resolve_run_inputs(base, {{"plant.w.gain", false}}, {{"plant.w.gain", 1.0}});
  EXPECT_FALSE(s.scenario);
  EXPECT_TRUE(s.unknown_key);
}

TEST(CampaignRunInputs, ValuesAreWrittenAsTomlAndAsParameterText) {
  EXPECT_EQ(toml_value_text(2.0), "2.0");  // a float stays a float in TOML
  EXPECT_EQ(toml_value_text(2), "2");
  EXPECT_EQ(toml_value_text(0.1), "0.1");
  EXPECT_EQ(toml_value_text(true), "true");
  EXPECT_EQ(toml_value_text("pid"), "\"pid\"");
  EXPECT_EQ(param_value_text("pid"), "pid");
  EXPECT_EQ(param_value_text(0.35), "0.35");
}

}  // namespace
}  // namespace tnv::campaign
