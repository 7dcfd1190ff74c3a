// tnvctl as a script sees it: exit codes (0 ok, 1 refused / failed, 2 bad
// input with nothing sent), one-line errors naming what is wrong, JSON,
// scripts on one emulated session, parameters persisting through storage.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "hal/axis.hpp"
#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv {
namespace {

using test::ToolRun;

using test::has;

std::string script_args(const std::filesystem::path& script) {
  std::string args = "--emu script ";
  return args.append(script.string());
}

TEST(TnvctlCli, ChoosingNoNodeOrBothTransportsIsBadInput) {
  const auto state = test::state_dir("transport");
  ToolRun r = test::tnvctl(state, "params list");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "--iface IFACE")) << r.err;
  EXPECT_TRUE(has(r.err, "--emu")) << r.err;
  EXPECT_TRUE(r.out.empty());
  r = test::tnvctl(state, "--iface can0 --emu status");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "excludes")) << r.err;
  EXPECT_EQ(test::tnvctl(state, "--emu-seed 3 status").exit_code, 2) << "--emu-seed needs --emu";
  EXPECT_EQ(test::tnvctl(state, "--emu --node 64 status").exit_code, 2);
  EXPECT_EQ(test::tnvctl(state, "").exit_code, 2);
  r = test::tnvctl(state, "--help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_TRUE(has(r.out, "Exit codes: 0 ok; 1 refused")) << "documented in --help";
  std::filesystem::remove_all(state);
}

TEST(TnvctlCli, AMissingInterfaceIsADeviceErrorNamingIt) {
  const auto state = test::state_dir("iface");
  const ToolRun r = test::tnvctl(state, "--iface tnvnosuchcan9 status");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(has(r.err, "tnvnosuchcan9: no such network interface")) << r.err;
  std::filesystem::remove_all(state);
}

TEST(TnvctlCli, BadParameterNamesAndValuesAreRefusedBeforeAnythingIsSent) {
  const auto state = test::state_dir("badparam");
  ToolRun r = test::tnvctl(state, "--emu params set x.sliding.gama=0.2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "no parameter 'x.sliding.gama' (did you mean x.sliding.gamma?)")) << r.err;
  r = test::tnvctl(state, "--emu params set x.sliding.gamma=2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "x.sliding.gamma: 2 is outside 0 .. 1")) << r.err;
  r = test::tnvctl(state, "--emu params set x.sliding.gamma=nan");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "not a finite number")) << r.err;
  r = test::tnvctl(state, "--emu params set x.controller=fuzzy");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "{pid, dvsc, rdvsc}")) << r.err;
  r = test::tnvctl(state, "--emu capture --channels pos_x,bogus --circle");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "unknown capture channel 'bogus'")) << r.err;
  std::filesystem::remove_all(state);
}

TEST(TnvctlCli, RefusalsByTheNodeExitWith1NamingTheErrorCodeAndTheParameter) {
  const auto state = test::state_dir("refused");
  // In range, but the set as a whole is invalid: gamma < min(1 - g, q) (S1 Theorem 5).
  ToolRun r = test::tnvctl(state, "--emu params set x.sliding.gamma=0.9");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(has(r.err, "refused 'commit': invalid")) << r.err;
  EXPECT_TRUE(has(r.err, "x.sliding.gamma")) << r.err;
  // An idle-only parameter while the circle runs: busy.
  const auto script = test::write_file(state / "busy.tnvctl", "circle --no-wait\nparams set x.controller=pid\n");
  r = test::tnvctl(state, script_args(script));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(has(r.err, "busy")) << r.err;
  EXPECT_TRUE(has(r.err, "x.controller can only change at rest")) << r.err;
  EXPECT_TRUE(has(r.err, "busy.tnvctl:2")) << "the failing line: " << r.err;
  std::filesystem::remove_all(state);
}

TEST(TnvctlCli, AScriptIsParsedWholeBeforeItsFirstLineRuns) {
  const auto state = test::state_dir("script");
  const auto storage = state / "node.params";
  const auto script = test::write_file(state / "bad.tnvctl", "params save\n\n# fine so far\nparams sett x=1\n");
  std::string args = "--emu --emu-storage ";
  const ToolRun r = test::tnvctl(state, args.append(storage.string()).append(" script ").append(script.string()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "bad.tnvctl:4:")) << r.err;
  EXPECT_FALSE(std::filesystem::exists(storage)) << "line 1 must not have run";
  // Values are checked before the first line too, not only the syntax.
  const auto bad_value = test::write_file(state / "value.tnvctl", "params save\nparams set x.sliding.gamma=2\n");
  std::string value_args = "--emu --emu-storage ";
  const ToolRun v = test::tnvctl(state, value_args.append(storage.string()).append(" script ").append(bad_value.string()));
  EXPECT_EQ(v.exit_code, 2);
  EXPECT_TRUE(has(v.err, "value.tnvctl:2: x.sliding.gamma: 2 is outside 0 .. 1")) << v.err;
  EXPECT_FALSE(std::filesystem::exists(storage)) << "line 1 must not have run";
  std::filesystem::remove_all(state);
}

TEST(TnvctlCli, ParamsGetTakesGlobsAndGroupsAndRefusesAPatternThatMatchesNothing) {
  const auto state = test::state_dir("globs");
  ToolRun r = test::tnvctl(state, "--emu --json params get '?.sliding.gamma' x.sliding.gamma");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["params"].size(), hal::kAxisCount) << "x.sliding.gamma named twice is read once";
  EXPECT_EQ(j["params"][0]["name"], "x.sliding.gamma");
  EXPECT_EQ(j["params"][1]["name"], "y.sliding.gamma");
  EXPECT_EQ(j["params"][2]["name"], "z.sliding.gamma");
  r = test::tnvctl(state, "--emu params get 'x.nothing*'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "no parameter matches 'x.nothing*'")) << r.err;
}

TEST(TnvctlCli, ExportThenImportRestoresTheSetAndAnEditedOrForeignFileIsRefused) {
  const auto state = test::state_dir("export");
  const auto file = state / "node1.toml";
  // One emulated node: export, change two parameters, import, read back.
  const auto script = test::write_file(state / "roundtrip.tnvctl",
                                       "params export " + file.string() +
                                           "\nparams set x.sliding.gamma=0.4375 y.controller=pid\n"
                                           "params import " + file.string() + "\nparams get x.sliding.gamma y.controller\n");
  ToolRun r = test::tnvctl(state, script_args(script));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  const ToolRun defaults = test::tnvctl(state, "--emu params get x.sliding.gamma y.controller");
  ASSERT_EQ(defaults.exit_code, 0) << defaults.err;
  EXPECT_TRUE(has(r.out, defaults.out)) << "the import put back the exported values:\n" << r.out << "\n" << defaults.out;
  EXPECT_TRUE(has(r.out, "(was 0.4375)")) << r.out;
  const std::string text = test::read_file(file);
  EXPECT_TRUE(has(text, "[node]\nid = 1\n")) << text;
  EXPECT_TRUE(has(text, "params_hash = \"fnv1a64:")) << text;

  // Importing onto a node that holds the set changes nothing.
  r = test::tnvctl(state, "--emu params import " + file.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "nothing to change")) << r.out;

  // An edited file needs --edited; a file from another node needs --any-node. Both: exit 2, nothing sent.
  std::string edited = text;
  const auto at = edited.find("\nx.sliding.gamma = ");
  ASSERT_NE(at, std::string::npos);
  edited.replace(at, edited.find('\n', at + 1) - at, "\nx.sliding.gamma = 0.5");
  const auto edited_file = test::write_file(state / "edited.toml", edited);
  r = test::tnvctl(state, "--emu params import " + edited_file.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "changed after the export")) << r.err;
  r = test::tnvctl(state, "--emu --json params import --edited " + edited_file.string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["params"][0]["value"], 0.5) << r.out;
  r = test::tnvctl(state, "--emu --node 2 params import " + file.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "exported from node 1, not node 2")) << r.err;
  // A directory, a missing file: refused before a node is opened.
  EXPECT_EQ(test::tnvctl(state, "--emu params import " + state.string()).exit_code, 2);
  EXPECT_EQ(test::tnvctl(state, "--emu params import " + (state / "absent.toml").string()).exit_code, 2);
  std::filesystem::remove_all(state);
}

TEST(TnvctlCli, SavedParametersSurviveTheProcessAndLoadRestoresThem) {
  const auto state = test::state_dir("storage");
  const auto script = test::write_file(state / "save.tnvctl",
                                       "params set x.sliding.eta_mm_s=1.5 y.pid.kp=400\nparams save\n"
                                       "params set x.sliding.eta_mm_s=2\n");
  ToolRun r = test::tnvctl(state, script_args(script));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(state / "tnvctl" / "emu-node.params")) << "default path under XDG_STATE_HOME";
  r = test::tnvctl(state, "--emu --json params get x.sliding.eta_mm_s y.pid.kp");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // A saved set changes every later --emu result: the tool says it loaded one, and how many differ.
  EXPECT_TRUE(has(r.err, "loaded the parameters saved in")) << r.err;
  EXPECT_TRUE(has(r.err, "(2 differ from a fresh node's")) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["params"][0]["value"], 1.5) << "the saved value, not the unsaved 2";
  EXPECT_EQ(j["params"][1]["value"], 400.0);
  const auto reload = test::write_file(state / "reload.tnvctl",
                                       "params set x.sliding.eta_mm_s=0.5\nparams load\nparams get x.sliding.eta_mm_s\n");
  r = test::tnvctl(state, script_args(reload));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "x.sliding.eta_mm_s = 1.5 mm/s")) << r.out;
  // The defaults saved: a fresh node's set, nothing to say.
  const auto reset = test::write_file(state / "reset.tnvctl", "params defaults\nparams save\n");
  ASSERT_EQ(test::tnvctl(state, script_args(reset)).exit_code, 0);
  r = test::tnvctl(state, "--emu status");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(has(r.err, "loaded the parameters saved in")) << r.err;
  // The node names its firmware: the version tnvctl --version prints (one project), and a build.
  const ToolRun version = test::tnvctl(state, "--version");
  ASSERT_EQ(version.out.rfind("tnvctl ", 0), 0u) << version.out;
  const std::string tool_version = version.out.substr(7, version.out.find('\n') - 7);
  EXPECT_TRUE(has(r.out, "(firmware " + tool_version + ", build ")) << r.out << " / " << version.out;
  std::filesystem::remove_all(state);
}

TEST(TnvctlCli, JsonErrorsCarryTheExitCodeAndTheMessage) {
  const auto state = test::state_dir("json");
  const ToolRun r = test::tnvctl(state, "--emu --json params set x.sliding.gamma=2");
  EXPECT_EQ(r.exit_code, 2);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["ok"], false);
  EXPECT_EQ(j["exit_code"], 2);
  EXPECT_TRUE(has(j["error"].get<std::string>(), "x.sliding.gamma")) << j.dump();
  std::filesystem::remove_all(state);
}

TEST(TnvctlCli, MotionsRunAndReportTheirEndState) {
  const auto state = test::state_dir("motion");
  const auto script = test::write_file(state / "motion.tnvctl",
                                       "enable\nmove --axis x --distance-mm 1 --speed-mm-s 5\n"
                                       "jog --axis y --speed-mm-s -2 --duration-s 0.2\nestop\nclear-faults\n");
  std::string args = "--emu --json script ";
  const ToolRun r = test::tnvctl(state, args.append(script.string()));
  ASSERT_EQ(r.exit_code, 0) << r.err << r.out;
  std::istringstream lines(r.out);
  std::string line;
  std::vector<nlohmann::json> out;
  while (std::getline(lines, line)) out.push_back(nlohmann::json::parse(line));
  ASSERT_EQ(out.size(), 6u) << r.out;  // five commands and the script
  EXPECT_EQ(out[1]["status"]["state"], "holding");
  EXPECT_EQ(out[2]["status"]["state"], "holding");
  EXPECT_GE(out[2]["frames"].get<int>(), 4) << "0.2 s of JOG frames every 50 ms, and the stop";
  EXPECT_EQ(out[3]["status"]["state"], "faulted");
  EXPECT_EQ(out[4]["state"], "disabled");
  std::filesystem::remove_all(state);
}

TEST(TnvctlCli, PlotComparesSavedCapturesWithoutANode) {
  const auto state = test::state_dir("plot");
  // A captured circle: one sample before the motion, then a turn of R = 6 mm.
  std::string csv = "t_s,pos_x_mm,pos_y_mm,ref_x_mm,ref_y_mm,contour_um,motion_tick\n";
  csv += "0.000,6.000000,0.000000,6.000000,0.000000,0,-1\n";
  for (int k = 0; k < 400; ++k) {
    const double a = 2.0 * std::acos(-1.0) * k / 400.0;
    const double e = k % 2 == 0 ? 0.5 : 1.5;
    char row[160];
    std::snprintf(row, sizeof row, "%.3f,%.6f,%.6f,%.6f,%.6f,%.1f,%d\n", (k + 1) * 1e-3, (6.0 + e * 1e-3) * std::cos(a),
                  (6.0 + e * 1e-3) * std::sin(a), 6.0 * std::cos(a), 6.0 * std::sin(a), e, k);
    csv += row;
  }
  const auto a = test::write_file(state / "a.csv", csv);
  const auto b = test::write_file(state / "b.csv", csv);
  std::string args = "plot --csv ";
  args.append(a.string()).append(" --csv ").append(b.string()).append(" --label first --label second --out ");
  args.append((state / "cmp.svg").string());
  ToolRun r = test::tnvctl(state, args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "first                    max 1.5000 um   mean 1.0000 um   std 0.5000 um")) << r.out;
  std::ifstream svg(state / "cmp.svg");
  std::stringstream figure;
  figure << svg.rdbuf();
  EXPECT_EQ(figure.str().rfind("<?xml", 0), 0u) << "an SVG document";
  EXPECT_NE(figure.str().find("second"), std::string::npos) << "both rows";
  const auto bad = test::write_file(state / "bad.csv", "t_s,pos_x_mm\n0,1\n0.001\n");
  std::string bad_args = "plot --csv ";
  r = test::tnvctl(state, bad_args.append(bad.string()).append(" --out x.svg"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(has(r.err, "bad.csv: line 3: 1 values, the header has 2")) << r.err;
  std::filesystem::remove_all(state);
}

TEST(TnvctlCli, DumpDbcNeedsNoNode) {
  const auto state = test::state_dir("dbc");
  const ToolRun r = test::tnvctl(state, "dump-dbc");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(has(r.out, "BO_ ")) << r.out.substr(0, 200);
  EXPECT_TRUE(has(r.out, "PARAM_REPLY")) << r.out.substr(0, 200);
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv
