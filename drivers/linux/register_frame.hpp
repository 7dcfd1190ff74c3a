#pragma once
// The register transport's framing (docs/register-map.md, "Transport"):
// one request, one reply, each protected by a CRC-32. The same bytes go
// over spidev to the board's FPGA and over a Unix SOCK_SEQPACKET socket to
// the board-emulator process.
//
//   request: A5 | op (1 read, 2 write) | seq | word address (u16) | count (u16)
//            | count x u32 data (write only) | CRC-32 of everything before
//   reply:   5A | status (hal::HalStatus) | seq | count (u16)
//            | count x u32 data (read with status ok only) | CRC-32
//
// Little-endian throughout. count is 1..kMaxWords. Encoding and decoding
// work on fixed buffers: nothing allocates, so the tick may use them.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "hal/status.hpp"

namespace tnv::drivers::regwire {

inline constexpr std::uint8_t kRequestMagic = 0xA5;
inline constexpr std::uint8_t kReplyMagic = 0x5A;
inline constexpr std::uint8_t kOpRead = 1;
inline constexpr std::uint8_t kOpWrite = 2;
inline constexpr std::size_t kMaxWords = 64;
inline constexpr std::size_t kRequestHeaderBytes = 7;
inline constexpr std::size_t kReplyHeaderBytes = 5;
inline constexpr std::size_t kCrcBytes = 4;
inline constexpr std::size_t kMaxFrameBytes = kRequestHeaderBytes + 4 * kMaxWords + kCrcBytes;

using FrameBuffer = std::array<std::uint8_t, kMaxFrameBytes>;

// CRC-32 (IEEE 802.3, reflected, init and xor-out 0xFFFFFFFF): check value
// of "123456789" is 0xCBF43926.
std::uint32_t crc32(std::span<const std::uint8_t> bytes) noexcept;

struct Request {
  std::uint8_t op = kOpRead;
  std::uint8_t seq = 0;
  std::uint16_t first_word = 0;
  std::uint16_t count = 0;
  std::array<std::uint32_t, kMaxWords> data{};  // write data (count words)
};

// Bytes written to `out`, 0 when count is 0 or above kMaxWords.
std::size_t encode_read_request(std::uint8_t seq, std::uint16_t first_word, std::uint16_t count, FrameBuffer& out) noexcept;
std::size_t encode_write_request(std::uint8_t seq, std::uint16_t first_word, std::span<const std::uint32_t> data,
                                 FrameBuffer& out) noexcept;
// Length of the reply a request expects.
std::size_t reply_bytes(std::uint8_t op, std::uint16_t count) noexcept;

enum class DecodeError : std::uint8_t { none = 0, short_frame, bad_magic, bad_op, bad_count, bad_length, bad_crc };
const char* to_string(DecodeError e) noexcept;

DecodeError decode_request(std::span<const std::uint8_t> in, Request& out) noexcept;

// A reply with data (read ok) or without (write, or any error status).
std::size_t encode_reply(std::uint8_t seq, hal::HalStatus status, std::span<const std::uint32_t> data,
                         FrameBuffer& out) noexcept;
// Checks framing, CRC and that the reply carries `expected_seq`; copies read
// data into `data` (whose size must be the request's count). `status` is
// the board's answer.
DecodeError decode_reply(std::span<const std::uint8_t> in, std::uint8_t expected_op, std::uint8_t& seq,
                         hal::HalStatus& status, std::span<std::uint32_t> data) noexcept;

}  // namespace tnv::drivers::regwire
