#pragma once
// hal::RegisterBus over Linux spidev (/dev/spidevB.C), framed as in
// register_frame.hpp. One full-duplex transfer per request: the host
// clocks out the request, kTurnaroundBytes of zeros while the FPGA
// executes it, then zeros while the FPGA shifts out the reply; the reply is
// taken from the receive buffer after request + turnaround. SPI mode 0,
// 8-bit words, MSB first. Untested against hardware in this tree (no
// board here): the framing it sends is the one the Unix-socket transport
// and its tests use.
#include <cstdint>
#include <memory>
#include <string>

#include "drivers/linux/register_frame.hpp"
#include "hal/register_bus.hpp"

namespace tnv::drivers {

struct SpidevOptions {
  std::string device = "/dev/spidev0.0";
  std::uint32_t speed_hz = 10'000'000;
};

class SpidevRegisterBus final : public hal::RegisterBus {
 public:
  static constexpr std::size_t kTurnaroundBytes = 4;

  static std::unique_ptr<SpidevRegisterBus> open(const SpidevOptions& options, std::string& error);
  ~SpidevRegisterBus() override;
  SpidevRegisterBus(const SpidevRegisterBus&) = delete;
  SpidevRegisterBus& operator=(const SpidevRegisterBus&) = delete;

  hal::HalStatus read_block(std::uint16_t first_word, std::span<std::uint32_t> out) noexcept override;
  hal::HalStatus write_block(std::uint16_t first_word, std::span<const std::uint32_t> in) noexcept override;

 private:
  SpidevRegisterBus(int fd, std::uint32_t speed_hz) noexcept : fd_(fd), speed_hz_(speed_hz) {}
  hal::HalStatus transfer(std::size_t request_bytes, std::uint8_t op, std::uint16_t count,
                          std::span<std::uint32_t> read_out) noexcept;

  int fd_;
  std::uint32_t speed_hz_;
  std::uint8_t seq_ = 0;
  std::array<std::uint8_t, 2 * regwire::kMaxFrameBytes + kTurnaroundBytes> tx_{};
  std::array<std::uint8_t, 2 * regwire::kMaxFrameBytes + kTurnaroundBytes> rx_{};
  regwire::FrameBuffer frame_{};
};

}  // namespace tnv::drivers
