// The spindle drive (ramp limit, first-order speed loop, load droop) and
// its encoder with the index (reference plant "Spindle").
#include "emulator/spindle_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "emulator/spindle_encoder.hpp"
#include "emulator/substep_timing.hpp"

namespace tnv::emu {
namespace {

constexpr int kSubstepsPerSecond = static_cast<int>(tnv::emu::kSubstepsPerSecond);

// Steps the drive for `seconds`; returns the largest |dn/dt| seen (rpm/s).
double run(SpindleDrive& drive, double seconds, double load_n = 0.0, SpindleEncoder* encoder = nullptr) {
  double max_rate = 0.0;
  const int n = static_cast<int>(std::lround(seconds * kSubstepsPerSecond));
  for (int i = 0; i < n; ++i) {
    const double before = drive.speed_rpm();
    drive.step(load_n);
    max_rate = std::max(max_rate, std::abs(drive.speed_rpm() - before) / kSubstep_s);
    if (encoder != nullptr) encoder->follow(drive.revolutions());
  }
  return max_rate;
}

TEST(SpindleDrive, DacCodesMapTenVoltsToTwelveThousandRpm) {
  SpindleDrive drive(SpindleParams{});
  EXPECT_EQ(drive.mid_code(), 2048u);
  EXPECT_EQ(drive.max_code(), 4095u);
  EXPECT_DOUBLE_EQ(drive.rpm_per_code(), 12'000.0 / 2048.0);
  EXPECT_EQ(drive.code_for_rpm(6000.0), 3072u) << "5 V";
  drive.set_command_code(3072);
  EXPECT_EQ(drive.commanded_rpm(), 6000.0);
  drive.set_command_code(0);
  EXPECT_EQ(drive.commanded_rpm(), -12'000.0) << "-10 V: full speed the other way";
  drive.set_command_code(4095);
  EXPECT_EQ(drive.commanded_rpm(), 12'000.0 - 12'000.0 / 2048.0);
  drive.set_command_code(70'000);
  EXPECT_EQ(drive.commanded_rpm(), 12'000.0 - 12'000.0 / 2048.0) << "codes beyond the DAC saturate";
  EXPECT_EQ(drive.code_for_rpm(1e9), 4095u);
  EXPECT_EQ(drive.code_for_rpm(-1e9), 0u);
}

TEST(SpindleDrive, RampToSixThousandIsSlewLimited) {
  SpindleDrive drive(SpindleParams{});
  drive.set_command_code(drive.code_for_rpm(6000.0));
  // While the demand exceeds a_sp tau_sp = 1200 rpm the speed ramps at a_sp.
  const double max_rate = run(drive, 0.5);
  EXPECT_NEAR(drive.speed_rpm(), 3000.0, 1e-6) << "0.5 s at 6000 rpm/s";
  EXPECT_LE(max_rate, 6000.0 * (1.0 + 1e-9));
  double time_s = 0.5;
  while (drive.speed_rpm() < 0.99 * 6000.0 && time_s < 10.0) {
    run(drive, 1e-3);
    time_s += 1e-3;
  }
  EXPECT_GE(time_s, 1.0) << "0 -> 6000 rpm cannot take less than 6000 / a_sp";
  // Ramp to 4800 rpm at 0.8 s, then the exponential: 99 % at 0.8 + tau ln(1200 / 60).
  EXPECT_NEAR(time_s, 0.8 + 0.2 * std::log(20.0), 1.5e-3);
}

TEST(SpindleDrive, SteadyStateIsTheCommandAndDroopsUnderLoad) {
  SpindleDrive idle(SpindleParams{});
  idle.set_command_code(idle.code_for_rpm(6000.0));
  run(idle, 6.0);
  EXPECT_NEAR(idle.speed_rpm(), 6000.0, 1e-5);
  SpindleDrive loaded(SpindleParams{});
  loaded.set_command_code(loaded.code_for_rpm(6000.0));
  run(loaded, 6.0, 150.0);
  EXPECT_NEAR(loaded.speed_rpm(), 6000.0 - 0.2 * 150.0, 1e-5) << "k_d = 0.2 rpm/N";
  // Droop opposes the rotation in either direction.
  SpindleDrive reverse(SpindleParams{});
  reverse.set_command_code(reverse.code_for_rpm(-6000.0));
  run(reverse, 6.0, 150.0);
  EXPECT_NEAR(reverse.speed_rpm(), -5970.0, 1e-5);
}

TEST(SpindleDrive, DirectionReversalRampsThroughZero) {
  SpindleDrive drive(SpindleParams{});
  SpindleEncoder encoder(SpindleParams{});
  drive.set_command_code(drive.code_for_rpm(3000.0));
  run(drive, 3.0, 0.0, &encoder);
  ASSERT_NEAR(drive.speed_rpm(), 3000.0, 0.05);
  const std::int64_t count_at_reversal = encoder.count();
  drive.set_command_code(drive.code_for_rpm(-3000.0));
  double time_s = 0.0, max_rate = 0.0;
  bool passed_zero = false;
  while (drive.speed_rpm() > -0.99 * 3000.0 && time_s < 10.0) {
    max_rate = std::max(max_rate, run(drive, 1e-3, 0.0, &encoder));
    time_s += 1e-3;
    passed_zero = passed_zero || drive.speed_rpm() < 0.0;
  }
  EXPECT_TRUE(passed_zero);
  EXPECT_GE(time_s, 1.0) << "6000 rpm of change at 6000 rpm/s";
  EXPECT_LE(max_rate, 6000.0 * (1.0 + 1e-9));
  run(drive, 5.0, 0.0, &encoder);
  EXPECT_NEAR(drive.speed_rpm(), -3000.0, 1e-4);
  EXPECT_LT(encoder.count(), count_at_reversal) << "the encoder counts down after the reversal";
}

TEST(SpindleEncoder, OneIndexPulsePerRevolutionAndCountsPerRev) {
  SpindleDrive drive(SpindleParams{});
  SpindleEncoder encoder(SpindleParams{});
  drive.set_command_code(drive.code_for_rpm(6000.0));
  run(drive, 2.0, 0.0, &encoder);
  while (drive.revolutions() < 250.5) run(drive, 1e-4, 0.0, &encoder);
  const double revs = drive.revolutions();
  EXPECT_EQ(encoder.index_edges(), static_cast<std::uint64_t>(std::floor(revs)));
  EXPECT_EQ(encoder.count(), std::llround(revs * 4096.0));
  EXPECT_EQ(encoder.latched_count(), std::int64_t{4096} * static_cast<std::int64_t>(std::floor(revs)))
      << "the count latched at the last index is a whole number of turns";
}

TEST(SpindleEncoder, IndexAngleShiftsTheMarkAndReversalCountsEdgesBothWays) {
  SpindleParams p;
  p.index_deg = 90.0;  // a quarter turn
  SpindleEncoder encoder(p);
  encoder.follow(0.2);
  EXPECT_EQ(encoder.index_edges(), 0u);
  encoder.follow(0.3);
  EXPECT_EQ(encoder.index_edges(), 1u);
  EXPECT_EQ(encoder.latched_count(), 1024);
  encoder.follow(2.3);  // marks at 1.25, 2.25
  EXPECT_EQ(encoder.index_edges(), 3u);
  encoder.follow(1.0);  // back over 2.25 and 1.25
  EXPECT_EQ(encoder.index_edges(), 5u);
  EXPECT_EQ(encoder.latched_count(), 4096 + 1024) << "the last edge crossed is the mark at 1.25 turns";
}

TEST(SpindleDrive, TheBoardsInputsCommandItOnlyEnabledAndWithTheDirectionAgreeing) {
  SpindleDrive drive(SpindleParams{});
  const std::uint32_t forward = drive.code_for_rpm(3000.0), reverse = drive.code_for_rpm(-3000.0);
  drive.set_inputs(forward, true, false);
  EXPECT_EQ(drive.commanded_rpm(), 3000.0);
  drive.set_inputs(reverse, true, true);
  EXPECT_EQ(drive.commanded_rpm(), -3000.0);
  drive.set_inputs(forward, false, false);
  EXPECT_EQ(drive.commanded_rpm(), 0.0) << "disabled";
  drive.set_inputs(forward, true, true);
  EXPECT_EQ(drive.commanded_rpm(), 0.0) << "direction input against the sign";
  drive.set_inputs(reverse, true, false);
  EXPECT_EQ(drive.commanded_rpm(), 0.0) << "direction input against the sign";
  drive.set_inputs(drive.mid_code(), true, true);
  EXPECT_EQ(drive.commanded_rpm(), 0.0);
}

TEST(SpindleDrive, ABlockIsItsSubStepsAndAStoppingSpindleEndsExactlyAtRest) {
  SpindleDrive stepped(SpindleParams{}), blocked(SpindleParams{});
  for (SpindleDrive* d : {&stepped, &blocked}) d->set_command_code(d->code_for_rpm(2000.0));
  for (int block = 0; block < 500; ++block) {  // 0.5 s: the ramp, the knee and the approach
    for (int i = 0; i < 100; ++i) stepped.step();
    blocked.advance_unloaded(100);
  }
  EXPECT_NEAR(blocked.speed_rpm(), stepped.speed_rpm(), 1e-7);
  EXPECT_NEAR(blocked.revolutions(), stepped.revolutions(), 1e-7);

  // Coming to rest from v0 under the linear law (v0 < a_sp tau_sp): it
  // turns v0 tau_sp more, in rpm*s, and then sits at exactly 0.
  SpindleDrive drive(SpindleParams{});
  drive.set_command_code(drive.code_for_rpm(600.0));
  for (int i = 0; i < 3000; ++i) drive.advance_unloaded(100);  // 3 s: settled
  const double v0_rpm = drive.speed_rpm(), rev0 = drive.revolutions();
  drive.set_command_code(drive.mid_code());
  int blocks = 0;
  while (!drive.at_rest() && blocks < 10'000) {
    drive.advance_unloaded(100);
    ++blocks;
  }
  ASSERT_TRUE(drive.at_rest());
  EXPECT_EQ(drive.speed_rpm(), 0.0);
  EXPECT_NEAR(blocks, 0.2 * std::log(v0_rpm / SpindleDrive::kRestRpm) * 1000.0, 2.0) << "tau_sp ln(v0 / rest)";
  EXPECT_NEAR((drive.revolutions() - rev0) * 60.0, v0_rpm * 0.2, 1e-8);
  const double rest_rev = drive.revolutions();
  drive.advance_unloaded(100);
  EXPECT_EQ(drive.revolutions(), rest_rev);
}

}  // namespace
}  // namespace tnv::emu
