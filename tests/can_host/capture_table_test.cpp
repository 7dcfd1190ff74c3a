// Capture image decoding, channel lists, CSV round trip and circle scoring.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>

#include "firmware/can/capture_channels.hpp"
#include "tools/can/capture_csv.hpp"
#include "tools/can/capture_score.hpp"
#include "tools/can/capture_table.hpp"

namespace tnv {
namespace {

using can_host::CaptureTable;

void put(std::vector<std::uint8_t>& image, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) image.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

// pos_x (i32 nm), ref_x (i32 nm), contour (f32 um), motion_tick (i32): 4 samples.
std::vector<std::uint8_t> image_of(const std::vector<std::array<double, 4>>& rows) {
  std::vector<std::uint8_t> image;
  for (const auto& r : rows) {
    put(image, static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(r[0] * 1e6))));
    put(image, static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(r[1] * 1e6))));
    put(image, std::bit_cast<std::uint32_t>(static_cast<float>(r[2])));
    put(image, static_cast<std::uint32_t>(static_cast<std::int32_t>(r[3])));
  }
  return image;
}

using fw::can::channel_bit;
constexpr std::uint32_t kMask = (1u << channel_bit("pos_x")) | (1u << channel_bit("ref_x")) |
                                (1u << channel_bit("contour")) | (1u << channel_bit("motion_tick"));

TEST(CaptureTable, DecodesSampleMajorChannelsInBitOrderToPhysicalUnits) {
  const auto image = image_of({{6.0, 6.0, 0.0, -1}, {5.999999, 6.000001, 0.5, 0}, {-0.000123, 0.0, 1.25, 1}});
  std::string error;
  const auto t = can_host::decode_capture(image, kMask, 3, 2, error);
  ASSERT_TRUE(t) << error;
  ASSERT_EQ(t->channels.size(), 4u);
  EXPECT_STREQ(t->channels[0]->name, "pos_x");
  EXPECT_STREQ(t->channels[3]->name, "motion_tick");
  EXPECT_EQ(t->samples(), 3u);
  EXPECT_NEAR((*t->column("pos_x"))[1], 5.999999, 1e-12);
  EXPECT_NEAR((*t->column("pos_x"))[2], -0.000123, 1e-12) << "signed nm";
  EXPECT_EQ((*t->column("contour"))[2], 1.25);
  EXPECT_EQ((*t->column("motion_tick"))[0], -1.0);
  EXPECT_EQ(t->column("pos_y"), nullptr);
  EXPECT_DOUBLE_EQ(t->period_s(), 0.002);
}

TEST(CaptureTable, AnImageOfTheWrongLengthIsRefused) {
  auto image = image_of({{6.0, 6.0, 0.0, -1}});
  image.pop_back();
  std::string error;
  EXPECT_FALSE(can_host::decode_capture(image, kMask, 1, 1, error));
  EXPECT_NE(error.find("15 bytes"), std::string::npos) << error;
}

TEST(CaptureTable, ChannelListsByNameWithClearErrors) {
  std::string error;
  EXPECT_EQ(can_host::parse_channel_list("pos_x,ref_x,contour,motion_tick", error), kMask);
  EXPECT_EQ(can_host::parse_channel_list("default", error), fw::can::kDefaultCaptureChannels);
  EXPECT_FALSE(can_host::parse_channel_list("pos_x,contuor", error));
  EXPECT_NE(error.find("'contuor'"), std::string::npos) << error;
  EXPECT_NE(error.find("motion_tick"), std::string::npos) << "lists the valid names: " << error;
  EXPECT_FALSE(can_host::parse_channel_list(",", error));
  EXPECT_EQ(can_host::channel_list_text(kMask), "pos_x,ref_x,contour,motion_tick");
}

TEST(CaptureCsv, RoundTripsExactlyAndNamesUnits) {
  const auto image = image_of({{6.0, 6.0, 0.0, -1}, {5.999999, 6.000001, 0.123456789, 0}, {-0.000123, 0.0, 1.25, 1}});
  std::string error;
  const auto t = can_host::decode_capture(image, kMask, 3, 1, error);
  ASSERT_TRUE(t);
  const std::string csv = can_host::capture_csv(*t);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t_s,pos_x_mm,ref_x_mm,contour_um,motion_tick");
  const auto back = can_host::read_capture_csv(csv, error);
  ASSERT_TRUE(back) << error;
  ASSERT_EQ(back->channels.size(), 4u);
  for (std::size_t c = 0; c < 4; ++c)
    for (std::size_t s = 0; s < 3; ++s) {
      if (c == 2) EXPECT_EQ(static_cast<float>(back->columns[c][s]), static_cast<float>(t->columns[c][s]));
      else EXPECT_NEAR(back->columns[c][s], t->columns[c][s], 1e-12);
    }
  EXPECT_FALSE(can_host::read_capture_csv("t_s,pos_q_mm\n0,1\n", error));
  EXPECT_NE(error.find("pos_q_mm"), std::string::npos) << error;
  EXPECT_FALSE(can_host::read_capture_csv("t_s,pos_x_mm\n0,1\n0.001,nan\n", error));
  EXPECT_NE(error.find("line 3"), std::string::npos) << error;
}

TEST(CaptureScore, ScoresOnlySamplesInMotionLikeTheHilRun) {
  const auto image = image_of({{6.0, 6.0, 9.0, -1}, {6.0, 6.0, 1.0, 0}, {6.0, 6.0, 3.0, 1}, {6.0, 6.0, 7.0, -1}});
  std::string error;
  const auto t = can_host::decode_capture(image, kMask, 4, 1, error);
  ASSERT_TRUE(t);
  const auto stats = can_host::score_circle(*t, error);
  ASSERT_TRUE(stats) << error;
  EXPECT_EQ(stats->samples, 2u);
  EXPECT_NEAR(stats->max_um, 3.0, 1e-12);
  EXPECT_NEAR(stats->mean_um, 2.0, 1e-12);
  EXPECT_NEAR(stats->std_um, 1.0, 1e-12);
  const auto trace = can_host::circle_trace(*t);
  ASSERT_EQ(trace.size(), 2u);
  EXPECT_DOUBLE_EQ(trace[1].t_s, 0.001);
}

TEST(CaptureScore, NeedsMotionTickAndAContour) {
  std::vector<std::uint8_t> image;
  put(image, 0);
  std::string error;
  const auto t = can_host::decode_capture(image, 1u << 0, 1, 1, error);
  ASSERT_TRUE(t);
  EXPECT_FALSE(can_host::score_circle(*t, error));
  EXPECT_NE(error.find("motion_tick"), std::string::npos) << error;
}

}  // namespace
}  // namespace tnv
