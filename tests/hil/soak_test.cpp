// A shortened soak: 450 s of circles and jogs with the 32-bit clock set to
// wrap 10 s in, so it wraps twice (every 429.5 s). Every tick accounted
// for, no counter drift, and the last cycles like the first.
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "tools/hil/soak_run.hpp"

namespace tnv::hil {
namespace {

TEST(Soak, FourHundredFiftySecondsWrapTheClockTwiceWithoutDriftOrMissedTicks) {
  SoakRequest request;
  request.scenario = *emu::builtin_scenario("no-cut");
  request.scenario.board.clock_start = 0xFFFF'FFFFu - 100'000'000u;  // wraps at 10 s and 439.5 s
  request.duration_s = 450.0;
  const SoakResult r = run_soak(request, fw::default_firmware_config());
  ASSERT_TRUE(r.completed) << r.error;
  EXPECT_GE(r.simulated_s, 450.0);
  EXPECT_EQ(r.clock_wraps, 2u);
  ASSERT_EQ(r.clock_wrap_s.size(), 2u);
  EXPECT_NEAR(r.clock_wrap_s[0], 10.0, 1.5e-3) << "s";
  EXPECT_NEAR(r.clock_wrap_s[1] - r.clock_wrap_s[0], 429.4967296, 1.5e-3) << "s between wraps";
  EXPECT_GT(r.encoder_register_wraps, 0u) << "the 16-bit encoder registers wrap too";
  ASSERT_GE(r.cycles.size(), 15u);

  // Every tick: none missed or late, the board's count and the firmware's agree.
  EXPECT_EQ(r.counters.missed_ticks, 0u);
  EXPECT_EQ(r.counters.late_ticks, 0u) << "a clock wrap looked like a late tick";
  EXPECT_EQ(r.counters.bus_errors, 0u);
  EXPECT_EQ(r.board_ticks + 3, r.firmware_ticks) << "board ticks (after homing) vs firmware ticks";
  EXPECT_TRUE(r.no_missed_ticks);
  // No drift: the extended encoder count is the board's true count at every
  // tick, and the tick count is the clock's.
  EXPECT_EQ(r.max_encoder_drift_counts, 0) << "counts";
  EXPECT_EQ(r.max_clock_drift_clocks, 0) << "clocks";
  EXPECT_TRUE(r.no_counter_drift);

  // Stationary: contour statistics, rest error and the DDC estimate.
  EXPECT_TRUE(r.stationary);
  EXPECT_GE(r.first.cycles, 5u);
  EXPECT_NEAR(r.last.contour_max_um.mean, r.first.contour_max_um.mean, 0.1 * r.first.contour_max_um.mean) << "um";
  EXPECT_NEAR(r.last.contour_mean_um.mean, r.first.contour_mean_um.mean, 0.1 * r.first.contour_mean_um.mean) << "um";
  EXPECT_LT(r.max_rest_error_um, 1.0) << "um at rest, every cycle";
  EXPECT_LT(r.max_abs_d_hat_mm_s, 2.0 * request.scenario.plant[0].stiction_mm_s) << "mm/s: d_hat stays bounded";
  EXPECT_TRUE(r.passed());
}

TEST(Soak, RefusesScenariosItCannotJudge) {
  SoakRequest request;
  request.scenario = *emu::builtin_scenario("cut-900");
  request.duration_s = 10.0;
  SoakResult r = run_soak(request, fw::default_firmware_config());
  EXPECT_FALSE(r.completed);
  EXPECT_NE(r.error.find("cut"), std::string::npos) << r.error;
  EXPECT_EQ(r.firmware_ticks, 0u) << "nothing ran";
  request.scenario = *emu::builtin_scenario("no-cut");
  request.scenario.faults.push_back({.kind = emu::FaultKind::estop, .start_s = 1.0});
  r = run_soak(request, fw::default_firmware_config());
  EXPECT_FALSE(r.completed);
  EXPECT_NE(r.error.find("fault"), std::string::npos) << r.error;
}

}  // namespace
}  // namespace tnv::hil
