// The emulated machine's cutting force follows the table's own motion:
// straight moves, a diagonal, arcs both ways, speed scaling and rest (the
// S1 circle: cutting_on_s1_circle_test.cpp).
// The bench drives the DACs open loop and reads the judge's truth: no
// firmware involved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "emulator/scenario_file.hpp"
#include "emulator/substep_timing.hpp"
#include "tests/emulator/cutting_bench.hpp"
#include "tests/emulator/cutting_reference.hpp"

namespace tnv::emu {
namespace {

using test_support::CuttingBench;
using test_support::TableSample;

double angle_from_velocity_deg(const TableSample& s) {
  return test_support::angle_from_velocity_deg(s.cut, s.vx_mm_s, s.vy_mm_s);
}
double direction_deg(double x, double y) { return test_support::degrees(std::atan2(y, x)); }

Scenario without_friction(Scenario s) {
  for (AxisPlantParams& p : s.plant) p.coulomb_mm_s = p.stiction_mm_s = 0.0;
  return s;
}

struct StraightMove {
  const char* name;
  double ux_lsb, uy_lsb;       // one of them 0
  double force_direction_deg;  // travel direction - 135 deg
};
void PrintTo(const StraightMove& move, std::ostream* os) { *os << move.name; }

class CuttingOnAStraightMove : public ::testing::TestWithParam<StraightMove> {};

// Along one axis the load across the travel (at most 1.2 / sqrt 2 x speed / F
// mm/s) stays below the other axis' stiction, so that axis stays stuck and
// the travel is exactly along the axis.
TEST_P(CuttingOnAStraightMove, OpposesTheTravelRotated45DegreesToItsRight) {
  const StraightMove move = GetParam();
  const Scenario s = *builtin_scenario("cut-900");
  CuttingBench bench(s);
  bench.enable();
  bench.command(move.ux_lsb * bench.lsb_mm_s(), move.uy_lsb * bench.lsb_mm_s());
  for (int k = 0; k < 50; ++k) bench.tick();  // up to speed
  for (int k = 0; k < 300; ++k) {
    const TableSample t = bench.tick();
    const double speed_mm_s = std::hypot(t.vx_mm_s, t.vy_mm_s);
    ASSERT_GT(speed_mm_s, 1.0) << "mm/s: the table moves";
    ASSERT_GT(t.cut.magnitude_mm_s(), 0.0) << "cutting while moving, t = " << t.t_s;
    ASSERT_TRUE(move.ux_lsb == 0.0 ? t.x_stuck : t.y_stuck) << "the other axis holds: a straight move";
    // The travel direction is exact: only rounding of atan2 is left.
    ASSERT_NEAR(angle_from_velocity_deg(t), -135.0, 1e-9) << "deg from the travel, t = " << t.t_s;
    ASSERT_NEAR(direction_deg(t.cut.x_mm_s, t.cut.y_mm_s), move.force_direction_deg, 1e-9) << "deg, t = " << t.t_s;
    // |d| = load(t) |v|, the load of the sub-step that ended at the tick.
    const double load = test_support::cutting_level_mm_s(s.cutting, s.circle.feed_mm_s, t.t_s - kSubstep_s, 1.0);
    ASSERT_NEAR(t.cut.magnitude_mm_s() / (load * speed_mm_s), 1.0, 1e-3) << "t = " << t.t_s;
  }
}

// 48 LSB (3.9 mm/s) is about F plus friction and the mean load.
INSTANTIATE_TEST_SUITE_P(
    Directions, CuttingOnAStraightMove,
    ::testing::Values(StraightMove{"plus_x", 48, 0, -135.0}, StraightMove{"minus_x", -48, 0, 45.0},
                      StraightMove{"plus_y", 0, 48, -45.0}, StraightMove{"minus_y", 0, -48, 135.0}),
    [](const ::testing::TestParamInfo<StraightMove>& p) { return std::string(p.param.name); });

// Commanded at 45 deg, the force (travel - 135 deg) lies nearly all on -Y,
// so Y runs slower than X and the table travels below 45 deg. The force
// used the velocity at the start of the last sub-step, 10 us before the
// tick; the tooth pulsation turns the travel by up to ~0.02 deg in that time.
TEST(CuttingOnADiagonal, OpposesTheTravelAndHoldsBackTheAxisOnItsRight) {
  CuttingBench bench(*builtin_scenario("cut-900"));
  bench.enable();
  bench.command(48 * bench.lsb_mm_s(), 48 * bench.lsb_mm_s());
  for (int k = 0; k < 50; ++k) bench.tick();  // up to speed
  double worst_deg = 0.0, lowest_travel_deg = 90.0, highest_travel_deg = 0.0;
  for (int k = 0; k < 300; ++k) {
    const TableSample t = bench.tick();
    const double travel_deg = direction_deg(t.vx_mm_s, t.vy_mm_s);
    lowest_travel_deg = std::min(lowest_travel_deg, travel_deg);
    highest_travel_deg = std::max(highest_travel_deg, travel_deg);
    worst_deg = std::max(worst_deg, std::abs(angle_from_velocity_deg(t) + 135.0));
    ASSERT_LT(std::abs(t.cut.x_mm_s), std::abs(t.cut.y_mm_s)) << "mm/s: Y carries the load, t = " << t.t_s;
  }
  std::printf("worst %.5f travel %.3f..%.3f\n", worst_deg, lowest_travel_deg, highest_travel_deg);
  EXPECT_LT(worst_deg, 0.05) << "deg off -135 deg from the travel";
  EXPECT_LT(highest_travel_deg, 45.0) << "deg: Y slower than X";
  EXPECT_GT(lowest_travel_deg, 20.0) << "deg: still a diagonal";
}

struct ArcRun {
  double outward_share_min = 1.0, outward_share_max = -1.0;  // d . n_out / |d|
  double angle_min_deg = 1e9, angle_max_deg = -1e9;
  int turning_sign_errors = 0;
  int samples = 0;
};

// An open-loop arc: the command turns at omega (rad/s, + = counter-clockwise).
// Friction off, so no reversal sticks; no tooth pulsation, so the actual
// travel turns smoothly and its curvature shows the side the centre is on.
ArcRun run_arc(double omega_rad_s) {
  Scenario s = without_friction(*builtin_scenario("cut-900"));
  s.cutting.amplitude_mm_s = 0.0;
  CuttingBench bench(s);
  bench.enable();
  ArcRun r;
  TableSample previous{};
  for (int k = 0; k < 1500; ++k) {
    const double t_s = k * 1e-3;
    const double heading = std::numbers::pi / 2 + omega_rad_s * t_s;  // starts travelling +Y
    bench.command(2.0 * std::cos(heading), 2.0 * std::sin(heading));
    const TableSample t = bench.tick();
    if (k >= 200) {  // turning steadily
      const double speed = std::hypot(t.vx_mm_s, t.vy_mm_s);
      const double ax = (t.vx_mm_s - previous.vx_mm_s) / 1e-3, ay = (t.vy_mm_s - previous.vy_mm_s) / 1e-3;
      const double tx = t.vx_mm_s / speed, ty = t.vy_mm_s / speed;
      const double along = ax * tx + ay * ty;
      // The centripetal part of the acceleration points at the centre.
      double nx = -(ax - along * tx), ny = -(ay - along * ty);
      const double n = std::hypot(nx, ny);
      nx /= n, ny /= n;
      const double cross = previous.vx_mm_s * t.vy_mm_s - previous.vy_mm_s * t.vx_mm_s;
      if ((cross > 0) != (omega_rad_s > 0)) ++r.turning_sign_errors;
      const double share = (t.cut.x_mm_s * nx + t.cut.y_mm_s * ny) / t.cut.magnitude_mm_s();
      r.outward_share_min = std::min(r.outward_share_min, share);
      r.outward_share_max = std::max(r.outward_share_max, share);
      r.angle_min_deg = std::min(r.angle_min_deg, angle_from_velocity_deg(t));
      r.angle_max_deg = std::max(r.angle_max_deg, angle_from_velocity_deg(t));
      ++r.samples;
    }
    previous = t;
  }
  return r;
}

TEST(CuttingOnAnArc, PushesOutwardTurningLeftAndInwardTurningRight) {
  const double half = std::sqrt(0.5);  // cos 45 deg
  const ArcRun ccw = run_arc(+2.0);
  const ArcRun cw = run_arc(-2.0);
  for (const ArcRun* r : {&ccw, &cw}) {
    ASSERT_GT(r->samples, 1000);
    EXPECT_EQ(r->turning_sign_errors, 0) << "the table turns the way it was commanded";
    EXPECT_NEAR(r->angle_min_deg, -135.0, 0.01) << "deg from the travel";
    EXPECT_NEAR(r->angle_max_deg, -135.0, 0.01) << "deg from the travel";
  }
  // Counter-clockwise the right-hand side is outside (the S1 circle), clockwise inside.
  EXPECT_NEAR(ccw.outward_share_min, half, 0.01) << "share of |d| along the outward normal, counter-clockwise";
  EXPECT_NEAR(ccw.outward_share_max, half, 0.01);
  EXPECT_NEAR(cw.outward_share_min, -half, 0.01) << "share of |d| along the outward normal, clockwise";
  EXPECT_NEAR(cw.outward_share_max, -half, 0.01);
}

// Friction off the whole machine is linear in the command (the load is
// linear in the speed), so three times the command is three times the
// speed and three times the force, tick by tick.
TEST(CuttingFollowsTheTable, ScalesWithTheSpeed) {
  const Scenario s = without_friction(*builtin_scenario("cut-1500"));
  CuttingBench slow(s), fast(s);
  slow.enable();
  fast.enable();
  slow.command(10 * slow.lsb_mm_s(), -7 * slow.lsb_mm_s());
  fast.command(30 * fast.lsb_mm_s(), -21 * fast.lsb_mm_s());
  for (int k = 0; k < 500; ++k) {
    const TableSample a = slow.tick(), b = fast.tick();
    ASSERT_NEAR(b.vx_mm_s, 3.0 * a.vx_mm_s, 1e-9 * std::abs(b.vx_mm_s) + 1e-12) << "mm/s, tick " << k;
    ASSERT_NEAR(b.cut.x_mm_s, 3.0 * a.cut.x_mm_s, 1e-9 * std::abs(b.cut.x_mm_s) + 1e-12) << "mm/s, tick " << k;
    ASSERT_NEAR(b.cut.y_mm_s, 3.0 * a.cut.y_mm_s, 1e-9 * std::abs(b.cut.y_mm_s) + 1e-12) << "mm/s, tick " << k;
  }
}

TEST(CuttingFollowsTheTable, IsZeroAtRest) {
  CuttingBench bench(*builtin_scenario("cut-900"));
  for (int k = 0; k < 100; ++k) ASSERT_EQ(bench.tick().cut.magnitude_mm_s(), 0.0) << "servo off, tick " << k;
  bench.enable();
  for (int k = 0; k < 1000; ++k) ASSERT_EQ(bench.tick().cut.magnitude_mm_s(), 0.0) << "servo on at rest, tick " << k;
  bench.command(48 * bench.lsb_mm_s(), -30 * bench.lsb_mm_s());
  for (int k = 0; k < 200; ++k) bench.tick();
  ASSERT_GT(bench.tick().cut.magnitude_mm_s(), 0.5) << "mm/s while moving";
  bench.command(0.0, 0.0);
  int stopped_at = -1;
  for (int k = 0; k < 500; ++k) {
    const TableSample t = bench.tick();
    if (stopped_at < 0 && t.x_stuck && t.y_stuck) stopped_at = k;
    // The tick it stuck may end a sub-step that began in motion; the next may not.
    if (stopped_at >= 0 && k > stopped_at) {
      ASSERT_EQ(t.cut.magnitude_mm_s(), 0.0) << "table stopped at tick " << stopped_at << ", now " << k;
    }
  }
  EXPECT_GE(stopped_at, 0) << "the table stopped";
}

}  // namespace
}  // namespace tnv::emu
