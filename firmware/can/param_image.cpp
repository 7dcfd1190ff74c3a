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

// Where the parts of an intact image are: header and trailing-block sizes,
// by version (header 0: not an image).
struct Layout {
  std::size_t header = 0;
  std::size_t entries = 0;      // count
  std::size_t bore_state = 0;   // bytes of the bore-state block (0 before version 3)
  std::size_t body() const noexcept { return header + entries * kParamImageEntryBytes + bore_state; }
};

Layout layout_of(std::uint64_t version, std::size_t count) noexcept {
  if (version == kParamImageVersion) return {kParamImageHeaderBytes, count, kBoreStateImageBytes};
  if (version == kParamImageVersion2) return {kParamImageHeaderBytes, count, 0};
  if (version == kParamImageVersion1) return {kParamImageVersion1HeaderBytes, count, 0};
  return {};
}

// Magic, version, length and CRC: the image's layout, header 0 when any is wrong.
Layout intact_layout(std::span<const std::uint8_t> image) noexcept {
  if (image.size() < kParamImageVersion1HeaderBytes + kParamImageCrcBytes) return {};
  if (get_le(image, 0, 4) != kParamImageMagic) return {};
  const Layout l = layout_of(get_le(image, 4, 2), static_cast<std::size_t>(get_le(image, 6, 2)));
  if (l.header == 0) return {};
  if (image.size() != l.body() + kParamImageCrcBytes) return {};
  if (get_le(image, l.body(), 4) != crc32(image.first(l.body()))) return {};
  return l;
}

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes) noexcept {
  std::uint32_t c = 0xFFFFFFFFu;
  for (const std::uint8_t b : bytes) c = kCrcTable[(c ^ b) & 0xFFu] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

std::size_t encode_image(const NodeSettings& settings, std::span<std::uint8_t> out,
                         std::uint32_t generation) noexcept {
  std::size_t count = 0;
  for (const ParamDef& p : param_table())
    if (stored(p)) ++count;
  const std::size_t size =
      kParamImageHeaderBytes + count * kParamImageEntryBytes + kBoreStateImageBytes + kParamImageCrcBytes;
  if (count > kParamImageMaxEntries || out.size() < size) return 0;
  put_le(out, 0, kParamImageMagic, 4);
  put_le(out, 4, kParamImageVersion, 2);
  put_le(out, 6, count, 2);
  put_le(out, 8, generation, 4);
  std::size_t at = kParamImageHeaderBytes;
  for (const ParamDef& p : param_table()) {
    if (!stored(p)) continue;
    put_le(out, at, p.id, 2);
    put_le(out, at + 2, std::bit_cast<std::uint64_t>(p.get(settings)), 8);
    at += kParamImageEntryBytes;
  }
  encode_bore_state(settings.bore_state, out.subspan(at).first<kBoreStateImageBytes>());
  at += kBoreStateImageBytes;
  put_le(out, at, crc32(out.first(at)), 4);
  return size;
}

bool image_generation(std::span<const std::uint8_t> image, std::uint32_t& generation) noexcept {
  const Layout l = intact_layout(image);
  if (l.header == 0) return false;
  generation = l.header == kParamImageHeaderBytes ? static_cast<std::uint32_t>(get_le(image, 8, 4)) : 0u;
  return true;
}

void stamp_generation(std::span<std::uint8_t> image, std::uint32_t generation) noexcept {
  if (intact_layout(image).header != kParamImageHeaderBytes) return;
  put_le(image, 8, generation, 4);
  const std::size_t body = image.size() - kParamImageCrcBytes;
  put_le(image, body, crc32(image.first(body)), 4);
}

std::uint32_t next_generation(hal::ParamStorage& storage) noexcept {
  std::array<std::uint8_t, kParamImageMaxBytes> buffer{};
  std::size_t size = 0;
  std::uint32_t generation = 0;
  if (storage.read(buffer, size) != hal::HalStatus::ok || size > buffer.size() ||
      !image_generation(std::span<const std::uint8_t>(buffer.data(), size), generation))
    return 1;
  return generation == 0xFFFFFFFFu ? generation : generation + 1;  // saturates: 4e9 saves is no machine's life
}

ErrorCode decode_image(std::span<const std::uint8_t> image, NodeSettings& inout) noexcept {
  const Layout l = intact_layout(image);
  if (l.header == 0) return ErrorCode::storage_corrupt;
  NodeSettings next = inout;
  for (std::size_t e = 0; e < l.entries; ++e) {
    const std::size_t at = l.header + e * kParamImageEntryBytes;
    const ParamDef* p = find_param(static_cast<std::uint16_t>(get_le(image, at, 2)));
    if (p == nullptr || !stored(*p)) return ErrorCode::storage_corrupt;
    const double value = std::bit_cast<double>(get_le(image, at + 2, 8));
    if (check_value(*p, value) != ErrorCode::ok) return ErrorCode::storage_corrupt;
    p->set(next, value);
  }
  // The learned state, whole and plausible, or the image is damaged.
  if (l.bore_state != 0) {
    const std::size_t at = l.header + l.entries * kParamImageEntryBytes;
    if (!decode_bore_state(image.subspan(at).first<kBoreStateImageBytes>(), next.bore_state))
      return ErrorCode::storage_corrupt;
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
  const std::size_t size = encode_image(settings, buffer, next_generation(storage));
  if (size == 0) return ErrorCode::storage_error;
  return storage.write(std::span<const std::uint8_t>(buffer.data(), size)) == hal::HalStatus::ok
             ? ErrorCode::ok
             : ErrorCode::storage_error;
}

}  // namespace tnv::fw::can
