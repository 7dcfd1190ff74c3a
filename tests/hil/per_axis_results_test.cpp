// The HIL result structs hold one value per axis of the list (TNV_AXES in
// hal/axis.hpp), and their JSON names every axis: a struct or a key list
// written for x and y by hand fails here once the list grows.
#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "emulator/machine.hpp"
#include "hal/axis.hpp"
#include "tools/hil/fault_run.hpp"
#include "tools/hil/fault_verdict.hpp"
#include "tools/hil/homing_json.hpp"
#include "tools/hil/homing_run.hpp"
#include "tools/hil/shaper_jog_run.hpp"
#include "tools/hil/soak_run.hpp"

namespace tnv::hil {
namespace {

template <class Array>
constexpr bool per_axis = std::tuple_size_v<Array> == hal::kAxisCount;

static_assert(per_axis<decltype(HomingSeedResult::power_up_offset_mm)>);
static_assert(per_axis<decltype(HomingSeedResult::offset_counts)>);
static_assert(per_axis<decltype(HomingSeedResult::home_error_um)>);
static_assert(per_axis<decltype(HomingSeedResult::reading_error_um)>);
static_assert(per_axis<decltype(SoakCycle::rest_error_um)>);
static_assert(per_axis<decltype(SoakCycle::rest_d_hat_mm_s)>);
static_assert(per_axis<decltype(SoakCycle::max_abs_d_hat_mm_s)>);
static_assert(per_axis<decltype(FaultObservation::command_after_mm_s)>);
static_assert(per_axis<decltype(WatchdogObservation::command_at_trip_mm_s)>);
static_assert(per_axis<decltype(JogCommand::speed_mm_s)>);
static_assert(per_axis<decltype(JogRunRequest::shaper)>);
static_assert(per_axis<decltype(JogTraceSample::unshaped_mm)>);
static_assert(per_axis<decltype(JogTraceSample::reference_mm)>);
static_assert(per_axis<decltype(JogTraceSample::tool_mm)>);
static_assert(per_axis<decltype(JogRunResult::axis)>);

TEST(PerAxisResults, HomingJsonNamesEveryAxisWithItsOwnValue) {
  HomingSeedResult r;
  r.seed = 7;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    r.power_up_offset_mm[i] = 1.0 + static_cast<double>(i);
    r.offset_counts[i] = 10.0 + static_cast<double>(i);
    r.home_error_um[i] = 100.0 + static_cast<double>(i);
    r.reading_error_um[i] = 1000.0 + static_cast<double>(i);
  }
  const nlohmann::json j = homing_seed_json(r);
  for (const hal::Axis a : hal::kAxes) {
    const auto i = static_cast<double>(hal::index(a));
    EXPECT_EQ(j.at(axis_key("power_up_offset_*_mm", a)), 1.0 + i) << hal::axis_label(a);
    EXPECT_EQ(j.at(axis_key("offset_counts_*", a)), 10.0 + i) << hal::axis_label(a);
    EXPECT_EQ(j.at(axis_key("home_error_*_um", a)), 100.0 + i) << hal::axis_label(a);
    EXPECT_EQ(j.at(axis_key("reading_error_*_um", a)), 1000.0 + i) << hal::axis_label(a);
  }
  // seed, homed, failure, time_s and four keys per axis: none left over from a hand-written pair.
  EXPECT_EQ(j.size(), 4 + 4 * hal::kAxisCount);
}

TEST(PerAxisResults, HomingKeyListsGoPatternByPatternOverTheList) {
  EXPECT_EQ(axis_key("home_error_*_um", hal::Axis::y), "home_error_y_um");
  const std::vector<std::string> start = homing_start_keys();
  const std::vector<std::string> error = homing_error_keys();
  ASSERT_EQ(start.size(), 2 * hal::kAxisCount);
  ASSERT_EQ(error.size(), 2 * hal::kAxisCount);
  for (const hal::Axis a : hal::kAxes) {
    const std::size_t i = hal::index(a);
    EXPECT_EQ(start[i], axis_key("power_up_offset_*_mm", a));
    EXPECT_EQ(start[hal::kAxisCount + i], axis_key("offset_counts_*", a));
    EXPECT_EQ(error[i], axis_key("home_error_*_um", a));
    EXPECT_EQ(error[hal::kAxisCount + i], axis_key("reading_error_*_um", a));
  }
  EXPECT_EQ(std::set<std::string>(start.begin(), start.end()).size(), start.size()) << "no key twice";
}

TEST(PerAxisResults, AFaultCaseIsMetOnlyWithEveryAxisCommandAtZero) {
  std::array<double, hal::kAxisCount> command{};
  EXPECT_TRUE(every_command_zero(command));
  for (const hal::Axis a : hal::kAxes) {
    command = {};
    command[hal::index(a)] = 0.5;
    EXPECT_FALSE(every_command_zero(command)) << hal::axis_label(a) << " still commanded";
  }
}

TEST(PerAxisResults, FaultJsonListsEveryAxisOutputsAfterTheLatch) {
  FaultCase c;
  c.name = "case";
  FaultObservation obs;
  obs.detected = true;
  for (std::size_t i = 0; i < hal::kAxisCount; ++i) {
    obs.after_latch.dac_register[i] = 2000 + static_cast<std::uint32_t>(i);
    obs.after_latch.enabled[i] = i % 2 == 0;
  }
  const nlohmann::json after = fault_case_json(c, obs, true).at("after_latch");
  EXPECT_EQ(after.size(), 2 * hal::kAxisCount);
  for (const hal::Axis a : hal::kAxes) {
    const std::size_t i = hal::index(a);
    EXPECT_EQ(after.at(std::string("dac_") + hal::axis_label(a)), 2000 + i);
    EXPECT_EQ(after.at(std::string("enable_") + hal::axis_label(a)), i % 2 == 0);
  }
}

TEST(PerAxisResults, JogCsvHasASpeedColumnPerAxis) {
  std::string header = "t_s";
  std::string row = "0.5";
  for (const hal::Axis a : hal::kAxes) {
    header += std::string(",") + hal::axis_label(a) + "_mm_s";
    row += "," + std::to_string(10 * (hal::index(a) + 1));
  }
  EXPECT_EQ(jog_csv_header(), header);
  std::string error;
  const auto commands = parse_jog_csv(header + "\n" + row + "\n", error);
  ASSERT_TRUE(commands) << error;
  ASSERT_EQ(commands->size(), 1u);
  for (const hal::Axis a : hal::kAxes)
    EXPECT_EQ((*commands)[0].speed_mm_s[hal::index(a)], 10.0 * static_cast<double>(hal::index(a) + 1))
        << hal::axis_label(a);
  // One speed short: refused, naming the columns it wants.
  EXPECT_FALSE(parse_jog_csv(header + "\n" + row.substr(0, row.rfind(',')) + "\n", error));
  EXPECT_NE(error.find("expected " + std::to_string(1 + hal::kAxisCount) + " fields (" + header + ")"),
            std::string::npos)
      << error;
}

}  // namespace
}  // namespace tnv::hil
