#include "drivers/linux/register_frame.hpp"

namespace tnv::drivers::regwire {

namespace {

void put16(std::uint8_t* p, std::uint16_t v) noexcept {
  p[0] = static_cast<std::uint8_t>(v);
  p[1] = static_cast<std::uint8_t>(v >> 8);
}
void put32(std::uint8_t* p, std::uint32_t v) noexcept {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(v >> (8 * i));
}
std::uint16_t get16(const std::uint8_t* p) noexcept { return static_cast<std::uint16_t>(p[0] | (p[1] << 8)); }
std::uint32_t get32(const std::uint8_t* p) noexcept {
  return static_cast<std::uint32_t>(p[0]) | (static_cast<std::uint32_t>(p[1]) << 8) |
         (static_cast<std::uint32_t>(p[2]) << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
}

std::size_t seal(FrameBuffer& out, std::size_t body) noexcept {
  put32(out.data() + body, crc32({out.data(), body}));
  return body + kCrcBytes;
}

bool crc_ok(std::span<const std::uint8_t> in) noexcept {
  const std::size_t body = in.size() - kCrcBytes;
  return crc32(in.first(body)) == get32(in.data() + body);
}

bool is_status(std::uint8_t s) noexcept { return s <= static_cast<std::uint8_t>(hal::HalStatus::bad_address); }

}  // namespace

std::uint32_t crc32(std::span<const std::uint8_t> bytes) noexcept {
  std::uint32_t crc = 0xFFFFFFFFu;
  for (const std::uint8_t b : bytes) {
    crc ^= b;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::size_t encode_read_request(std::uint8_t seq, std::uint16_t first_word, std::uint16_t count,
                                FrameBuffer& out) noexcept {
  if (count == 0 || count > kMaxWords) return 0;
  out[0] = kRequestMagic;
  out[1] = kOpRead;
  out[2] = seq;
  put16(&out[3], first_word);
  put16(&out[5], count);
  return seal(out, kRequestHeaderBytes);
}

std::size_t encode_write_request(std::uint8_t seq, std::uint16_t first_word, std::span<const std::uint32_t> data,
                                 FrameBuffer& out) noexcept {
  if (data.empty() || data.size() > kMaxWords) return 0;
  out[0] = kRequestMagic;
  out[1] = kOpWrite;
  out[2] = seq;
  put16(&out[3], first_word);
  put16(&out[5], static_cast<std::uint16_t>(data.size()));
  std::size_t at = kRequestHeaderBytes;
  for (const std::uint32_t w : data) {
    put32(&out[at], w);
    at += 4;
  }
  return seal(out, at);
}

std::size_t reply_bytes(std::uint8_t op, std::uint16_t count) noexcept {
  return kReplyHeaderBytes + (op == kOpRead ? 4u * count : 0u) + kCrcBytes;
}

const char* to_string(DecodeError e) noexcept {
  switch (e) {
    case DecodeError::none: return "ok";
    case DecodeError::short_frame: return "frame too short";
    case DecodeError::bad_magic: return "bad magic byte";
    case DecodeError::bad_op: return "unknown operation";
    case DecodeError::bad_count: return "word count out of range";
    case DecodeError::bad_length: return "length does not match the word count";
    case DecodeError::bad_crc: return "CRC mismatch";
  }
  return "?";
}

DecodeError decode_request(std::span<const std::uint8_t> in, Request& out) noexcept {
  if (in.size() < kRequestHeaderBytes + kCrcBytes) return DecodeError::short_frame;
  if (in[0] != kRequestMagic) return DecodeError::bad_magic;
  if (!crc_ok(in)) return DecodeError::bad_crc;
  out.op = in[1];
  out.seq = in[2];
  out.first_word = get16(&in[3]);
  out.count = get16(&in[5]);
  if (out.op != kOpRead && out.op != kOpWrite) return DecodeError::bad_op;
  if (out.count == 0 || out.count > kMaxWords) return DecodeError::bad_count;
  const std::size_t data_bytes = out.op == kOpWrite ? 4u * out.count : 0u;
  if (in.size() != kRequestHeaderBytes + data_bytes + kCrcBytes) return DecodeError::bad_length;
  for (std::size_t i = 0; i < (out.op == kOpWrite ? out.count : 0u); ++i) {
    out.data[i] = get32(&in[kRequestHeaderBytes + 4 * i]);
  }
  return DecodeError::none;
}

std::size_t encode_reply(std::uint8_t seq, hal::HalStatus status, std::span<const std::uint32_t> data,
                         FrameBuffer& out) noexcept {
  if (data.size() > kMaxWords) return 0;
  out[0] = kReplyMagic;
  out[1] = static_cast<std::uint8_t>(status);
  out[2] = seq;
  put16(&out[3], static_cast<std::uint16_t>(data.size()));
  std::size_t at = kReplyHeaderBytes;
  for (const std::uint32_t w : data) {
    put32(&out[at], w);
    at += 4;
  }
  return seal(out, at);
}

DecodeError decode_reply(std::span<const std::uint8_t> in, std::uint8_t expected_op, std::uint8_t& seq,
                         hal::HalStatus& status, std::span<std::uint32_t> data) noexcept {
  if (in.size() < kReplyHeaderBytes + kCrcBytes) return DecodeError::short_frame;
  if (in[0] != kReplyMagic) return DecodeError::bad_magic;
  if (!crc_ok(in)) return DecodeError::bad_crc;
  if (!is_status(in[1])) return DecodeError::bad_op;
  status = static_cast<hal::HalStatus>(in[1]);
  seq = in[2];
  const std::uint16_t count = get16(&in[3]);
  const bool carries_data = expected_op == kOpRead && status == hal::HalStatus::ok;
  if (carries_data && count != data.size()) return DecodeError::bad_count;
  if (!carries_data && count != 0) return DecodeError::bad_count;
  if (in.size() != kReplyHeaderBytes + 4u * count + kCrcBytes) return DecodeError::bad_length;
  for (std::size_t i = 0; i < count; ++i) data[i] = get32(&in[kReplyHeaderBytes + 4 * i]);
  return DecodeError::none;
}

}  // namespace tnv::drivers::regwire
