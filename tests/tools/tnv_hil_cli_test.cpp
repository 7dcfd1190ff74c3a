// tnv-hil as a script sees it: exit codes, one-line errors, JSON on stdout.
#include <gtest/gtest.h>

#include "tests/tools/cli_runner.hpp"
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace tnv {
namespace {

using test::CliRun;

using test::run_tnv_hil;

std::filesystem::path temp_file(const std::string& name, const std::string& content) {
  const auto p = std::filesystem::temp_directory_path() / (std::to_string(::getpid()) + "_" + name);
  std::ofstream(p) << content;
  return p;
}

TEST(TnvHilCli, BadScenarioFileIsOneLineNamingFileLineAndKeyWithExitCode2) {
  const auto path = temp_file("bad.toml", "name = \"x\"\n[plant.x]\ntau_s = 0.005\ntua_s = 1.0\n");
  const CliRun r = run_tnv_hil("circle --scenario " + path.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty()) << "nothing may run: " << r.out;
  EXPECT_NE(r.err.find(path.filename().string()), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(":4"), std::string::npos) << "line number: " << r.err;
  EXPECT_NE(r.err.find("tua_s"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  std::filesystem::remove(path);
}

TEST(TnvHilCli, NonFiniteAndOutOfRangeValuesAreRefused) {
  const auto nan_path = temp_file("nan.toml", "[circle]\nfeed_mm_s = nan\n");
  CliRun r = run_tnv_hil("circle --scenario " + nan_path.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("feed_mm_s"), std::string::npos) << r.err;
  const auto neg_path = temp_file("neg.toml", "[plant.y]\ntau_s = -0.001\n");
  r = run_tnv_hil("circle --scenario " + neg_path.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("tau_s"), std::string::npos) << r.err;
  std::filesystem::remove(nan_path);
  std::filesystem::remove(neg_path);
}

TEST(TnvHilCli, MissingScenarioAndBadOptionsExitWith2) {
  EXPECT_EQ(run_tnv_hil("circle --scenario /nonexistent/nothing.toml").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("circle --controller fuzzy").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("table3 --seeds 0").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("").exit_code, 2);
  EXPECT_EQ(run_tnv_hil("--help").exit_code, 0);
}

TEST(TnvHilCli, Table3JsonHasTwelveRowsAndThePidGains) {
  const CliRun r = run_tnv_hil("table3 --seeds 1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["results"].size(), 12u);
  for (const auto& row : j["results"]) {
    for (const char* key : {"scenario", "controller", "max_um", "mean_um", "std_um"}) EXPECT_TRUE(row.contains(key)) << key;
    EXPECT_GT(row["max_um"].get<double>(), row["mean_um"].get<double>());
  }
  EXPECT_TRUE(j["pid_gains"]["x"].contains("kp_per_s"));
  EXPECT_NE(r.err.find("[table3]"), std::string::npos) << "progress goes to stderr";
}

TEST(TnvHilCli, RefusesAFigureOfAnUnknownFormatBeforeTheRun) {
  const CliRun r = run_tnv_hil("circle --plot " + (std::filesystem::temp_directory_path() / "c.gif").string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(".svg, .png or .pdf"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "") << "nothing was run";
}

TEST(TnvHilCli, CircleWritesPlotAndCsv) {
  const auto dir = std::filesystem::temp_directory_path() / ("tnv_hil_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const CliRun r = run_tnv_hil("circle --controller pid --scenario cut-1500 --json --plot " + (dir / "c.svg").string() +
                    " --csv " + (dir / "c.csv").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["results"][0]["controller"], "pid");
  std::ifstream svg(dir / "c.svg");
  std::stringstream figure;
  figure << svg.rdbuf();
  EXPECT_EQ(figure.str().rfind("<?xml", 0), 0u) << "an SVG document";
  EXPECT_NE(figure.str().find("<svg"), std::string::npos);
  EXPECT_NE(figure.str().find("contour error (\u00b5m)"), std::string::npos) << "micrometres on the axis";
  EXPECT_TRUE(std::filesystem::exists(dir / "c.plot.json")) << "the figure's data, kept beside it";
  std::ifstream csv(dir / "c.csv");
  std::string line;
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  EXPECT_GT(lines, 18'000) << "one row per tick of motion";
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tnv
