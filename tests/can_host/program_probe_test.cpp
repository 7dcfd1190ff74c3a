// Programs that probe (G38.2-G38.5) streamed over the virtual bus to the
// emulated node with a stock ([stock] on), as `tnvctl --emu run` runs them:
// the host sends what precedes a probe, waits for its PROBE_RESULT (with
// PROBE_RESULT_Z and PROBE_REST), sets #5061-#5070 and reads on from where
// the node rests. Judged against the stock's faces on the emulated machine.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "emulator/cutting_at_tool.hpp"
#include "tools/can/program_run.hpp"
#include "tools/can_emu/emulated_bus.hpp"

namespace tnv {
namespace {

using can_host::StreamResult;

// The head powers up with the spindle nose at -25 mm and a 125 mm tool (the tool point at -150 mm),
// the table at X = 6 mm; the trip is reported within 2.4 um at 2 mm/s (docs/motion.md "Probe moves").
constexpr double kToolLength_mm = 125.0;
constexpr double kProbeTolerance_mm = 2.0 * 1e-3 + 0.42e-3;
// The probe in the spindle: a 0.5 mm stylus ball on a 0.8 mm shank (the machine's "tool"): it trips half a
// millimetre from a face, so braking never takes the shank into the stock (a crash, the spindle being off).
constexpr double kTipRadius_mm = 0.5;
constexpr double kShankDiameter_mm = 0.8;

class ProgramProbe : public ::testing::Test {
 protected:
  // The stock: its top and its side face at X max.
  void start(double top_mm, double x_max_mm) {
    const std::string stem = std::filesystem::temp_directory_path() / ("tnv_probe_" + std::to_string(::getpid()));
    scenario_path_ = stem + ".toml";
    std::ofstream(scenario_path_) << "[stock]\nenabled = true\ntop_mm = " << top_mm << "\nx_max_mm = " << x_max_mm
                                  << "\n[probe]\ntip_radius_mm = " << kTipRadius_mm
                                  << "\n[tool]\ndiameter_mm = " << kShankDiameter_mm << "\n";
    can_host::EmulatedNodeOptions o;
    o.scenario = scenario_path_;
    o.storage_path = stem + ".img";
    storage_path_ = o.storage_path;
    std::string error;
    bus_ = can_host::EmulatedBus::create(o, error);
    ASSERT_TRUE(bus_) << error;
    client_ = std::make_unique<can_host::NodeClient>(*bus_, 1);
  }
  void TearDown() override {
    client_.reset();
    bus_.reset();
    std::filesystem::remove(scenario_path_);
    std::filesystem::remove(storage_path_);
  }
  can_host::ProgramRunResult run(const std::string& text) { return can_host::run_gcode(*client_, text, {}); }
  double standing_mm(hal::Axis a) { return bus_->rig().task.standing_mm(a); }
  std::uint64_t crashes() { return bus_->rig().machine.cutting_at_tool()->crashes().count(); }

  std::string scenario_path_, storage_path_;
  std::unique_ptr<can_host::EmulatedBus> bus_;
  std::unique_ptr<can_host::NodeClient> client_;
};

TEST_F(ProgramProbe, G38_2DownOntoTheTopThenOneMillimetreAboveItFromNumber5063) {
  const double top_mm = -155.0;
  ASSERT_NO_FATAL_FAILURE(start(top_mm, 1e3));
  const can_host::ProgramRunResult r = run("G21 G90\nG38.2 Z-40 F120\nG0 Z[#5063 - 0.5 + 1]\nM2\n");
  ASSERT_EQ(r.stream.end, StreamResult::End::done) << r.stream.message;
  EXPECT_EQ(r.program.probes, 1u);
  const double tool_point_mm = standing_mm(hal::Axis::z) - kToolLength_mm;
  // The wire carries positions in 0.1 um steps.
  EXPECT_NEAR(tool_point_mm, top_mm + 1.0, kProbeTolerance_mm + 1e-4) << "Z[#5063 - 0.5 + 1]: 1 mm above the found top";
  EXPECT_NEAR(bus_->rig().machine.truth(hal::Axis::z).position_mm - kToolLength_mm, top_mm + 1.0,
              kProbeTolerance_mm + 2e-3);
  EXPECT_EQ(crashes(), 0u);
  std::printf("G38.2 onto the top over CAN: tool point ends %.4f um from 1 mm above it\n",
              (tool_point_mm - top_mm - 1.0) * 1e3);
}

TEST_F(ProgramProbe, G38_2SidewaysOntoASideFaceThenOneMillimetreBesideItFromNumber5061) {
  const double side_mm = 3.0;
  ASSERT_NO_FATAL_FAILURE(start(-145.0, side_mm));  // the tool point 5 mm below the top, beside the stock
  const can_host::ProgramRunResult r = run("G21 G90\nG38.2 X-2 F120\nG0 X[#5061 - 0.5 + 1]\nM2\n");
  ASSERT_EQ(r.stream.end, StreamResult::End::done) << r.stream.message;
  EXPECT_NEAR(standing_mm(hal::Axis::x), side_mm + 1.0, kProbeTolerance_mm + 1e-4);
  EXPECT_EQ(crashes(), 0u);
}

TEST_F(ProgramProbe, G38_3ThatDoesNotTripGoesOnWithNumber5070Zero) {
  ASSERT_NO_FATAL_FAILURE(start(-155.0, 1e3));
  const can_host::ProgramRunResult r = run("G21 G90\nG38.3 Z-27 F120\nG0 Z[#5063 + 2 + 10 * #5070]\nM2\n");
  ASSERT_EQ(r.stream.end, StreamResult::End::done) << r.stream.message;
  EXPECT_NEAR(standing_mm(hal::Axis::z), -25.0, 1e-4) << "#5063 the programmed end (-27), #5070 0";
  EXPECT_EQ(r.stream.sent, 2u);
}

TEST_F(ProgramProbe, G38_2ThatDoesNotTripStopsTheProgramAtItsLineAndSendsNothingAfterIt) {
  ASSERT_NO_FATAL_FAILURE(start(-155.0, 1e3));
  const can_host::ProgramRunResult r = run("G21 G90\nG38.2 Z-27 F120\nG0 Z-20\nG0 X0\nM2\n");
  EXPECT_EQ(r.stream.end, StreamResult::End::failed);
  EXPECT_NE(r.stream.message.find("line 2"), std::string::npos) << r.stream.message;
  EXPECT_NE(r.stream.message.find("G38.2"), std::string::npos) << r.stream.message;
  EXPECT_EQ(r.stream.sent, 1u) << "only the probe was sent";
  EXPECT_NEAR(standing_mm(hal::Axis::z), -27.0, 1e-4) << "it rests at the probe's end";
}

}  // namespace
}  // namespace tnv
