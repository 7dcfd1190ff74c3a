// `tnvctl bore` as an operator uses it on the emulated node: one part's
// readings in, the next part's infeeds out (text and --json), the learning
// kept across processes by `params save`, refusals with exit 1 naming the
// reason, bad readings exit 2 with nothing sent.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/can_host/tnvctl_runner.hpp"

namespace tnv {
namespace {

using test::ToolRun;

bool says(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(TnvctlBore, APartsReadingsGiveTheNextPartsInfeedsAndTheLearningSurvivesASave) {
  const auto state = test::state_dir("bore-gauge");
  ToolRun r = test::tnvctl(state, "--emu bore status");
  EXPECT_EQ(r.exit_code, 1) << "the planner is off by default";
  EXPECT_TRUE(says(r.err, "not_ready: the planner is off (bore.enable)")) << r.err;
  const auto script = test::write_file(state / "bore.tnvctl",
                                       "params set bore.enable=1\n"
                                       "bore status\n"
                                       "bore gauge --top-mm 0.0485 --bottom-mm 0.1689\n"
                                       "params save\n");
  r = test::tnvctl(state, "--emu script " + script.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(says(r.out, "infeed for the part to cut now: 0.50000 mm/rev at L1 = 40 mm")) << r.out;
  EXPECT_TRUE(says(r.out, "part 1 recorded (start-up part, eq. (10)): out of band top no, bottom yes")) << r.out;

  // A new process: the node loads its image with the learning in it.
  r = test::tnvctl(state, "--emu --json bore gauge --top-mm 0.0102 --bottom-mm -0.0213");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  const nlohmann::json& b = j["bore"];
  EXPECT_EQ(b["op"], "record");
  EXPECT_EQ(b["part"], 2) << "bore.parts + 1, read from the node";
  EXPECT_EQ(b["parts"], 2);
  EXPECT_EQ(b["startup"], false);
  EXPECT_EQ(b["started"], true);
  EXPECT_EQ(b["out_of_band"]["top"], false);
  EXPECT_EQ(b["overhang_mm"]["bottom"], 310.0);
  const double top = b["infeed_mm_rev"]["top"].get<double>();
  const double bottom = b["infeed_mm_rev"]["bottom"].get<double>();
  EXPECT_GT(top, bottom) << "the longer overhang deflects more: less infeed (eq. (3), beta > 0)";
  EXPECT_GT(bottom, 0.005);
  EXPECT_LT(top, 0.5);
  EXPECT_GT(b["estimate"]["beta"].get<double>(), 0.0);

  // Not saved this time: the next process starts from the image of part 1.
  r = test::tnvctl(state, "--emu --json params get bore.parts");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["params"][0]["value"], 1);
  std::filesystem::remove_all(state);
}

TEST(TnvctlBore, ARepeatedPartIsRefusedWithExit1AndARestartStartsAgain) {
  const auto state = test::state_dir("bore-refused");
  const auto script = test::write_file(state / "bore.tnvctl",
                                       "params set bore.enable=1\n"
                                       "bore gauge --top-mm 0.0485 --bottom-mm 0.1689 --part 1\n"
                                       "bore gauge --top-mm 0.0485 --bottom-mm 0.1689 --part 1\n");
  ToolRun r = test::tnvctl(state, "--emu script " + script.string());
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_TRUE(says(r.err, "refused 'bore record of part 1': out_of_range (field part): not the next part")) << r.err;
  const auto again = test::write_file(state / "again.tnvctl",
                                      "params set bore.enable=1\n"
                                      "bore gauge --top-mm 0.0485 --bottom-mm 0.1689\n"
                                      "bore restart\n"
                                      "bore status\n");
  r = test::tnvctl(state, "--emu script " + again.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(says(r.out, "planner restarted: the next part is the start-up part")) << r.out;
  EXPECT_TRUE(says(r.out, "parts recorded 0, resets 0")) << r.out;
  std::filesystem::remove_all(state);
}

TEST(TnvctlBore, AReadingTheMessageCannotCarryExits2WithNothingSent) {
  const auto state = test::state_dir("bore-bad");
  for (const char* args : {"bore gauge --top-mm 3.5 --bottom-mm 0", "bore gauge --top-mm 0 --bottom-mm nan",
                           "bore gauge --top-mm 0", "bore gauge --top-mm 0 --bottom-mm 0 --part 0", "bore"}) {
    const ToolRun r = test::tnvctl(state, std::string("--emu ") + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
  }
  EXPECT_TRUE(says(test::tnvctl(state, "--emu bore gauge --top-mm 3.5 --bottom-mm 0").err, "--top-mm"));
  std::filesystem::remove_all(state);
}

}  // namespace
}  // namespace tnv
