// tnv-hil path --csv (tools/hil/path_csv.hpp): every axis of the list is in
// the file, the plane's columns where they always were, and the columns
// beyond the plane follow the axis they name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "emulator/scenario_file.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "hal/axis.hpp"
#include "tools/hil/path_csv.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {
namespace path_csv_test {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) out.push_back(cell);
  return out;
}

std::size_t column(const std::vector<std::string>& header, const std::string& name) {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return i;
  ADD_FAILURE() << "no column " << name;
  return 0;
}

TEST(PathCsv, ThePlaneColumnsKeepTheirPlaceAndEveryOtherAxisHasItsReferenceAndPosition) {
  const std::vector<std::string> header = split(path_csv_header());
  const std::vector<std::string> plane{"t_s", "x_ref_mm", "y_ref_mm", "x_mm", "y_mm", "contour_um", "path_speed_mm_s"};
  ASSERT_GE(header.size(), plane.size());
  for (std::size_t i = 0; i < plane.size(); ++i) EXPECT_EQ(header[i], plane[i]) << "column " << i;
  EXPECT_EQ(header.size(), plane.size() + 2 * (hal::kAxisCount - 2)) << path_csv_header();
  for (const hal::Axis axis : hal::kAxes) {
    const std::string n = hal::axis_label(axis);
    EXPECT_EQ(std::count(header.begin(), header.end(), n + "_ref_mm"), 1) << n;
    EXPECT_EQ(std::count(header.begin(), header.end(), n + "_mm"), 1) << n;
  }
}

TEST(PathCsv, TheZColumnsFollowAPlungeAndItsReturn) {
  PathRunOptions options;
  options.keep_samples = true;
  const PathRunResult r = run_path(*emu::builtin_scenario("no-cut"), fw::default_firmware_config(),
                                   fw::ControllerKind::rdvsc, "G21 G91\nG1 Z-2 F300\nG1 X1\nG1 Z2\nM2\n", options);
  ASSERT_TRUE(r.completed) << r.error;
  const std::string csv = path_csv(r.program, r);
  std::stringstream in(csv);
  std::string line;
  ASSERT_TRUE(std::getline(in, line));
  const std::vector<std::string> header = split(line);
  const std::size_t z_ref = column(header, "z_ref_mm");
  const std::size_t z = column(header, "z_mm");
  double first_ref = 0.0, lowest_ref = 0.0, lowest = 0.0, last_ref = 0.0;
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = split(line);
    ASSERT_EQ(cells.size(), header.size()) << line;
    const double ref_mm = std::strtod(cells[z_ref].c_str(), nullptr);
    const double pos_mm = std::strtod(cells[z].c_str(), nullptr);
    if (rows == 0) first_ref = lowest_ref = lowest = ref_mm;
    lowest_ref = std::min(lowest_ref, ref_mm);
    lowest = std::min(lowest, pos_mm);
    last_ref = ref_mm;
    ++rows;
  }
  EXPECT_EQ(rows, r.samples.size());
  EXPECT_NEAR(lowest_ref, first_ref - 2.0, 1e-6) << "the plunge's 2 mm";
  EXPECT_NEAR(lowest, first_ref - 2.0, 0.01) << "the measured Z went down with it";
  EXPECT_NEAR(last_ref, first_ref, 1e-6) << "and came back";
}

}  // namespace
}  // namespace path_csv_test
}  // namespace tnv::hil
