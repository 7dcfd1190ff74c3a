#include "firmware/can/param_image.hpp"

#include <array>
#include <bit>
#include <cstring>

#include "firmware/can/param_table.hpp"

namespace tnv::fw::can {
namespace {

constexpr std::array<std::uint32_t, 256> make_crc_table() noexcept {
  std::array<std::uint32_t, 256> t{};
  for (std::uint32_t n = 0; n < 256; ++n) {
    std::uint32_t c = n;
    for (int k = 0; k < 8; ++k) c = (c & 1u) != 0 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    t[n] = c;
  }
  return t;
}
constexpr std::array<std::uint32_t, 256> kCrcTable = make_crc_table();

void put_le(std::span<std::uint8_t> out, std::size_t at, std::uint64_t v, std::size_t bytes) noexcept {
  for (std::size_t i = 0; i < bytes; ++i) out[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
std::uint64_t get_le(std::span<const std::uint8_t> in, std::size_t at, std::size_t bytes) noexcept {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < bytes; ++i) v |= static_cast<std::uint64_t>(in[at + i]) << (8 * i);
  return v;
}

bool stored(const ParamDef& p) noexcept { return p.access == Access::read_write && p.set != nullptr; }

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes) noexcept {
  std::uint32_t c = 0xFFFFFFFFu;
  for (const std::uint8_t b : bytes) c = kCrcTable[(c ^ b) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

std::size_t encode_image(const NodeSettings& settings, std::span<std::uint8_t> out) noexcept {
  std::size_t count = 0;
  for (const ParamDef& p : param_table())
    if (stored(p)) ++count;
  const std::size_t size = kParamImageHeaderBytes + count * kParamImageEntryBytes + kParamImageCrcBytes;
  if (count > kParamImageMaxEntries || out.size() < size) return 0;
  put_le(out, 0, kParamImageMagic, 4);
  put_le(out, 4, kParamImageVersion, 2);
  put_le(out, 6, count, 2);
  std::size_t at = kParamImageHeaderBytes;
  for (const ParamDef& p : param_table()) {
    if (!stored(p)) continue;
    put_le(out, at, p.id, 2);
    put_le(out, at + 2, std::bit_cast<std::uint64_t>(p.get(settings)), 8);
    at += kParamImageEntryBytes;
  }
  put_le(out, at, crc32(out.first(at)), 4);
  return size;
}

ErrorCode decode_image(std::span<const std::uint8_t> image, NodeSettings& inout) noexcept {
  if (image.size() < kParamImageHeaderBytes + kParamImageCrcBytes) return ErrorCode::storage_corrupt;
  if (get_le(image, 0, 4) != kParamImageMagic || get_le(image, 4, 2) != kParamImageVersion)
    return ErrorCode::storage_corrupt;
  const std::size_t count = static_cast<std::size_t>(get_le(image, 6, 2));
  const std::size_t body = kParamImageHeaderBytes + count * kParamImageEntryBytes;
  if (image.size() != body + kParamImageCrcBytes) return ErrorCode::storage_corrupt;
  if (get_le(image, body, 4) != crc32(image.first(body))) return ErrorCode::storage_corrupt;
  NodeSettings next = inout;
  for (std::size_t e = 0; e < count; ++e) {
    const std::size_t at = kParamImageHeaderBytes + e * kParamImageEntryBytes;
    const ParamDef* p = find_param(static_cast<std::uint16_t>(get_le(image, at, 2)));
    if (p == nullptr || !stored(*p)) return ErrorCode::storage_corrupt;
    const double value = std::bit_cast<double>(get_le(image, at + 2, 8));
    if (check_value(*p, value) != ErrorCode::ok) return ErrorCode::storage_corrupt;
    p->set(next, value);
  }
  if (!validate(next).ok) return ErrorCode::invalid;
  inout = next;
  return ErrorCode::ok;
}

ErrorCode load_settings(hal::ParamStorage& storage, NodeSettings& inout) noexcept {
  std::array<std::uint8_t, kParamImageMaxBytes> buffer{};
  std::size_t size = 0;
  const hal::HalStatus st = storage.read(buffer, size);
  if (st == hal::HalStatus::not_present) return ErrorCode::ok;
  if (st != hal::HalStatus::ok || size > buffer.size()) return ErrorCode::storage_error;
  return decode_image(std::span<const std::uint8_t>(buffer.data(), size), inout);
}

ErrorCode save_settings(hal::ParamStorage& storage, const NodeSettings& settings) noexcept {
  std::array<std::uint8_t, kParamImageMaxBytes> buffer{};
  const std::size_t size = encode_image(settings, buffer);
  if (size == 0) return ErrorCode::storage_error;
  return storage.write(std::span<const std::uint8_t>(buffer.data(), size)) == hal::HalStatus::ok
             ? ErrorCode::ok
             : ErrorCode::storage_error;
}

}  // namespace tnv::fw::can
