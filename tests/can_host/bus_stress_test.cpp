// tnv-hil bus-stress (tools/can_emu/bus_stress.hpp): the goals of docs/safety.md
// "Bus priority, tags, hosts and ownership" at 100 % load from 0x7ff, and
// the same run with the flood above the node's identifiers, where nothing of
// lower priority can get through (the honest limit of any CAN node).
#include <gtest/gtest.h>

#include "tools/can_emu/bus_stress.hpp"

namespace tnv {
namespace {

using can_host::BusStressOptions;
using can_host::run_bus_stress;

TEST(BusStress, AtFullLoadFrom0x7ffEveryReplyArrivesAndNoSetCrosses) {
  BusStressOptions o;
  o.flood_id = 0x7FF;
  o.load = 1.0;
  o.hosts = 2;
  const can_host::BusStressResult r = run_bus_stress(o);
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_TRUE(r.circle_ran);
  EXPECT_GT(r.bus_load, 0.99) << "the flood did not saturate the wire";
  EXPECT_GT(r.requests, 100u);
  EXPECT_EQ(r.replies_received, r.requests);
  EXPECT_EQ(r.replies_misattributed, 0u);
  EXPECT_LE(r.heartbeat_max_gap_ms, 200.0);
  EXPECT_GE(r.fault_event_delay_ms, 0.0) << "no FAULT_EVENT after the ESTOP";
  EXPECT_LE(r.fault_event_delay_ms, 10.0);
  EXPECT_EQ(r.missed_ticks, 0u);
  EXPECT_EQ(r.commits, 2u) << "each host commits its own set once";
  EXPECT_EQ(r.staged_sets_crossed, 0u);
  RecordProperty("requests", static_cast<int>(r.requests));
  RecordProperty("fault_event_delay_us", static_cast<int>(r.fault_event_delay_ms * 1000.0));
  RecordProperty("heartbeat_max_gap_ms", static_cast<int>(r.heartbeat_max_gap_ms));
}

TEST(BusStress, FourHostsStagingAtOnceEachCommitTheirOwnSet) {
  BusStressOptions o;
  o.hosts = 4;
  o.rounds = 10;
  const can_host::BusStressResult r = run_bus_stress(o);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.commits, 4u);
  EXPECT_EQ(r.staged_sets_crossed, 0u);
  EXPECT_EQ(r.replies_received, r.requests);
  EXPECT_EQ(r.replies_misattributed, 0u);
}

// A flood of higher priority than every reply starves them on any CAN bus:
// the run must say so (the counts are not made to look good), and the
// controller still keeps its ticks.
TEST(BusStress, AFloodAboveTheNodesIdentifiersIsReportedNotHidden) {
  BusStressOptions o;
  o.flood_id = 0x001;
  o.rounds = 5;
  const can_host::BusStressResult r = run_bus_stress(o);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_LT(r.replies_received, r.requests);
  EXPECT_GT(r.heartbeat_max_gap_ms, 200.0);
  EXPECT_EQ(r.missed_ticks, 0u);
}

TEST(BusStress, OptionsOutOfRangeAreRefused) {
  BusStressOptions o;
  o.flood_id = 0x800;
  EXPECT_FALSE(can_host::validate(o).empty());
  o = {};
  o.load = 1.5;
  EXPECT_FALSE(can_host::validate(o).empty());
  o = {};
  o.hosts = 5;
  EXPECT_FALSE(can_host::validate(o).empty());
  EXPECT_FALSE(run_bus_stress(o).error.empty());
}

}  // namespace
}  // namespace tnv
