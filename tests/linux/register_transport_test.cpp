// The register transport: framing, CRC, and a round trip from the
// firmware-side bus to an in-process board server over a socketpair.
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <map>
#include <thread>
#include <vector>

#include "drivers/linux/register_frame.hpp"
#include "drivers/linux/register_server.hpp"
#include "drivers/linux/socket_register_bus.hpp"

namespace tnv {
namespace {

namespace rw = drivers::regwire;

// A board with registers 0x000..0x03F; anything above is unmapped.
class FakeBoard final : public hal::RegisterBus {
 public:
  std::array<std::uint32_t, 0x40> words{};
  hal::HalStatus read_block(std::uint16_t first, std::span<std::uint32_t> out) noexcept override {
    if (first + out.size() > words.size()) return hal::HalStatus::bad_address;
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = words[first + i];
    return hal::HalStatus::ok;
  }
  hal::HalStatus write_block(std::uint16_t first, std::span<const std::uint32_t> in) noexcept override {
    if (first + in.size() > words.size()) return hal::HalStatus::bad_address;
    for (std::size_t i = 0; i < in.size(); ++i) words[first + i] = in[i];
    return hal::HalStatus::ok;
  }
};

TEST(RegisterFrame, Crc32HasTheStandardCheckValue) {
  const std::string text = "123456789";
  EXPECT_EQ(rw::crc32({reinterpret_cast<const std::uint8_t*>(text.data()), text.size()}), 0xCBF43926u);
}

TEST(RegisterFrame, AWriteRequestDecodesToWhatWasEncoded) {
  rw::FrameBuffer buf{};
  const std::array<std::uint32_t, 3> data{0xDEADBEEF, 1, 0x80000000};
  const std::size_t n = rw::encode_write_request(7, 0x20, data, buf);
  ASSERT_EQ(n, rw::kRequestHeaderBytes + 12 + rw::kCrcBytes);
  rw::Request r;
  ASSERT_EQ(rw::decode_request({buf.data(), n}, r), rw::DecodeError::none);
  EXPECT_EQ(r.op, rw::kOpWrite);
  EXPECT_EQ(r.seq, 7);
  EXPECT_EQ(r.first_word, 0x20);
  ASSERT_EQ(r.count, 3);
  EXPECT_EQ(r.data[0], 0xDEADBEEFu);
  EXPECT_EQ(r.data[2], 0x80000000u);
}

TEST(RegisterFrame, EveryFlippedBitIsCaughtAndBadShapesAreNamed) {
  rw::FrameBuffer buf{};
  const std::size_t n = rw::encode_read_request(1, 0x10, 8, buf);
  for (std::size_t byte = 1; byte < n; ++byte) {
    for (int bit = 0; bit < 8; ++bit) {
      rw::FrameBuffer bad = buf;
      bad[byte] ^= static_cast<std::uint8_t>(1u << bit);
      rw::Request r;
      EXPECT_NE(rw::decode_request({bad.data(), n}, r), rw::DecodeError::none) << "byte " << byte << " bit " << bit;
    }
  }
  rw::Request r;
  EXPECT_EQ(rw::decode_request({buf.data(), 5}, r), rw::DecodeError::short_frame);
  EXPECT_EQ(rw::encode_read_request(1, 0, 0, buf), 0u);
  EXPECT_EQ(rw::encode_read_request(1, 0, rw::kMaxWords + 1, buf), 0u);
}

TEST(RegisterFrame, AReplyForAnotherOperationShapeIsRefused) {
  rw::FrameBuffer buf{};
  const std::array<std::uint32_t, 2> data{5, 6};
  const std::size_t n = rw::encode_reply(3, hal::HalStatus::ok, data, buf);
  std::array<std::uint32_t, 2> out{};
  std::uint8_t seq = 0;
  hal::HalStatus status = hal::HalStatus::bus_error;
  ASSERT_EQ(rw::decode_reply({buf.data(), n}, rw::kOpRead, seq, status, out), rw::DecodeError::none);
  EXPECT_EQ(out[1], 6u);
  EXPECT_EQ(seq, 3);
  std::array<std::uint32_t, 3> wrong_count{};
  EXPECT_EQ(rw::decode_reply({buf.data(), n}, rw::kOpRead, seq, status, wrong_count), rw::DecodeError::bad_count);
  EXPECT_EQ(rw::decode_reply({buf.data(), n}, rw::kOpWrite, seq, status, {}), rw::DecodeError::bad_count);
}

TEST(RegisterFrame, AnUndecodableRequestIsAnsweredWithABusErrorNotSilence) {
  FakeBoard board;
  rw::FrameBuffer req{};
  const std::size_t n = rw::encode_read_request(9, 0, 1, req);
  req[n - 1] ^= 0xFF;  // break the CRC
  rw::FrameBuffer reply{};
  const std::size_t m = drivers::answer_register_request({req.data(), n}, board, reply);
  std::uint8_t seq = 0;
  hal::HalStatus status = hal::HalStatus::ok;
  ASSERT_EQ(rw::decode_reply({reply.data(), m}, rw::kOpRead, seq, status, {}), rw::DecodeError::none);
  EXPECT_EQ(status, hal::HalStatus::bus_error);
  EXPECT_EQ(seq, 9);
}

// One end of a socketpair served by a thread, the other driven by the firmware's bus.
struct ServedPair {
  FakeBoard board;
  std::unique_ptr<drivers::SocketRegisterBus> bus;
  std::thread server;
  int server_fd = -1;
  drivers::ServeStats stats;
  drivers::ServeEnd end = drivers::ServeEnd::link_error;

  ServedPair() {
    int fds[2];
    EXPECT_EQ(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, fds), 0);
    server_fd = fds[1];
    bus = std::make_unique<drivers::SocketRegisterBus>(fds[0], 1000);
    server = std::thread([this] { end = drivers::serve_register_connection(server_fd, board, -1, stats); });
  }
  // Closing the client ends the server's loop (peer closed); joined here.
  void finish() {
    bus.reset();
    server.join();
    ::close(server_fd);
  }
};

TEST(SocketRegisterBus, ReadsAndWritesRoundTripThroughTheBoardServer) {
  ServedPair pair;
  const std::array<std::uint32_t, 4> written{0x800, 0x7FF, 3, 0x4B49434B};
  ASSERT_EQ(pair.bus->write_block(0x20, written), hal::HalStatus::ok);
  std::array<std::uint32_t, 4> read{};
  ASSERT_EQ(pair.bus->read_block(0x20, read), hal::HalStatus::ok);
  EXPECT_EQ(read, written);
  std::array<std::uint32_t, 2> beyond{};
  EXPECT_EQ(pair.bus->read_block(0x3F, beyond), hal::HalStatus::bad_address) << "the board's refusal comes back";
  const drivers::RegisterLinkCounters c = pair.bus->counters();
  pair.finish();
  EXPECT_EQ(pair.end, drivers::ServeEnd::peer_closed);
  EXPECT_EQ(pair.stats.requests, 3u);
  EXPECT_EQ(pair.stats.bad_requests, 0u);
  EXPECT_EQ(pair.board.words[0x23], 0x4B49434Bu);
  EXPECT_EQ(c.transfers, 3u);
  EXPECT_EQ(c.timeouts + c.frame_errors + c.link_errors, 0u);
}

TEST(SocketRegisterBus, ALateReplyToAnEarlierRequestIsDiscardedAndASilentBoardTimesOut) {
  int fds[2];
  ASSERT_EQ(::socketpair(AF_UNIX, SOCK_SEQPACKET, 0, fds), 0);
  drivers::SocketRegisterBus bus(fds[0], 30);
  std::array<std::uint32_t, 1> out{};
  EXPECT_EQ(bus.read_block(0x10, out), hal::HalStatus::timeout) << "nobody answers on the other end";
  // The board answers the timed-out request (seq 1) late, then the new one (seq 2).
  FakeBoard board;
  board.words[0x11] = 77;
  rw::FrameBuffer late{};
  ASSERT_GT(::recv(fds[1], late.data(), late.size(), 0), 0) << "the timed-out request reached the board";
  const std::array<std::uint32_t, 1> stale{99};
  const std::size_t n = rw::encode_reply(1, hal::HalStatus::ok, stale, late);
  ASSERT_EQ(::send(fds[1], late.data(), n, 0), static_cast<ssize_t>(n));
  std::thread server([&] {
    rw::FrameBuffer in{}, reply{};
    const ssize_t got = ::recv(fds[1], in.data(), in.size(), 0);
    const std::size_t m = drivers::answer_register_request({in.data(), static_cast<std::size_t>(got)}, board, reply);
    ::send(fds[1], reply.data(), m, 0);
  });
  EXPECT_EQ(bus.read_block(0x11, out), hal::HalStatus::ok);
  server.join();
  EXPECT_EQ(out[0], 77u) << "the stale value 99 must not be taken";
  EXPECT_EQ(bus.counters().stale_replies, 1u);
  EXPECT_EQ(bus.counters().timeouts, 1u);
  ::close(fds[1]);
  EXPECT_EQ(bus.read_block(0x11, out), hal::HalStatus::not_present) << "the board process went away";
}

}  // namespace
}  // namespace tnv
