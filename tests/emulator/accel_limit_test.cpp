// The servopack's current limit as |dv/dt| <= accel_limit_mm_s2: a ramp at
// the limit, then the speed loop's exponential, integrated exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "emulator/axis_plant.hpp"
#include "emulator/machine.hpp"
#include "emulator/substep_timing.hpp"
#include "hal/io_board_registers.hpp"
#include "tests/emulator/machine_register_read.hpp"

namespace tnv::emu {
namespace {

namespace regs = hal::regs;

constexpr double kTau_s = 0.005360;
constexpr double kLimit_mm_s2 = 5000.0;

AxisPlantParams limited(bool friction) {
  AxisPlantParams p;
  p.accel_limit_mm_s2 = kLimit_mm_s2;
  if (!friction) p.coulomb_mm_s = p.stiction_mm_s = 0.0;
  return p;
}

TEST(AccelLimit, StepDemandRampsAtTheLimitThenApproachesExactly) {
  AxisPlant plant(limited(false));
  plant.set_state(0.0, 0.0);
  const double w_mm_s = 100.0;  // demand 100 / tau = 18,657 mm/s^2 at first
  double largest_step_mm_s = 0.0;
  for (int k = 0; k < 1000; ++k) {  // 10 ms, all on the ramp (it lasts 14.64 ms)
    const double v0 = plant.speed_mm_s();
    plant.step(w_mm_s, 0.0);
    largest_step_mm_s = std::max(largest_step_mm_s, plant.speed_mm_s() - v0);
  }
  EXPECT_NEAR(plant.speed_mm_s(), kLimit_mm_s2 * 0.010, 1e-9);
  EXPECT_NEAR(plant.position_mm(), 0.5 * kLimit_mm_s2 * 0.010 * 0.010, 1e-12);
  EXPECT_LE(largest_step_mm_s, kLimit_mm_s2 * kSubstep_s * (1.0 + 1e-9)) << "an acceleration above the limit";
  for (int k = 0; k < 2000; ++k) plant.step(w_mm_s, 0.0);  // to 30 ms
  // After t1 = (w - A tau) / A the law meets the exponential at v = w - A tau.
  const double t1_s = (w_mm_s - kLimit_mm_s2 * kTau_s) / kLimit_mm_s2;
  const double since_s = 0.030 - t1_s;
  const double gap_mm_s = kLimit_mm_s2 * kTau_s;
  EXPECT_NEAR(plant.speed_mm_s(), w_mm_s - gap_mm_s * std::exp(-since_s / kTau_s), 1e-9);
  const double p_mm = 0.5 * kLimit_mm_s2 * t1_s * t1_s + w_mm_s * since_s - gap_mm_s * kTau_s * (1.0 - std::exp(-since_s / kTau_s));
  EXPECT_NEAR(plant.position_mm(), p_mm, 1e-10);
}

TEST(AccelLimit, SmallDemandsAreNotTouched) {
  AxisPlant free_plant(AxisPlantParams{.coulomb_mm_s = 0.0, .stiction_mm_s = 0.0});
  AxisPlant plant(limited(false));
  free_plant.set_state(1.0, 10.0);
  plant.set_state(1.0, 10.0);
  for (int k = 0; k < 500; ++k) {  // |w - v| = 20 mm/s < A tau = 26.8 mm/s: never clamped
    free_plant.step(30.0, 0.0);
    plant.step(30.0, 0.0);
  }
  EXPECT_EQ(plant.speed_mm_s(), free_plant.speed_mm_s());
  EXPECT_EQ(plant.position_mm(), free_plant.position_mm());
}

TEST(AccelLimit, ReversalUnderTheLimitStopsAfterVSquaredOverTwoA) {
  AxisPlant plant(limited(true));
  const double v0_mm_s = 10.3;
  plant.set_state(0.0, v0_mm_s);
  double furthest_mm = 0.0;
  bool stuck_once = false;
  for (int k = 0; k < 400; ++k) {
    plant.step(-100.0, 0.0);
    furthest_mm = std::max(furthest_mm, plant.position_mm());
    stuck_once = stuck_once || plant.stuck();
  }
  EXPECT_TRUE(stuck_once) << "the zero crossing sticks the axis (Karnopp)";
  EXPECT_NEAR(furthest_mm, v0_mm_s * v0_mm_s / (2.0 * kLimit_mm_s2), 1e-12);
  EXPECT_LT(plant.speed_mm_s(), 0.0) << "and it breaks away backwards";
}

TEST(AccelLimit, MachineTableAndAccelerometerObeyTheLimit) {
  Scenario s;
  s.plant[0].accel_limit_mm_s2 = 2000.0;
  Machine m(s);
  ASSERT_TRUE(m.write_register(regs::kDacX, m.dac_mid_code() + 1000));  // about 81 mm/s
  ASSERT_TRUE(m.write_register(regs::kOutputs, regs::kOutputEnableX));
  for (int i = 0; i < 10; ++i) m.advance_to_next_tick();  // 10 ms, on the ramp (it lasts about 34 ms)
  EXPECT_NEAR(m.truth(hal::Axis::x).speed_mm_s, 2000.0 * 0.010, 1e-9);
  EXPECT_NEAR(m.truth(hal::Axis::x).motor_position_mm - 6.0, 0.5 * 2000.0 * 0.010 * 0.010, 1e-12);
  const auto expected_code = static_cast<std::uint32_t>(std::round(2048.0 + 2000.0 / regs::kAccelFullScaleMmS2 * 2048.0));
  EXPECT_EQ(test_support::read(m, regs::kAdcAccelX), expected_code) << "the accelerometer reads the limited 2000 mm/s^2";
}

}  // namespace
}  // namespace tnv::emu
