// The per-axis telemetry messages of protocol 5 on the host: TelemetryView
// takes each axis' frame into its axis' slot, PathTelemetry pairs the
// plane's two axes of a tick (position and following error share an
// axis' frame), and telemetry decoded from an axis' frame is never put in
// another axis' place.
#include <gtest/gtest.h>

#include "firmware/can/frame_codec.hpp"
#include "firmware/can/node_fields.hpp"
#include "hal/axis.hpp"
#include "tools/can/path_telemetry.hpp"
#include "tools/can/telemetry_json.hpp"
#include "tools/can/telemetry_view.hpp"

namespace tnv {
namespace {

namespace can = fw::can;
namespace f = fw::can::fields;

hal::CanFrame axis_frame(const std::array<const can::MessageDef*, hal::kAxisCount>& block, hal::Axis a,
                         const can::FieldDef& field, double value) {
  hal::CanFrame frame = can::make_frame(*block[hal::index(a)], 1);
  can::write(frame, field, value);
  return frame;
}

hal::CanFrame position_frame(hal::Axis a, double position_mm, double following_mm) {
  hal::CanFrame frame = axis_frame(f::kPositionMsgs, a, f::kPosition, position_mm);
  can::write(frame, f::kFollowing, following_mm);
  return frame;
}

can::MessageId id_of(const hal::CanFrame& frame) { return static_cast<can::MessageId>(can::message_of(frame.id)); }

TEST(AxisTelemetry, EachAxisFrameFillsItsOwnAxis) {
  can_host::TelemetryView view;
  for (const hal::Axis a : hal::kAxes) {
    const double i = static_cast<double>(hal::index(a));
    for (const hal::CanFrame& fr : {position_frame(a, 1.5 + i, 0.001 * (i + 1)),
                                    axis_frame(f::kSlidingMsgs, a, f::kSlidingS, -2.0 - i),
                                    axis_frame(f::kDacMsgs, a, f::kDacCode, 30000 + i)})
      view.take(fr, id_of(fr));
  }
  ASSERT_TRUE(view.position_mm && view.following_mm && view.s_mm_s && view.output);
  for (const hal::Axis a : hal::kAxes) {
    SCOPED_TRACE(hal::axis_label(a));
    const std::size_t i = hal::index(a);
    EXPECT_NEAR((*view.position_mm)[i], 1.5 + static_cast<double>(i), 1e-6);
    EXPECT_NEAR((*view.following_mm)[i], 0.001 * static_cast<double>(i + 1), 1e-6);
    EXPECT_EQ((*view.s_mm_s)[i], -2.0 - static_cast<double>(i));
    EXPECT_EQ(view.output->dac_code[i], 30000.0 + static_cast<double>(i));
  }
  EXPECT_EQ(view.frames, 3 * hal::kAxisCount);
}

TEST(AxisTelemetry, PathSamplesPairThePlaneAxesOfATick) {
  can_host::PathTelemetry path;
  const auto take = [&path](const hal::CanFrame& fr) { path.take(fr, id_of(fr)); };
  // Counting began between x and y of a tick: that tick's y is no sample.
  take(position_frame(hal::kPlaneSecond, 9.0, 0.5));
  EXPECT_TRUE(path.samples().empty());
  for (const double x : {1.0, 2.0}) {
    take(position_frame(hal::kPlaneFirst, x, 0.001 * x));
    EXPECT_EQ(path.unpaired(), 1u);
    for (const hal::Axis a : hal::kAxes)  // the other axes' frames are not part of a sample
      if (a != hal::kPlaneFirst && a != hal::kPlaneSecond) take(position_frame(a, 77.0, 0.0));
    take(axis_frame(f::kSlidingMsgs, hal::kPlaneSecond, f::kSlidingS, 5.0));  // nor other messages
    take(position_frame(hal::kPlaneSecond, -x, -0.001 * x));
  }
  ASSERT_EQ(path.samples().size(), 2u);
  EXPECT_NEAR(path.samples()[0].position_mm[0], 1.0, 1e-9);
  EXPECT_NEAR(path.samples()[0].position_mm[1], -1.0, 1e-9);
  EXPECT_NEAR(path.samples()[0].reference_mm[0], 1.001, 1e-9);
  EXPECT_NEAR(path.samples()[1].reference_mm[1], -2.002, 1e-9);
  EXPECT_EQ(path.unpaired(), 0u);
}

TEST(AxisTelemetry, HeartbeatJsonNamesTheAxisBits) {
  hal::CanFrame hb = can::make_frame(f::kHeartbeatMsg, 1);
  can::write_raw(hb, f::kHbAxes, can::hb_homed_bit(hal::Axis::y) | can::hb_shaper_bit(hal::Axis::x));
  const can_host::Heartbeat h = can_host::read_heartbeat(hb);
  EXPECT_TRUE(h.homed(hal::Axis::y));
  EXPECT_FALSE(h.homed(hal::Axis::x));
  EXPECT_TRUE(h.shaper_on(hal::Axis::x));
  const nlohmann::json j = can_host::heartbeat_json(h);
  EXPECT_EQ(j["flags"], nlohmann::json::array({"shaper_x", "homed_y"}));
}

}  // namespace
}  // namespace tnv
