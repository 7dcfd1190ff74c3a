#include "drivers/linux/spidev_register_bus.hpp"

#include <fcntl.h>
#include <linux/spi/spidev.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace tnv::drivers {

std::unique_ptr<SpidevRegisterBus> SpidevRegisterBus::open(const SpidevOptions& options, std::string& error) {
  const int fd = ::open(options.device.c_str(), O_RDWR | O_CLOEXEC);
  auto fail = [&](const char* step) {
    error = options.device;
    error.append(": ").append(step).append(": ").append(std::strerror(errno));
    if (fd >= 0) ::close(fd);
    return nullptr;
  };
  if (fd < 0) return fail("cannot open");
  std::uint8_t mode = SPI_MODE_0;
  std::uint8_t bits = 8;
  std::uint32_t speed = options.speed_hz;
  if (::ioctl(fd, SPI_IOC_WR_MODE, &mode) < 0) return fail("cannot set SPI mode 0");
  if (::ioctl(fd, SPI_IOC_WR_BITS_PER_WORD, &bits) < 0) return fail("cannot set 8-bit words");
  if (::ioctl(fd, SPI_IOC_WR_MAX_SPEED_HZ, &speed) < 0) return fail("cannot set the clock");
  return std::unique_ptr<SpidevRegisterBus>(new SpidevRegisterBus(fd, options.speed_hz));
}

SpidevRegisterBus::~SpidevRegisterBus() { ::close(fd_); }

hal::HalStatus SpidevRegisterBus::read_block(std::uint16_t first_word, std::span<std::uint32_t> out) noexcept {
  if (out.empty() || out.size() > regwire::kMaxWords) return hal::HalStatus::bad_address;
  const auto count = static_cast<std::uint16_t>(out.size());
  const std::size_t n = regwire::encode_read_request(++seq_, first_word, count, frame_);
  return transfer(n, regwire::kOpRead, count, out);
}

hal::HalStatus SpidevRegisterBus::write_block(std::uint16_t first_word, std::span<const std::uint32_t> in) noexcept {
  const std::size_t n = regwire::encode_write_request(++seq_, first_word, in, frame_);
  if (n == 0) return hal::HalStatus::bad_address;
  return transfer(n, regwire::kOpWrite, static_cast<std::uint16_t>(in.size()), {});
}

hal::HalStatus SpidevRegisterBus::transfer(std::size_t request_bytes, std::uint8_t op, std::uint16_t count,
                                           std::span<std::uint32_t> read_out) noexcept {
  const std::size_t reply = regwire::reply_bytes(op, count);
  const std::size_t total = request_bytes + kTurnaroundBytes + reply;
  std::fill(tx_.begin(), tx_.begin() + static_cast<std::ptrdiff_t>(total), std::uint8_t{0});
  std::copy(frame_.begin(), frame_.begin() + static_cast<std::ptrdiff_t>(request_bytes), tx_.begin());
  spi_ioc_transfer t{};
  t.tx_buf = reinterpret_cast<std::uintptr_t>(tx_.data());
  t.rx_buf = reinterpret_cast<std::uintptr_t>(rx_.data());
  t.len = static_cast<std::uint32_t>(total);
  t.speed_hz = speed_hz_;
  t.bits_per_word = 8;
  if (::ioctl(fd_, SPI_IOC_MESSAGE(1), &t) < 0) return hal::HalStatus::bus_error;
  std::uint8_t seq = 0;
  hal::HalStatus status = hal::HalStatus::ok;
  const std::span<const std::uint8_t> answer(rx_.data() + request_bytes + kTurnaroundBytes, reply);
  // A board that answers only with the short error reply: try that length too.
  regwire::DecodeError e = regwire::decode_reply(answer, op, seq, status, read_out);
  if (e != regwire::DecodeError::none && reply != regwire::reply_bytes(regwire::kOpWrite, 0)) {
    e = regwire::decode_reply(answer.first(regwire::reply_bytes(regwire::kOpWrite, 0)), op, seq, status, read_out);
    if (e == regwire::DecodeError::none && status == hal::HalStatus::ok) return hal::HalStatus::bus_error;
  }
  if (e != regwire::DecodeError::none || seq != seq_) return hal::HalStatus::bus_error;
  return status;
}

}  // namespace tnv::drivers
