// tnvctl freq-response and tnv-hil freq-response (issue 17) as processes:
// the JSON shape ("points" with freq_hz, gain_db, phase_deg, coherence;
// "margins" with gain_db, phase_deg, crossover_hz), a bad option refused
// before anything runs, the plot path checked first.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv::test {
namespace {

void expect_freq_shape(const nlohmann::json& j, const std::string& who) {
  ASSERT_TRUE(j.contains("points") && j["points"].is_array()) << who << ": " << j.dump();
  ASSERT_FALSE(j["points"].empty()) << who;
  double previous_hz = 0.0;
  for (const nlohmann::json& p : j["points"]) {
    for (const char* key : {"freq_hz", "gain_db", "phase_deg", "coherence"})
      ASSERT_TRUE(p.contains(key) && p[key].is_number()) << who << ": point without " << key << ": " << p.dump();
    EXPECT_GT(p["freq_hz"].get<double>(), previous_hz) << who << ": points not in rising frequency";
    previous_hz = p["freq_hz"].get<double>();
    EXPECT_GE(p["coherence"].get<double>(), 0.0) << who;
    EXPECT_LE(p["coherence"].get<double>(), 1.0) << who;
  }
  ASSERT_TRUE(j.contains("margins") && j["margins"].is_object()) << who;
  for (const char* key : {"gain_db", "phase_deg", "crossover_hz"})
    ASSERT_TRUE(j["margins"].contains(key)) << who << ": margins without " << key;
  EXPECT_TRUE(j["margins"]["crossover_hz"].is_number()) << who << ": no crossover measured: " << j["margins"].dump();
}

TEST(FreqResponseCli, TnvctlJsonHasPointsAndMargins) {
  const auto state = state_dir("freq_json");
  const ToolRun r = tnvctl(state, "--emu --emu-scenario " TNV_SOURCE_DIR
                                  "/tests/data/tables/no-friction.toml freq-response --axis y --loop closed --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  expect_freq_shape(j, "tnvctl");
  EXPECT_EQ(j["loop"], "closed");
  EXPECT_EQ(j["axis"], "y");
  EXPECT_TRUE(j["ok"].get<bool>());
}

TEST(FreqResponseCli, TnvHilJsonHasPointsAndMarginsAndTheScenario) {
  const ToolRun r = tnv_hil("freq-response --axis x --scenario " TNV_SOURCE_DIR
                            "/tests/data/tables/no-friction.toml --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  expect_freq_shape(j, "tnv-hil");
  EXPECT_EQ(j["loop"], "plant");
  EXPECT_EQ(j["excitation"], "multisine_open");
  EXPECT_NE(j["scenario"].get<std::string>().find("no-friction"), std::string::npos);
}

TEST(FreqResponseCli, BadOptionsAreRefusedBeforeAnythingRuns) {
  const auto state = state_dir("freq_bad");
  ToolRun r = tnvctl(state, "--emu freq-response --axis x --loop-f-max 600");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "f_max_hz")) << r.err;
  r = tnvctl(state, "--emu freq-response --axis x --plot /nonexistent-dir/bode.svg");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = tnv_hil("freq-response --scenario no-such-scenario");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  r = tnv_hil("freq-response --duration 0.05");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(has(r.err, "duration_s")) << r.err;
}

}  // namespace
}  // namespace tnv::test
