// The 32-bit 10 MHz counter (wraps every 429 s) and the 16-bit encoder
// counters wrap in the middle of a circle: the contour error must not change.
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "tools/hil/circle_run.hpp"

namespace tnv::hil {
namespace {

TEST(CounterWrap, ClockAndEncoderWrapsMidCircleLeaveTheContourErrorUnchanged) {
  emu::Scenario base = *emu::builtin_scenario("cut-1200");
  base.encoder.axis_offset_counts[0] = 0.3;
  base.encoder.axis_offset_counts[1] = 0.7;
  const CircleRunResult plain = run_circle(base, fw::default_firmware_config(), fw::ControllerKind::rdvsc);

  emu::Scenario wrapped = base;
  wrapped.board.clock_start = 0xFFFFFFFFu - 50'000'000u;  // wraps 5 s in, mid-circle
  // x spans -14400..14400 counts: the 16-bit register wraps at x = 3 mm;
  // y wraps at about y = 2.3 mm.
  wrapped.encoder.axis_offset_counts[0] += 65536.0 - 7200.0;
  wrapped.encoder.axis_offset_counts[1] += 60000.0;
  const CircleRunResult shifted = run_circle(wrapped, fw::default_firmware_config(), fw::ControllerKind::rdvsc);

  ASSERT_TRUE(plain.completed) << plain.error;
  ASSERT_TRUE(shifted.completed) << shifted.error;
  EXPECT_EQ(shifted.counters.late_ticks, 0u) << "the clock wrap looked like a late tick";
  EXPECT_EQ(shifted.stats.samples, plain.stats.samples);
  EXPECT_NEAR(shifted.stats.max_um, plain.stats.max_um, 1e-9);
  EXPECT_NEAR(shifted.stats.mean_um, plain.stats.mean_um, 1e-9);
  EXPECT_NEAR(shifted.stats.std_um, plain.stats.std_um, 1e-9);
}

}  // namespace
}  // namespace tnv::hil
