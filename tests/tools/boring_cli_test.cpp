// `tnv-hil boring` as a script sees it: the issue's command line, JSON keys,
// exit codes, the plot.
#include <gtest/gtest.h>

#include "tests/tools/cli_runner.hpp"
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace tnv {
namespace {

using test::CliRun;

CliRun run_boring(const std::string& args) { return test::run_tnv_hil("boring " + args); }

TEST(BoringCli, TheIssuesCommandLineGivesTheRequiredJsonKeys) {
  const CliRun r = run_boring("--sigma-mm 0.016231 --alpha0 0.5 --parts 30 --change-at 11,21 --seeds 20 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  for (const char* key : {"bad_parts_mean", "bad_parts_max", "resets_mean", "segments", "seed1", "settings"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_GE(j["bad_parts_mean"].get<double>(), 1.0) << "part 1 is cut at S0 = 0.5 mm/rev: 0.285 mm at L = 310 mm";
  EXPECT_LE(j["bad_parts_mean"].get<double>(), static_cast<double>(j["bad_parts_max"].get<int>()));
  const auto& parts = j["seed1"]["parts"];
  ASSERT_EQ(parts.size(), 30u);
  EXPECT_EQ(parts[10]["true"]["alpha"].get<double>(), 0.7) << "part 11: the second set";
  EXPECT_EQ(parts[20]["true"]["alpha"].get<double>(), 0.6) << "part 21: the third set";
  for (const auto& p : parts) {
    ASSERT_EQ(p["positions"].size(), 2u);
    EXPECT_EQ(p["positions"][0]["overhang_mm"].get<double>(), 40.0);
    EXPECT_EQ(p["positions"][1]["overhang_mm"].get<double>(), 310.0);
    for (const char* key : {"infeed_mm_rev", "optimal_infeed_mm_rev", "true_deflection_mm", "measured_deflection_mm"})
      EXPECT_TRUE(p["positions"][0].contains(key)) << key;
    EXPECT_TRUE(p["estimate"].contains("c_mm"));
  }
  EXPECT_EQ(j["settings"]["gain_form"], "normalised");
  EXPECT_EQ(j["settings"]["reset_count"], "measurements");
  EXPECT_EQ(j["bad_fraction_by_part"].size(), 30u);
}

TEST(BoringCli, TextIsTheDefaultAndNamesTheSettings) {
  const CliRun r = run_boring("--sigma-mm 0.005 --alpha0 1.0 --seeds 3 --gain-form printed --reset-count parts");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("gain form printed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("parts out of d0"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("RESET"), std::string::npos) << "the large change resets P in seed 1";
}

// The node receives the reading in BORE_GAUGE's 0.1 um steps: eq. (11) at
// phi = 60 deg turns half a step into 0.05 um of deflection.
TEST(BoringCli, AnExactGaugeMeasuresTheTrueDeflectionToTheWiresResolution) {
  const CliRun r = run_boring("--sigma-mm 0.005 --alpha0 1.0 --gauge-sigma-mm 0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["settings"]["process_sigma_mm"].get<double>(), 0.0);
  EXPECT_EQ(j["settings"]["sigma_mm"].get<double>(), 0.005) << "the planner keeps --sigma-mm";
  EXPECT_EQ(j["planner"], "the node's planner over CAN (BORE_GAUGE)");
  int off_grid = 0;
  for (const auto& p : j["seed1"]["parts"])
    for (const auto& q : p["positions"]) {
      const double measured = q["measured_deflection_mm"].get<double>();
      EXPECT_NEAR(measured, q["true_deflection_mm"].get<double>(), 0.5e-4 + 1e-12) << "mm";
      off_grid += std::fabs(measured - q["true_deflection_mm"].get<double>()) > 1e-9 ? 1 : 0;
    }
  EXPECT_GT(off_grid, 0) << "the readings went through the wire's 0.1 um steps";
}

TEST(BoringCli, DirectRunsThePlannerInProcessAndTheNodeRefusesWhatItDoesNotCarry) {
  const CliRun direct = run_boring("--seeds 3 --planner direct --startup-in-rls --json");
  ASSERT_EQ(direct.exit_code, 0) << direct.err;
  EXPECT_EQ(nlohmann::json::parse(direct.out)["planner"], "firmware planner in this process, at the node's resolution");
  for (const char* args : {"--startup-in-rls", "--log-base decimal"}) {
    const CliRun node = run_boring(std::string("--seeds 3 ") + args);
    EXPECT_EQ(node.exit_code, 2) << args << ": " << node.err;
    EXPECT_NE(node.err.find("--planner direct"), std::string::npos) << node.err;
    EXPECT_TRUE(node.out.empty()) << args;
  }
}

TEST(BoringCli, OnTheMachineEveryPartIsAPassAndWhatItCannotRunIsRefused) {
  const CliRun r = run_boring("--on-machine --parts 2 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_NE(j["planner"].get<std::string>().find("emulated machine"), std::string::npos) << j["planner"];
  const auto& part1 = j["seed1"]["parts"][0];
  EXPECT_TRUE(part1["bad"].get<bool>()) << "cut at S0";
  for (const auto& q : part1["positions"]) {
    // The bar passed both gauge depths at S0 = 0.5 mm/rev (50 mm/s at 6000 rpm) and at their overhangs.
    EXPECT_NEAR(q["cut_infeed_mm_rev"].get<double>(), 0.5, 0.015) << q.dump();
    EXPECT_NEAR(q["cut_overhang_mm"].get<double>(), q["overhang_mm"].get<double>(), 0.01) << q.dump();
  }
  EXPECT_GT(part1["pass_error_mm"]["max"].get<double>(), 0.16) << "S0 bends the bottom 0.17 mm beyond d0";
  for (const char* args : {"--on-machine --planner direct", "--on-machine --spindle-rpm 50",
                           "--on-machine --startup-in-rls"}) {
    const CliRun refused = run_boring(args);
    EXPECT_EQ(refused.exit_code, 2) << args << ": " << refused.err;
    EXPECT_TRUE(refused.out.empty()) << args;
  }
}

TEST(BoringCli, BadInputExitsWith2AndRunsNothing) {
  for (const char* args : {"--sigma-mm -1", "--sigma-mm nan", "--alpha0 0", "--change-at 21,11", "--change-at x",
                           "--change-at 1", "--change-at 5,10,20", "--parts 0", "--seeds 0", "--gain-form fuzzy",
                           "--reset-count sometimes", "--s0 5", "--gauge-sigma-mm -0.1", "--planner remote"}) {
    const CliRun r = run_boring(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << args;
  }
  const CliRun r = run_boring("--change-at 21,11");
  EXPECT_NE(r.err.find("change_at"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  const CliRun s0 = run_boring("--s0 5");
  EXPECT_NE(s0.err.find("nominal_infeed_mm_rev"), std::string::npos) << s0.err;
}

TEST(BoringCli, WritesThePlotAndRefusesAnUnwritableOneBeforeTheRun) {
  const auto dir = std::filesystem::temp_directory_path() / ("tnv_hil_boring_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const CliRun r = run_boring("--seeds 5 --plot " + (dir / "b.svg").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream svg(dir / "b.svg");
  std::stringstream figure;
  figure << svg.rdbuf();
  EXPECT_EQ(figure.str().rfind("<?xml", 0), 0u) << "an SVG document";
  EXPECT_NE(figure.str().find("<svg"), std::string::npos);
  const CliRun refused = run_boring("--plot /nonexistent/dir/b.svg");
  EXPECT_EQ(refused.exit_code, 2) << "a bad command line: nothing was run";
  EXPECT_NE(refused.err.find("does not exist"), std::string::npos) << refused.err;
  EXPECT_EQ(refused.out, "") << "nothing was run";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tnv
