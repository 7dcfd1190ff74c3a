// The per-axis noise sources (tool accelerometer, encoder glitches) draw
// one stream per axis of the list: x and y the streams they always drew
// (so seeded runs stay bit for bit), a further axis new ones of its own.
#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <set>

#include "emulator/noise_stream.hpp"
#include "hal/axis.hpp"

namespace tnv::emu {
namespace {

TEST(AxisNoiseStream, XAndYKeepTheirStreamNumbers) {
  EXPECT_EQ(axis_noise_stream(AxisNoise::accel, hal::index(hal::Axis::x)), 2u);
  EXPECT_EQ(axis_noise_stream(AxisNoise::accel, hal::index(hal::Axis::y)), 3u);
  EXPECT_EQ(axis_noise_stream(AxisNoise::glitch, hal::index(hal::Axis::x)), 4u);
  EXPECT_EQ(axis_noise_stream(AxisNoise::glitch, hal::index(hal::Axis::y)), 5u);
}

TEST(AxisNoiseStream, OneStreamPerAxisOfTheListDrawingItsOwnNumbers) {
  constexpr std::uint64_t kSeed = 20261129;
  for (const AxisNoise source : {AxisNoise::accel, AxisNoise::glitch}) {
    std::array<NoiseStream, hal::kAxisCount> streams = make_axis_noise_streams(kSeed, source);
    for (const hal::Axis a : hal::kAxes) {
      const std::size_t i = hal::index(a);
      NoiseStream expected(kSeed, axis_noise_stream(source, i));
      for (int k = 0; k < 16; ++k) ASSERT_EQ(streams[i].normal(), expected.normal()) << hal::axis_label(a);
    }
  }
}

TEST(AxisNoiseStream, AFurtherAxisGetsNewStreamsNoneShared) {
  // Up to 26 axes (one letter each): no stream twice, none of the node-wide sources'.
  std::set<std::uint64_t> seen = {static_cast<std::uint64_t>(NoiseStreamId::force_adc),
                                  static_cast<std::uint64_t>(NoiseStreamId::io_jitter),
                                  static_cast<std::uint64_t>(NoiseStreamId::bore_gauge)};
  for (std::size_t i = 0; i < 26; ++i)
    for (const AxisNoise source : {AxisNoise::accel, AxisNoise::glitch})
      EXPECT_TRUE(seen.insert(axis_noise_stream(source, i)).second) << "axis " << i;
  EXPECT_EQ(axis_noise_stream(AxisNoise::accel, 2), kFirstFurtherAxisStream);
  EXPECT_EQ(axis_noise_stream(AxisNoise::glitch, 2), kFirstFurtherAxisStream + 1);
}

}  // namespace
}  // namespace tnv::emu
