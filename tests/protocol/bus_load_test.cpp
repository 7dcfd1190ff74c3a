// Bus time of the default telemetry and the streaming estimate.
#include <gtest/gtest.h>

#include "hal/axis.hpp"
#include "tools/protogen/bus_load.hpp"

namespace {

using namespace tnv::protogen;

TEST(BusLoad, FrameBits) {
  EXPECT_EQ(frame_bits_nominal(8), 111);  // 1+11+1+1+1+4 + 64 + 15+1+1+1+7 + 3 IFS
  EXPECT_EQ(frame_bits_worst(8), 135);
  EXPECT_EQ(frame_bits_nominal(0), 47);
}

TEST(BusLoad, PositionsAndContourEveryTickCountAFramePerAxis) {
  // TLM_POSITION_<AXIS> is one 8-byte frame per axis, TLM_CONTOUR one more.
  tnv::fw::can::NodeSettings s;
  s.telemetry = {};
  s.telemetry.heartbeat_ms = 0;
  s.telemetry.position_ms = 1;
  s.telemetry.contour_ms = 1;
  const BusLoad load = telemetry_load(s);
  const double axes = static_cast<double>(tnv::hal::kAxisCount);
  EXPECT_DOUBLE_EQ(load.frames_per_s, 1000.0 * (axes + 1.0));
  EXPECT_NEAR(load.load_nominal, 1e-3 * (axes + 1.0) * 111.0, 1e-9);  // 47 + 8 x 8 bits per frame
  EXPECT_NEAR(load.load_worst, 1e-3 * (axes + 1.0) * 135.0, 1e-9);
  if (tnv::hal::kAxisCount == 2) {
    EXPECT_NEAR(load.load_nominal, 0.333, 1e-9) << "two axes: 3 x 111 bits per ms";
  }
}

TEST(BusLoad, DefaultTelemetryIsLight) {
  const BusLoad load = telemetry_load(tnv::fw::can::default_node_settings());
  EXPECT_GT(load.frames_per_s, 0.0);
  EXPECT_LT(load.load_worst, 0.05) << "the default cyclic set should leave the bus to requests";
}

}  // namespace
