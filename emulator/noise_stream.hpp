#pragma once
// Seeded random numbers for the emulator's noise and transport jitter
// ([noise], [io]; docs/scenarios.md). std::mt19937_64, whose output the C++
// standard fixes, with the uniform, Gaussian and exponential transforms
// written out here rather than taken from <random>'s distributions (each
// standard library picks its own algorithm for those): one seed, one
// sequence, on every standard library. One stream per noise source, each
// seeded from the scenario seed and its own stream number, so switching
// one source on does not reshuffle another.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numbers>
#include <random>
#include <utility>

#include "hal/axis.hpp"

namespace tnv::emu {

// splitmix64's finaliser over (seed, stream): well-spread engine seeds.
constexpr std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream) noexcept {
  std::uint64_t z = seed + (stream + 1) * 0x9E37'79B9'7F4A'7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58'476D'1CE4'E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D0'49BB'1331'11EBull;
  return z ^ (z >> 31);
}

class NoiseStream {
 public:
  NoiseStream(std::uint64_t seed, std::uint64_t stream) : engine_(mix_seed(seed, stream)) {}

  // Uniform in [0, 1): the top 53 bits of one draw.
  double uniform() noexcept { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

  // Standard normal by Box-Muller; the pair's second value is kept for the next call.
  double normal() noexcept {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double radius = std::sqrt(-2.0 * std::log(1.0 - uniform()));  // 1 - u in (0, 1]: log finite
    const double angle = 2.0 * std::numbers::pi * uniform();
    spare_ = radius * std::sin(angle);
    has_spare_ = true;
    return radius * std::cos(angle);
  }

  // Exponential with mean 1: the gap between Poisson events at rate 1.
  double exponential() noexcept { return -std::log(1.0 - uniform()); }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

// Stream numbers (fixed: changing one changes every seeded run). The
// per-axis sources' streams are axis_noise_stream()'s.
enum class NoiseStreamId : std::uint64_t {
  force_adc = 1,
  accel_x = 2,
  accel_y = 3,
  glitch_x = 4,
  glitch_y = 5,
  io_jitter = 6,
  bore_gauge = 7,  // the S4 post-process gauge (boring_process.hpp)
};

inline NoiseStream make_noise_stream(std::uint64_t seed, NoiseStreamId id) {
  return NoiseStream(seed, static_cast<std::uint64_t>(id));
}

// A noise source with a stream per axis.
enum class AxisNoise : std::uint64_t {
  accel = 0,   // the tool accelerometer's random part
  glitch = 1,  // encoder glitches
};

// The first stream number past NoiseStreamId's: axes after x and y draw from here on.
inline constexpr std::uint64_t kFirstFurtherAxisStream = 8;

// The stream of `source` on the axis with list index `axis_index`: x and y
// keep the numbers they had before the list (accel_x/_y, glitch_x/_y), so
// their runs stay bit-identical; each further axis takes a pair of new ones
// (accel, glitch) from kFirstFurtherAxisStream on.
constexpr std::uint64_t axis_noise_stream(AxisNoise source, std::size_t axis_index) noexcept {
  const auto k = static_cast<std::uint64_t>(source);
  if (axis_index < 2) {
    const NoiseStreamId first = source == AxisNoise::accel ? NoiseStreamId::accel_x : NoiseStreamId::glitch_x;
    return static_cast<std::uint64_t>(first) + axis_index;
  }
  return kFirstFurtherAxisStream + 2 * (axis_index - 2) + k;
}

// One stream of `source` per axis of the list, in index order.
inline std::array<NoiseStream, hal::kAxisCount> make_axis_noise_streams(std::uint64_t seed, AxisNoise source) {
  return [&]<std::size_t... I>(std::index_sequence<I...>) {
    return std::array<NoiseStream, hal::kAxisCount>{NoiseStream(seed, axis_noise_stream(source, I))...};
  }(std::make_index_sequence<hal::kAxisCount>{});
}

namespace detail {
// No two streams alike and none of NoiseStreamId's, for `axes` axes.
constexpr bool axis_noise_streams_distinct(std::size_t axes) noexcept {
  for (std::size_t i = 0; i < 2 * axes; ++i) {
    const std::uint64_t a = axis_noise_stream(static_cast<AxisNoise>(i % 2), i / 2);
    for (const NoiseStreamId id : {NoiseStreamId::force_adc, NoiseStreamId::io_jitter, NoiseStreamId::bore_gauge})
      if (a == static_cast<std::uint64_t>(id)) return false;
    for (std::size_t j = 0; j < i; ++j)
      if (a == axis_noise_stream(static_cast<AxisNoise>(j % 2), j / 2)) return false;
  }
  return true;
}
}  // namespace detail
static_assert(detail::axis_noise_streams_distinct(hal::kAxisCount) && detail::axis_noise_streams_distinct(26),
              "every axis' noise sources draw from streams of their own");

}  // namespace tnv::emu
