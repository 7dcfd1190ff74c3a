// Feed hold and resume on the emulated machine (`tnv-hil path --hold-at
// --resume-at`): TickTask::feed_hold, what the node's COMMAND feed_hold
// does. A hold brakes the path point to rest at the planner's deceleration,
// nothing of the program is lost, the resumed run ends where the run without
// a hold ends with the same geometry (its contour score), the spindle keeps
// turning while held, and a hold during a dwell stops the dwell's clock.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>

#include "emulator/scenario_file.hpp"
#include "firmware/motion/motion_limits.hpp"
#include "firmware/tick/firmware_config.hpp"
#include "tools/hil/path_run.hpp"

namespace tnv::hil {
namespace path_feed_hold_test {
namespace {

// Incremental, so it runs from wherever the machine homes. The feed waits for
// the spindle at speed; 40 mm at 20 mm/s, a dwell, 10 mm at 10 mm/s.
constexpr const char* kProgram =
    "G21 G91\n"
    "M3 S1000\n"
    "G1 X40 F1200\n"
    "G4 P0.5\n"
    "G1 Y10 F600\n"
    "M5\n"
    "M2\n";

PathRunResult run(const std::vector<gcode::FeedHoldWindow>& holds, bool keep_samples = false) {
  const std::optional<emu::Scenario> scenario = emu::builtin_scenario("no-cut");
  EXPECT_TRUE(scenario.has_value());
  PathRunOptions options;
  options.keep_samples = keep_samples;
  options.feed_holds = holds;
  return run_path(*scenario, fw::default_firmware_config(), fw::ControllerKind::rdvsc, kProgram, options);
}

// The first and last loop ticks (index into path_speed_mm_s) where `pred` holds for at least `min_ticks` in a row.
std::pair<std::size_t, std::size_t> stretch(const std::vector<double>& speed, double min_ticks,
                                            const std::function<bool(double)>& pred) {
  std::size_t start = 0;
  for (std::size_t k = 0; k < speed.size(); ++k) {
    if (!pred(speed[k])) {
      start = k + 1;
      continue;
    }
    if (static_cast<double>(k + 1 - start) >= min_ticks) {
      std::size_t end = k;
      while (end + 1 < speed.size() && pred(speed[end + 1])) ++end;
      return {start, end};
    }
  }
  return {0, 0};
}

TEST(PathFeedHold, AHoldBrakesAtThePlannersDecelerationKeepsTheSpindleAndTheResumeEndsTheSameProgram) {
  const PathRunResult plain = run({}, true);
  ASSERT_TRUE(plain.completed) << plain.error;
  // The X move's cruise at 20 mm/s: hold in its middle.
  const auto [cruise_begin, cruise_end] =
      stretch(plain.path_speed_mm_s, 500, [](double v) { return std::fabs(v - 20.0) < 1e-9; });
  ASSERT_GT(cruise_end, cruise_begin) << "no cruise at the feed found";
  const double hold_at_s = static_cast<double>((cruise_begin + cruise_end) / 2) * 1e-3;
  const PathRunResult held = run({{hold_at_s, hold_at_s + 0.8}}, true);
  ASSERT_TRUE(held.completed) << held.error;
  ASSERT_EQ(held.holds.size(), 1u);
  const PathHold& h = held.holds.front();
  ASSERT_TRUE(h.applied);
  EXPECT_NEAR(h.path_speed_at_hold_mm_s, 20.0, 1e-9) << "held at the cruise";
  // At the planner's deceleration: along X, the tangent's share of X's acceleration limit.
  const fw::motion::MotionLimits limits = fw::path_limits(fw::default_firmware_config());
  const double braking_s = 20.0 / (fw::motion::kTangentShare * limits.axis[0].accel_mm_s2);
  ASSERT_GT(h.stopped_after_s, 0.0) << "never came to rest while held";
  EXPECT_LE(h.stopped_after_s, braking_s + 0.002) << "slower than the planner's deceleration";
  EXPECT_GE(h.stopped_after_s, braking_s - 0.001) << "faster than the planner's deceleration";
  // The path point rests from there to the resume.
  const auto rest_from = static_cast<std::size_t>(std::llround((hold_at_s + h.stopped_after_s) / 1e-3));
  const auto resume_tick = static_cast<std::size_t>(std::llround((hold_at_s + 0.8) / 1e-3));
  for (std::size_t k = rest_from; k < resume_tick; ++k) ASSERT_EQ(held.path_speed_mm_s[k], 0.0) << "tick " << k;
  EXPECT_GT(held.path_speed_mm_s[resume_tick + 50], 0.0) << "the feed went on after the resume";
  // The spindle keeps turning while held (S1000 within 2 %: its encoder's M-method quantisation).
  EXPECT_GE(h.spindle_rpm_min_held, 980.0);
  EXPECT_LE(h.spindle_rpm_max_held, 1020.0);
  // Nothing lost: every segment ran, the end is the same, the path is the same path.
  EXPECT_EQ(held.segments, plain.segments);
  for (std::size_t i = 0; i < hal::kAxisCount; ++i)
    EXPECT_NEAR(held.samples.back().reference_mm[i], plain.samples.back().reference_mm[i], 1e-9) << "axis " << i;
  EXPECT_LE(held.score.path_deviation_max_um, 5.0 + 1e-6) << "the reference left the path while braking";
  EXPECT_LE(held.score.contour_error_max_um, plain.score.contour_error_max_um + 1.0)
      << "the hold and the restart cost the contour";
  EXPECT_LE(held.score.accel_ratio_max, 1.0 + 1e-6);
  EXPECT_LE(held.score.jerk_ratio_max, 1.0 + 1e-6);
  EXPECT_NEAR(held.held_s, 0.8, 1e-9);
  EXPECT_GT(held.score.cycle_time_s, plain.score.cycle_time_s + 0.8 - 0.05) << "the hold's time is in the cycle";
  std::printf("feed hold: at rest after %.4f s (v/a %.4f s); contour max %.3f um (no hold %.3f um); spindle %.1f-%.1f "
              "rpm held; cycle %.3f s (no hold %.3f s)\n",
              h.stopped_after_s, braking_s, held.score.contour_error_max_um, plain.score.contour_error_max_um,
              h.spindle_rpm_min_held, h.spindle_rpm_max_held, held.score.cycle_time_s, plain.score.cycle_time_s);
}

TEST(PathFeedHold, AHoldDuringADwellStopsTheDwellsClock) {
  const PathRunResult plain = run({}, true);
  ASSERT_TRUE(plain.completed) << plain.error;
  // The dwell: the path point rests 500 ticks and more between the two moves.
  std::size_t moved = 0;
  while (moved < plain.path_speed_mm_s.size() && plain.path_speed_mm_s[moved] == 0.0) ++moved;
  const auto [dwell_begin, dwell_end] = [&] {
    const std::vector<double> after(plain.path_speed_mm_s.begin() + static_cast<std::ptrdiff_t>(moved),
                                    plain.path_speed_mm_s.end());
    const auto s = stretch(after, 500, [](double v) { return v == 0.0; });
    return std::pair{s.first + moved, s.second + moved};
  }();
  ASSERT_GT(dwell_end, dwell_begin + 400) << "no dwell found";
  // Held from 100 ticks into the dwell for 1 s: the rest grows by the time held.
  const double hold_at_s = static_cast<double>(dwell_begin + 100) * 1e-3;
  const PathRunResult held = run({{hold_at_s, hold_at_s + 1.0}}, true);
  ASSERT_TRUE(held.completed) << held.error;
  const auto [held_begin, held_end] = [&] {
    const std::vector<double> after(held.path_speed_mm_s.begin() + static_cast<std::ptrdiff_t>(moved),
                                    held.path_speed_mm_s.end());
    const auto s = stretch(after, 500, [](double v) { return v == 0.0; });
    return std::pair{s.first + moved, s.second + moved};
  }();
  EXPECT_EQ(held_begin, dwell_begin);
  EXPECT_EQ(held_end - held_begin, dwell_end - dwell_begin + 1000) << "the dwell ran on while held";
  EXPECT_EQ(held.segments, plain.segments);
  EXPECT_NEAR(held.score.contour_error_max_um, plain.score.contour_error_max_um, 1e-9)
      << "at rest the whole time, the hold changes nothing of the path";
}

TEST(PathFeedHold, AHoldAfterTheProgramsEndIsReportedNotApplied) {
  const PathRunResult r = run({{1000.0, 1001.0}});
  ASSERT_TRUE(r.completed) << r.error;
  ASSERT_EQ(r.holds.size(), 1u);
  EXPECT_FALSE(r.holds.front().applied);
  EXPECT_EQ(r.held_s, 0.0);
}

TEST(FeedHoldWindows, PairsInTimeOrderAreTakenAndAnythingElseIsRefusedNamingWhy) {
  std::vector<gcode::FeedHoldWindow> w;
  EXPECT_EQ(gcode::feed_hold_windows({1.0, 3.0}, {2.0, 4.5}, w), "");
  ASSERT_EQ(w.size(), 2u);
  EXPECT_FALSE(gcode::feed_held_at(w, 0.999));
  EXPECT_TRUE(gcode::feed_held_at(w, 1.0));
  EXPECT_FALSE(gcode::feed_held_at(w, 2.0));
  EXPECT_TRUE(gcode::feed_held_at(w, 4.0));
  EXPECT_NE(gcode::feed_hold_windows({1.0}, {}, w).find("in pairs"), std::string::npos);
  EXPECT_TRUE(w.empty()) << "nothing half taken";
  EXPECT_NE(gcode::feed_hold_windows({2.0}, {1.0}, w).find("must come after its --hold-at 2"), std::string::npos);
  EXPECT_NE(gcode::feed_hold_windows({1.0, 1.5}, {2.0, 3.0}, w).find("before the previous --resume-at 2"),
            std::string::npos);
  EXPECT_NE(gcode::feed_hold_windows({-1.0}, {1.0}, w).find(">= 0"), std::string::npos);
  EXPECT_NE(gcode::feed_hold_windows({std::nan("")}, {1.0}, w).find("finite"), std::string::npos);
}

}  // namespace
}  // namespace path_feed_hold_test
}  // namespace tnv::hil
