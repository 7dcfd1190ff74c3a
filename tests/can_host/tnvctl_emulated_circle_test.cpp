// The test: `tnvctl --emu` sets gamma, runs a circle, captures it,
// and the captured contour error equals what `tnv-hil circle` reports for
// the same settings (to float32 rounding of the captured values).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv {
namespace {

using test::ToolRun;

// The JSON object of one command from a `--json script` run (one per line).
nlohmann::json command_json(const std::string& out, const std::string& command) {
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
    if (!j.is_discarded() && j.value("command", "") == command) return j;
  }
  return {};
}

TEST(TnvctlEmulated, CapturedContourErrorWithGammaEqualsTnvHilCircle) {
  const auto state = test::state_dir("gamma");
  // 0.25 is a float32: the node stores exactly what tnv-hil is given.
  std::string text = "# both axes' gamma, then a captured circle\n";
  text += "params set x.sliding.gamma=0.25 y.sliding.gamma=0.25\n";
  text += "capture --channels pos_x,pos_y,ref_x,ref_y,contour,motion_tick --circle --csv ";
  text.append((state / "circle.csv").string()).append(" --plot ").append((state / "circle.svg").string()) += '\n';
  const auto script = test::write_file(state / "gamma.tnvctl", text);
  std::string args = "--emu --json script ";
  const ToolRun ctl = test::tnvctl(state, args.append(script.string()));
  ASSERT_EQ(ctl.exit_code, 0) << ctl.err << ctl.out;
  const nlohmann::json set = command_json(ctl.out, "params set");
  ASSERT_TRUE(set.contains("params")) << ctl.out;
  EXPECT_EQ(set["params"][0]["value"], 0.25);
  EXPECT_EQ(set["params"][1]["value"], 0.25);
  const nlohmann::json capture = command_json(ctl.out, "capture");
  ASSERT_TRUE(capture.contains("circle")) << ctl.out;
  const nlohmann::json& got = capture["circle"];

  const ToolRun hil = test::tnv_hil("circle --gamma 0.25 --json");
  ASSERT_EQ(hil.exit_code, 0) << hil.err;
  const nlohmann::json expected = nlohmann::json::parse(hil.out)["results"][0];
  for (const char* stat : {"max_um", "mean_um", "std_um"}) {
    EXPECT_NEAR(got[stat].get<double>(), expected[stat].get<double>(), 1e-4)
        << stat << ": tnvctl capture " << got[stat] << " um, tnv-hil " << expected[stat] << " um";
  }
  // And gamma mattered: the papers' gamma gives another circle.
  const ToolRun paper = test::tnv_hil("circle --json");
  ASSERT_EQ(paper.exit_code, 0);
  EXPECT_GT(std::fabs(nlohmann::json::parse(paper.out)["results"][0]["max_um"].get<double>() - got["max_um"].get<double>()),
            1e-3);
  EXPECT_EQ(capture["rerequests"], 0);
  EXPECT_TRUE(std::filesystem::exists(state / "circle.csv"));
  std::ifstream svg(state / "circle.svg");
  std::stringstream figure;
  figure << svg.rdbuf();
  EXPECT_NE(figure.str().find("<svg"), std::string::npos);
  EXPECT_NE(figure.str().find("contour error"), std::string::npos) << "the circle figure";
  std::filesystem::remove_all(state);
}

TEST(TnvctlEmulated, TnvHilRefusesAGammaTheFirmwareWouldRefuse) {
  const ToolRun r = test::tnv_hil("circle --gamma 0.9");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << "nothing may run";
  EXPECT_NE(r.err.find("gamma < min(1 - g, q)"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tnv
