// On the S1 circle the table-following cutting model is the circle model it
// replaced (v_feed and direction from the commanded circle), up to the
// difference between the table's actual and commanded velocity. The bench
// tracks the circle with a loop of its own through the DACs (feed-forward,
// position and speed feedback on the judge's truth): no firmware.
//
// The model is linear in v and v -> v_feed u_hat is a rotation by -135 deg
// (an isometry), so d_table - d_circle = load(t) R(-135 deg) (v_table - v_commanded)
// exactly: the whole difference is the velocity error, and
// |d_table - d_circle| = load(t) |v_table - v_commanded|.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "emulator/scenario_file.hpp"
#include "emulator/substep_timing.hpp"
#include "tests/emulator/cutting_bench.hpp"
#include "tests/emulator/cutting_reference.hpp"

namespace tnv::emu {
namespace {

struct BenchCircleRun {
  test_support::CircleModelComparison forces;
  double worst_unexplained_mm_s = 0.0;  // |(d_table - d_circle) - d_cut(v_table - v_commanded)|
  double rms_speed_error_mm_s = 0.0;    // |v| - commanded speed
};

BenchCircleRun track_s1_circle(const Scenario& s) {
  test_support::CuttingBench bench(s);
  bench.enable();
  const test_support::S1Circle path{s.circle, s.circle.dwell_s};  // servo on at t = 0
  constexpr double kTick_s = 1e-3, kGain_per_s = 100.0, kSpeedGain = 3.0;
  const double end_s = path.start_s + path.duration_s();
  BenchCircleRun r;
  double speed_error_sq = 0.0;
  for (int k = 0; k * kTick_s < end_s + 0.1; ++k) {
    const double t_s = k * kTick_s;
    const test_support::PathSample now = path.at(t_s), mid = path.at(t_s + kTick_s / 2);
    const test_support::TableSample table_now = bench.now();
    // Per axis: v_ref + tau a_ref + f_c sign(v_ref) + position and speed feedback.
    auto command = [&](const AxisPlantParams& plant, double v_mid, double a_mid, double p_ref, double v_ref,
                       double p, double v) {
      const double friction_mm_s = std::abs(v_mid) > 1e-6 ? std::copysign(plant.coulomb_mm_s, v_mid) : 0.0;
      return v_mid + plant.tau_s * a_mid + friction_mm_s + kGain_per_s * (p_ref - p) + kSpeedGain * (v_ref - v);
    };
    bench.command(command(s.plant[0], mid.vx_mm_s, mid.ax_mm_s2, now.x_mm, now.vx_mm_s, table_now.x_mm, table_now.vx_mm_s),
                  command(s.plant[1], mid.vy_mm_s, mid.ay_mm_s2, now.y_mm, now.vy_mm_s, table_now.y_mm, table_now.vy_mm_s));
    const test_support::TableSample t = bench.tick();
    // The force at the tick is the one of the sub-step that ended there.
    const double force_s = t.t_s - kSubstep_s;
    if (force_s < path.start_s || force_s > end_s) continue;
    const CuttingVector circle = test_support::circle_model_cutting(s.cutting, s.circle, path.start_s, force_s);
    const test_support::PathSample ref = path.at(force_s);
    r.forces.add(t.cut, circle, ref.angle_rad);
    const CuttingVector explained = test_support::direct_cutting(s.cutting, s.circle.feed_mm_s, force_s,
                                                                 t.vx_mm_s - ref.vx_mm_s, t.vy_mm_s - ref.vy_mm_s);
    r.worst_unexplained_mm_s = std::max(r.worst_unexplained_mm_s, std::hypot(t.cut.x_mm_s - circle.x_mm_s - explained.x_mm_s,
                                                                             t.cut.y_mm_s - circle.y_mm_s - explained.y_mm_s));
    speed_error_sq += std::pow(std::hypot(t.vx_mm_s, t.vy_mm_s) - ref.speed_mm_s, 2);
  }
  r.rms_speed_error_mm_s = std::sqrt(speed_error_sq / r.forces.samples());
  return r;
}

class CuttingOnTheS1Circle : public ::testing::TestWithParam<const char*> {};

// Tolerances. Unexplained 0.01 mm/s: the force used the velocity 10 us
// before the tick, where the truth reads it (the table accelerates by at
// most a few hundred mm/s^2 at a reversal: < 0.005 mm/s of speed). The
// rest holds for a loop that tracks the speed to < 0.1 mm/s rms (this
// bench: 0.05-0.08): the force differs from the circle model's by < 8% rms
// (measured 4-6%), its mean along the feed by < 1% (0.3%); its mean
// outward part is 3-5% lower (< 7% asserted), because the load itself
// pushes the travel outward when it peaks, turning the force toward the
// feed direction by a few degrees.
TEST_P(CuttingOnTheS1Circle, IsTheCircleModelPlusTheVelocityError) {
  const BenchCircleRun r = track_s1_circle(*builtin_scenario(GetParam()));
  const test_support::CircleModelComparison& c = r.forces;
  ASSERT_GT(c.samples(), 18'900) << "ticks of motion compared";
  EXPECT_LT(r.worst_unexplained_mm_s, 0.01) << "mm/s of difference the velocity error does not explain";
  EXPECT_LT(r.rms_speed_error_mm_s, 0.1) << "mm/s rms: the bench loop tracks the circle";
  EXPECT_LT(c.rms_difference_mm_s(), 0.08 * c.rms_circle_mm_s())
      << "mm/s rms of the difference, against " << c.rms_circle_mm_s() << " mm/s rms of the circle model";
  EXPECT_NEAR(c.along_table_mm_s(), c.along_circle_mm_s(), 0.01 * std::abs(c.along_circle_mm_s()))
      << "mm/s, mean component along the commanded feed";
  EXPECT_LT(c.along_circle_mm_s(), 0.0) << "mm/s: opposing the feed";
  EXPECT_GT(c.outward_table_mm_s(), 0.93 * c.outward_circle_mm_s()) << "mm/s, mean outward component";
  EXPECT_LT(c.outward_table_mm_s(), c.outward_circle_mm_s()) << "mm/s, mean outward component";
}

INSTANTIATE_TEST_SUITE_P(S1Spindles, CuttingOnTheS1Circle, ::testing::Values("cut-900", "cut-1200", "cut-1500"));

}  // namespace
}  // namespace tnv::emu
