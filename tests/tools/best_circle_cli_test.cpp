// tnv-hil best-circle --scenario: bad input is refused before anything runs
// (exit 2, one line on stderr, nothing on stdout); a table file gives the
// three columns (papers' R-DVSC+DDC, best, best with the observer off).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/tools/cli_runner.hpp"
#include "tests/tools/unique_temp_dir.hpp"

namespace tnv::test {
namespace {

std::size_t best_circle_cli_lines(const std::string& text) {
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

TEST(BestCircleCli, MissingTableFileIsBadInputNothingRun) {
  const CliRun r = run_tnv_hil("best-circle --seeds 1 --scenario /nonexistent/table.toml");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(best_circle_cli_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("table.toml"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("runs"), std::string::npos) << "progress printed: something ran\n" << r.err;
}

TEST(BestCircleCli, BadValueInTableFileNamesTheFieldNothingRun) {
  const test::UniqueTempDir dir("tnv-best-circle");
  const std::filesystem::path file = dir / "bad_table.toml";
  {
    std::ofstream out(file);
    out << "name = \"bad\"\n[plant.x]\ntau_s = -0.004\n";
  }
  // A good table first: it must not be run either when a later one is bad.
  const CliRun r = run_tnv_hil(std::string("best-circle --seeds 1 --scenario no-cut --scenario ") + file.string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(best_circle_cli_lines(r.err), 1u) << r.err;
  EXPECT_NE(r.err.find("plant.x.tau_s"), std::string::npos) << r.err;
}

TEST(BestCircleCli, UnknownTableNameIsBadInput) {
  const CliRun r = run_tnv_hil("best-circle --seeds 1 --scenario no-such-table");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_EQ(best_circle_cli_lines(r.err), 1u) << r.err;
}

TEST(BestCircleCli, TableFileGivesThreeColumnsOnThatTable) {
  std::string args = "best-circle --seeds 1 --json --scenario ";
  args += TNV_SOURCE_DIR;
  args += "/tests/data/tables/sticky.toml";
  const CliRun r = run_tnv_hil(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j.at("tables").size(), 1u);
  const nlohmann::json& t = j.at("tables").at(0);
  EXPECT_EQ(t.at("scenario"), "sticky");
  EXPECT_EQ(t.at("error"), "");
  // Identified on sticky itself: X's true tau is 8.5 ms (the reference's 5.36 ms).
  const double tau_x_s = t.at("identified").at(0).at("identification").at("tau_s").get<double>();
  EXPECT_NEAR(tau_x_s, 0.0085, 0.02 * 0.0085) << "identified tau_x " << tau_x_s * 1e3 << " ms";
  for (const char* column : {"rdvsc", "best", "best_observer_off"}) {
    const double max_um = t.at(column).at("max_um").get<double>();
    EXPECT_GT(max_um, 0.0) << column;
    EXPECT_LT(max_um, 10.0) << column << ": max " << max_um << " um";
  }
  EXPECT_NE(t.at("best").at("mean_um").get<double>(), t.at("best_observer_off").at("mean_um").get<double>());
}

}  // namespace
}  // namespace tnv::test
