// `tnvctl identify` / `tnvctl autotune` on the emulated controller, run as
// a user runs them: identification within the issue's tolerances on three
// tables, a dry run that changes nothing, an applied design that satisfies
// the theorems and reads back equal, and the refusals (no TTY, disabled).
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "emulator/scenario_file.hpp"
#include "hal/axis.hpp"
#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv::tnvctl_autotune_test {
namespace {

using test::ToolRun;

// The JSON object of one command from a `--json script` run (one per line).
nlohmann::json script_json(const std::string& out, const std::string& command, int nth = 0) {
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    if (!j.is_discarded() && j.is_object() && j.value("command", "") == command && nth-- == 0) return j;
  }
  return {};
}

ToolRun run_script(const std::filesystem::path& state, const std::string& global, const std::string& lines) {
  const auto script = test::write_file(state / "run.tnvctl", lines);
  std::string args = "--emu --json ";
  args.append(global).append(" script ").append(script.string()).append(" < /dev/null");
  return test::tnvctl(state, args);
}

std::string data_file(const char* name) {
  std::string path = TNV_SOURCE_DIR;
  return path.append("/tests/data/tables/").append(name);
}

struct Table {
  const char* label;
  std::string scenario;  // --emu-scenario
};

TEST(TnvctlAutotune, IdentifyOnThreeTablesIsWithinTheIssueTolerances) {
  const auto state = test::state_dir("identify3");
  const Table tables[] = {{"reference (no-cut)", "no-cut"},
                          {"slow-heavy", data_file("slow-heavy.toml")},
                          {"sticky", data_file("sticky.toml")}};
  for (const Table& t : tables) {
    const emu::ScenarioResult truth = emu::resolve_scenario(t.scenario);
    ASSERT_TRUE(truth.scenario) << t.label << ": " << truth.error;
    const ToolRun r = run_script(state, "--emu-scenario " + t.scenario, "enable\nidentify --axis both\n");
    ASSERT_EQ(r.exit_code, 0) << t.label << ": " << r.err << r.out;
    const nlohmann::json id = script_json(r.out, "identify");
    ASSERT_TRUE(id.contains("axes")) << r.out;
    ASSERT_EQ(id["axes"].size(), hal::kAxisCount) << "both: every axis";
    for (std::size_t a = 0; a < hal::kAxisCount; ++a) {
      const nlohmann::json& got = id["axes"][a];
      const emu::AxisPlantParams& p = truth.scenario->plant[a];
      const std::string what = std::string(t.label) + (a == 0 ? " x" : " y");
      ASSERT_TRUE(got["ok"].get<bool>()) << what << ": " << got["error"];
      EXPECT_NEAR(got["tau_s"].get<double>(), p.tau_s, 0.02 * p.tau_s)
          << what << ": tau " << got["tau_s"].get<double>() * 1e3 << " ms, true " << p.tau_s * 1e3 << " ms";
      EXPECT_NEAR(got["gain"].get<double>(), p.gain, 0.02 * p.gain)
          << what << ": K " << got["gain"] << ", true " << p.gain;
      EXPECT_NEAR(got["coulomb_mm_s"].get<double>(), p.coulomb_mm_s, 0.15 * p.coulomb_mm_s)
          << what << ": f_c " << got["coulomb_mm_s"] << " mm/s, true " << p.coulomb_mm_s << " mm/s";
      EXPECT_NEAR(got["stiction_mm_s"].get<double>(), p.stiction_mm_s, 0.15 * p.stiction_mm_s)
          << what << ": f_s " << got["stiction_mm_s"] << " mm/s, true " << p.stiction_mm_s << " mm/s";
    }
  }
  std::filesystem::remove_all(state);
}

// Every parameter autotune would write, as `params get` arguments.
std::string autotune_param_names(const nlohmann::json& autotune) {
  std::string names;
  for (const nlohmann::json& axis : autotune["axes"])
    for (const nlohmann::json& c : axis["changes"]) names.append(" ").append(c["name"].get<std::string>());
  return names;
}

TEST(TnvctlAutotune, DryRunShowsTheChangeAndAppliesNothing) {
  const auto state = test::state_dir("dryrun");
  const ToolRun first = run_script(state, "", "enable\nautotune --axis both --dry-run\n");
  ASSERT_EQ(first.exit_code, 0) << first.err << first.out;
  const nlohmann::json plan = script_json(first.out, "autotune");
  ASSERT_EQ(plan["axes"].size(), hal::kAxisCount) << first.out;
  EXPECT_FALSE(plan["applied"].get<bool>());
  const std::string names = autotune_param_names(plan);
  ASSERT_GT(names.size(), 100u);

  std::string lines = "enable\nparams get";
  lines.append(names).append("\nautotune --axis both --dry-run\nparams get").append(names).append("\n");
  const ToolRun r = run_script(state, "", lines);
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json before = script_json(r.out, "params get", 0);
  const nlohmann::json after = script_json(r.out, "params get", 1);
  ASSERT_TRUE(before.contains("params")) << r.out;
  EXPECT_EQ(before["params"], after["params"]) << "the dry run changed a parameter";
  // And the design does differ from the defaults: the dry run had something to not apply.
  std::size_t differing = 0;
  for (const nlohmann::json& axis : plan["axes"])
    for (const nlohmann::json& c : axis["changes"])
      differing += static_cast<float>(c["old"].get<double>()) != static_cast<float>(c["new"].get<double>());
  EXPECT_GT(differing, 10u);
  std::filesystem::remove_all(state);
}

TEST(TnvctlAutotune, YesAppliesADesignThatMeetsTheTheoremsAndReadsBackEqual) {
  const auto state = test::state_dir("yes");
  const ToolRun probe = run_script(state, "", "enable\nautotune --axis both --dry-run\n");
  ASSERT_EQ(probe.exit_code, 0) << probe.err;
  const std::string names = autotune_param_names(script_json(probe.out, "autotune"));

  std::string lines = "enable\nautotune --axis both --yes\nparams get";
  const ToolRun r = run_script(state, "", lines.append(names).append("\n"));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json tune = script_json(r.out, "autotune");
  ASSERT_TRUE(tune["applied"].get<bool>()) << r.out;
  const nlohmann::json after = script_json(r.out, "params get")["params"];
  std::size_t k = 0;
  for (const nlohmann::json& axis : tune["axes"]) {
    const std::string ax = axis["axis"];
    const nlohmann::json& s = axis["design"]["sliding"];
    const double eta = s["eta_mm_s"], phi = s["phi_mm_s"], q = s["q"], g = s["g"], gamma = s["gamma"];
    EXPECT_GT(eta, 0.0) << ax;
    EXPECT_TRUE(q > 0.0 && q < 1.0) << ax << ": q " << q;
    EXPECT_TRUE(g > 0.0 && g < 1.0) << ax << ": g " << g;
    EXPECT_GT(phi, eta / (q + 1.0)) << ax << ": Theorem 2 wants phi > eta/(q+1): phi " << phi << " mm/s";
    EXPECT_TRUE(gamma > 0.0 && gamma < std::min(1.0 - g, q)) << ax << ": Theorem 5: gamma " << gamma;
    for (const char* loop : {"rdvsc", "dvsc", "pid"}) {
      const nlohmann::json& pred = axis["predicted"][loop]["new"];
      ASSERT_TRUE(pred["ok"].get<bool>()) << ax << " " << loop << ": " << pred;
      EXPECT_LT(pred["spectral_radius"].get<double>(), 1.0) << ax << " " << loop;
    }
    // The observer's gains are designed (on or off): their error dynamics must be stable.
    const nlohmann::json& observer = axis["predicted"]["observer"]["new"];
    if (observer["ok"].get<bool>()) {
      EXPECT_LT(observer["spectral_radius"].get<double>(), 1.0) << ax << " observer";
    }
    for (const nlohmann::json& c : axis["changes"]) {
      ASSERT_LT(k, tune["read_back"].size());
      const std::string name = c["name"];
      const auto design = static_cast<float>(c["new"].get<double>());
      EXPECT_EQ(static_cast<float>(tune["read_back"][k]["value"].get<double>()), design) << name;
      const nlohmann::json& got = after[k]["value"];
      ASSERT_EQ(after[k]["name"], name);
      if (got.is_number())
        EXPECT_EQ(static_cast<float>(got.get<double>()), design) << name << " read back by `params get`";
      else
        EXPECT_EQ(got.get<std::string>(), design != 0.0f ? "on" : "off") << name;
      ++k;
    }
  }
  EXPECT_EQ(k, after.size());
  std::filesystem::remove_all(state);
}

TEST(TnvctlAutotune, AStructuralModeSeenByTheToolAccelerometerSetsTheShaper) {
  const auto state = test::state_dir("mode");
  const emu::ScenarioResult truth = emu::resolve_scenario("flex-30");
  ASSERT_TRUE(truth.scenario) << truth.error;
  const emu::AxisPlantParams& x = truth.scenario->plant[0];
  ASSERT_GT(x.mode_hz, 0.0) << "flex-30 has no x mode any more";
  const ToolRun r = run_script(state, "--emu-scenario flex-30",
                               "enable\nautotune --axis x --yes\nparams get x.shaper.type x.shaper.freq_hz "
                               "x.shaper.zeta x.shaper.enable\n");
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const nlohmann::json shaper = script_json(r.out, "params get")["params"];
  ASSERT_EQ(shaper.size(), 4u) << r.out;
  EXPECT_EQ(shaper[0]["value"], "zvd");
  EXPECT_NEAR(shaper[1]["value"].get<double>(), x.mode_hz, 0.05 * x.mode_hz) << "Hz";
  EXPECT_NEAR(shaper[2]["value"].get<double>(), x.mode_zeta, 0.5 * x.mode_zeta);
  EXPECT_EQ(shaper[3]["value"], "on");
  std::filesystem::remove_all(state);
}

TEST(TnvctlAutotune, WithoutYesAndWithoutATerminalNothingIsSent) {
  const auto state = test::state_dir("notty");
  const ToolRun r = test::tnvctl(state, "--emu autotune --axis x < /dev/null");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--yes"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("nothing was sent"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  std::filesystem::remove_all(state);
}

TEST(TnvctlAutotune, IdentifyOnADisabledNodeSaysItMustBeEnabled) {
  const auto state = test::state_dir("disabled");
  const ToolRun r = test::tnvctl(state, "--emu identify --axis x");
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("busy"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("enabled and holding"), std::string::npos) << r.err;
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv::tnvctl_autotune_test
