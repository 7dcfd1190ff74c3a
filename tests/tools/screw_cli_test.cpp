// tnv-hil screw-map / screw-fit as a user runs them: measure, write the
// file, fit it again, and feed the parameters to a circle; a bad file is
// refused with its line and nothing is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/tools/cli_runner.hpp"

namespace tnv::test {
namespace {

TEST(ScrewCli, MeasuresFitsAndTheParameterFileDrivesACircle) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("tnv-screw-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string gauge = (dir / "x.csv").string(), params = (dir / "x.toml").string();
  const CliRun map = run_tnv_hil("screw-map --axis x --length-mm 30 --start-mm -15 --json --gauge-out " + gauge +
                                 " --params-out " + params);
  ASSERT_EQ(map.exit_code, 0) << map.err;
  const nlohmann::json m = nlohmann::json::parse(map.out);
  EXPECT_NEAR(m["backlash_um"].get<double>(), 10.0, 2.5);
  EXPECT_EQ(m["params"]["x.screw.turn_period_mm"], 10.0);

  // The file (1 nm resolution) refits to the same numbers.
  const CliRun fit = run_tnv_hil("screw-fit " + gauge + " --json");
  ASSERT_EQ(fit.exit_code, 0) << fit.err;
  EXPECT_NEAR(nlohmann::json::parse(fit.out)["lead_um_per_m"].get<double>(), m["lead_um_per_m"].get<double>(), 0.02);

  const CliRun circle = run_tnv_hil("circle --scenario bench-no-cut --json --params " + params);
  ASSERT_EQ(circle.exit_code, 0) << circle.err;

  // A corrupt measurement: exit 2, the line named, no parameter file written.
  std::ofstream(dir / "bad.csv") << "position_mm,direction,table_mm\n1,1,1\n2,2,2\n";
  const std::string out = (dir / "bad.toml").string();
  const CliRun bad = run_tnv_hil("screw-fit " + (dir / "bad.csv").string() + " --params-out " + out);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("line 3"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(out));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tnv::test
