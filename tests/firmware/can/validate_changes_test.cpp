// validate(next, valid_base): a parameter change re-checks only the parts
// that differ from the running (valid) set, and still refuses every bad
// change, whatever part it is in. Metered, a change that leaves the force
// loop alone skips its pole-placement solve.
#include <gtest/gtest.h>

#include <cmath>

#include "firmware/adaptive/arsc/arsc_source_params.hpp"
#include "firmware/can/node_settings.hpp"
#include "firmware/can/param_table.hpp"
#include "firmware/tick/work_meter.hpp"

namespace tnv::test {
namespace {

using fw::can::NodeSettings;

const NodeSettings& base() { return fw::can::cached_default_node_settings(); }

TEST(ValidateChanges, TheSameSetPassesAndEveryBadChangeIsStillRefused) {
  ASSERT_TRUE(fw::can::validate(base()).ok);
  EXPECT_TRUE(fw::can::validate(base(), base()).ok);

  NodeSettings q = base();
  q.firmware.axis[1].sliding.q = 1.5;  // 0 < q < 1
  NodeSettings arsc = base();
  arsc.firmware.arsc.pole_re_rad_s = 5.0;  // an unstable pole
  NodeSettings limit = base();
  limit.firmware.supervisor.axis[0].position_min_mm = limit.firmware.supervisor.axis[0].position_max_mm + 1.0;
  NodeSettings shaper = base();
  shaper.shaper[0].spec.mode.freq_hz = 1000.0;
  NodeSettings nan = base();
  nan.firmware.axis[0].count_mm = std::nan("");
  for (const NodeSettings* bad : {&q, &arsc, &limit, &shaper, &nan}) {
    const fw::can::SettingsCheck whole = fw::can::validate(*bad);
    const fw::can::SettingsCheck changed = fw::can::validate(*bad, base());
    EXPECT_FALSE(whole.ok);
    EXPECT_FALSE(changed.ok) << whole.section << ": " << whole.reason;
    EXPECT_EQ(changed.param, whole.param) << whole.section;
  }
  // A good change passes both ways.
  NodeSettings good = base();
  good.firmware.axis[0].sliding.eta_mm_s *= 1.5;
  EXPECT_TRUE(fw::can::validate(good).ok);
  EXPECT_TRUE(fw::can::validate(good, base()).ok);
}

TEST(ValidateChanges, AChangeOutsideTheForceLoopDoesNotSolveItsDesignAgain) {
  if (!fw::work_meter_enabled()) GTEST_SKIP() << "the firmware is built without the work meter";
  NodeSettings next = base();
  next.firmware.axis[0].sliding.eta_mm_s *= 1.5;
  ASSERT_TRUE(fw::arsc::validate(next.firmware.arsc).ok);  // warm: nothing computed once is counted below
  std::uint64_t before = fw::work_blocks();
  ASSERT_TRUE(fw::arsc::validate(next.firmware.arsc).ok);
  const std::uint64_t force_loop = fw::work_blocks() - before;
  before = fw::work_blocks();
  ASSERT_TRUE(fw::can::validate(next).ok);
  const std::uint64_t whole = fw::work_blocks() - before;
  before = fw::work_blocks();
  ASSERT_TRUE(fw::can::validate(next, base()).ok);
  const std::uint64_t changed = fw::work_blocks() - before;
  EXPECT_GT(force_loop, 0u);
  EXPECT_LE(changed + force_loop, whole) << "whole " << whole << " blocks, changed " << changed << ", force loop "
                                         << force_loop;
}

}  // namespace
}  // namespace tnv::test
