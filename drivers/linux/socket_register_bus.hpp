#pragma once
// hal::RegisterBus over a connected Unix SOCK_SEQPACKET socket, framed as
// in register_frame.hpp: the firmware process's link to the
// board-emulator process (tnv-board-emu). One request, then poll() for
// its reply up to the reply timeout; a late reply of an earlier request
// (wrong sequence number) is discarded. No allocation per transfer.
#include <atomic>
#include <cstdint>
#include <memory>
#include <string>

#include "drivers/linux/register_frame.hpp"
#include "hal/register_bus.hpp"

namespace tnv::drivers {

struct RegisterLinkCounters {
  std::uint64_t transfers = 0;
  std::uint64_t timeouts = 0;
  std::uint64_t frame_errors = 0;  // bad CRC, magic, length
  std::uint64_t stale_replies = 0;
  std::uint64_t link_errors = 0;   // send/recv failed or the peer closed
};

class SocketRegisterBus final : public hal::RegisterBus {
 public:
  // Connects to a board server at `path` (retrying up to connect_timeout_ms).
  static std::unique_ptr<SocketRegisterBus> connect(const std::string& path, int connect_timeout_ms,
                                                    int reply_timeout_ms, std::string& error);
  // Takes ownership of a connected descriptor (tests: one end of a socketpair).
  SocketRegisterBus(int fd, int reply_timeout_ms) noexcept : fd_(fd), reply_timeout_ms_(reply_timeout_ms) {}
  ~SocketRegisterBus() override;
  SocketRegisterBus(const SocketRegisterBus&) = delete;
  SocketRegisterBus& operator=(const SocketRegisterBus&) = delete;

  hal::HalStatus read_block(std::uint16_t first_word, std::span<std::uint32_t> out) noexcept override;
  hal::HalStatus write_block(std::uint16_t first_word, std::span<const std::uint32_t> in) noexcept override;

  RegisterLinkCounters counters() const noexcept;

 private:
  hal::HalStatus transact(std::size_t request_bytes, std::uint8_t op, std::span<std::uint32_t> read_out) noexcept;

  int fd_;
  int reply_timeout_ms_;
  std::uint8_t seq_ = 0;
  regwire::FrameBuffer tx_{};
  regwire::FrameBuffer rx_{};
  std::atomic<std::uint64_t> transfers_{0}, timeouts_{0}, frame_errors_{0}, stale_replies_{0}, link_errors_{0};
};

}  // namespace tnv::drivers
