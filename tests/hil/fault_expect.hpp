#pragma once
// Shared checks of the fault-injection HIL tests: what the board's outputs
// show right after the tick that latched the fault (not what the firmware
// says it wrote), and the latched record.
#include <gtest/gtest.h>

#include "emulator/scenario_file.hpp"
#include "tools/hil/fault_run.hpp"

namespace tnv::test {

inline constexpr std::uint32_t kMidCode = 2048;  // 12-bit offset binary: 0 V

// The scenario every fault runs on: the S1 circle, friction only.
inline emu::Scenario fault_scenario() { return *emu::builtin_scenario("no-cut"); }

// The fault was latched with `reason` (and axis, -1 = none) on the tick that
// detected it, and that same tick's write left both DACs at mid-scale and
// both enables off at the board; one sub-step later the servopacks get 0.
inline void expect_safe_at_latch(const hil::FaultObservation& o, fw::FaultReason reason, int axis) {
  ASSERT_TRUE(o.error.empty()) << o.error;
  ASSERT_TRUE(o.detected) << "nothing latched; expected " << fw::to_string(reason);
  EXPECT_EQ(o.fault.reason, reason) << "latched " << fw::to_string(o.fault.reason);
  EXPECT_EQ(o.fault.axis, axis);
  EXPECT_EQ(o.fault.tick, o.latching_tick) << "the record names the tick that latched it";
  EXPECT_EQ(o.after_latch.dac_register[0], kMidCode) << "X DAC after the latching tick";
  EXPECT_EQ(o.after_latch.dac_register[1], kMidCode) << "Y DAC after the latching tick";
  EXPECT_FALSE(o.after_latch.enabled[0]) << "X enable after the latching tick";
  EXPECT_FALSE(o.after_latch.enabled[1]) << "Y enable after the latching tick";
  EXPECT_EQ(o.command_after_mm_s[0], 0.0) << "mm/s reaching the X servopack";
  EXPECT_EQ(o.command_after_mm_s[1], 0.0) << "mm/s reaching the Y servopack";
  ASSERT_TRUE(o.outputs_safe_s.has_value());
  EXPECT_LE(*o.outputs_safe_s, o.detected_s) << "safe no later than the latching tick";
}

// Detected on the first tick after the injection, outputs live until then.
inline void expect_first_tick(const hil::FaultObservation& o) {
  EXPECT_EQ(o.ticks_to_detect(), 1u) << "ticks from the injection to the latch";
  EXPECT_TRUE(o.live_before_detection) << "the outputs dropped before the fault was detected";
  ASSERT_TRUE(o.time_to_safe_s().has_value());
  EXPECT_LE(*o.time_to_safe_s(), 1e-3) << "s from the injection to safe outputs";
}

}  // namespace tnv::test
