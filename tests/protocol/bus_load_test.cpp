// Bus time of the default telemetry and the streaming estimate.
#include <gtest/gtest.h>

#include "tools/protogen/bus_load.hpp"

namespace {

using namespace tnv::protogen;

TEST(BusLoad, FrameBits) {
  EXPECT_EQ(frame_bits_nominal(8), 111);  // 1+11+1+1+1+4 + 64 + 15+1+1+1+7 + 3 IFS
  EXPECT_EQ(frame_bits_worst(8), 135);
  EXPECT_EQ(frame_bits_nominal(0), 47);
}

TEST(BusLoad, TwoFramesPerTickIsAQuarterOfTheBus) {
  // The issue: 2 axes x 1 kHz streaming would take 22-27 % of 1 Mbit/s.
  tnv::fw::can::NodeSettings s;
  s.telemetry = {};
  s.telemetry.heartbeat_ms = 0;
  s.telemetry.following_ms = 0;
  s.telemetry.position_ms = 1;
  s.telemetry.contour_ms = 1;
  const BusLoad load = telemetry_load(s);
  EXPECT_DOUBLE_EQ(load.frames_per_s, 2000.0);
  EXPECT_NEAR(load.load_nominal, 0.222, 1e-9);
  EXPECT_NEAR(load.load_worst, 0.270, 1e-9);
}

TEST(BusLoad, DefaultTelemetryIsLight) {
  const BusLoad load = telemetry_load(tnv::fw::can::default_node_settings());
  EXPECT_GT(load.frames_per_s, 0.0);
  EXPECT_LT(load.load_worst, 0.05) << "the default cyclic set should leave the bus to requests";
}

}  // namespace
