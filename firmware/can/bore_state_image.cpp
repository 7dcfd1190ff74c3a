#include "firmware/can/bore_state_image.hpp"

#include <bit>

namespace tnv::fw::can {

namespace {

// Little-endian, one field after the other.
class BlockWriter {
 public:
  explicit BlockWriter(std::span<std::uint8_t> out) noexcept : out_(out) {}
  void u32(std::uint32_t v) noexcept { put(v, 4); }
  void i32(std::int32_t v) noexcept { put(static_cast<std::uint32_t>(v), 4); }
  void f64(double v) noexcept { put(std::bit_cast<std::uint64_t>(v), 8); }

 private:
  void put(std::uint64_t v, std::size_t bytes) noexcept {
    for (std::size_t i = 0; i < bytes; ++i) out_[at_ + i] = static_cast<std::uint8_t>(v >> (8 * i));
    at_ += bytes;
  }
  std::span<std::uint8_t> out_;
  std::size_t at_ = 0;
};

class BlockReader {
 public:
  explicit BlockReader(std::span<const std::uint8_t> in) noexcept : in_(in) {}
  std::uint32_t u32() noexcept { return static_cast<std::uint32_t>(get(4)); }
  std::int32_t i32() noexcept { return static_cast<std::int32_t>(static_cast<std::uint32_t>(get(4))); }
  double f64() noexcept { return std::bit_cast<double>(get(8)); }

 private:
  std::uint64_t get(std::size_t bytes) noexcept {
    std::uint64_t v = 0;
    for (std::size_t i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(in_[at_ + i]) << (8 * i);
    at_ += bytes;
    return v;
  }
  std::span<const std::uint8_t> in_;
  std::size_t at_ = 0;
};

}  // namespace

void encode_bore_state(const BoringStationState& state, std::span<std::uint8_t, kBoreStateImageBytes> out) noexcept {
  const BoringPlannerState& p = state.planner;
  BlockWriter w(out);
  w.u32(p.started ? 1u : 0u);
  w.i32(p.parts);
  w.i32(p.resets);
  w.i32(p.streak);
  for (std::int32_t n : p.position_streak) w.i32(n);
  for (int i = 0; i < 3; ++i) w.f64(p.theta(i));
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) w.f64(p.covariance(r, c));
  w.f64(p.innovation);
  for (double v : state.infeed_mm_rev) w.f64(v);
}

bool decode_bore_state(std::span<const std::uint8_t, kBoreStateImageBytes> in, BoringStationState& out) noexcept {
  BoringStationState s;
  BoringPlannerState& p = s.planner;
  BlockReader r(in);
  const std::uint32_t started = r.u32();
  if (started > 1u) return false;
  p.started = started == 1u;
  p.parts = r.i32();
  p.resets = r.i32();
  p.streak = r.i32();
  for (std::int32_t& n : p.position_streak) n = r.i32();
  for (int i = 0; i < 3; ++i) p.theta(i) = r.f64();
  for (int row = 0; row < 3; ++row)
    for (int c = 0; c < 3; ++c) p.covariance(row, c) = r.f64();
  p.innovation = r.f64();
  for (double& v : s.infeed_mm_rev) v = r.f64();
  if (!validate(s).ok) return false;
  out = s;
  return true;
}

}  // namespace tnv::fw::can
