#include "drivers/linux/socket_register_bus.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>

#include "drivers/linux/unix_seqpacket.hpp"

namespace tnv::drivers {

namespace {

std::int64_t now_ms() noexcept {
  timespec ts{};
  ::clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000 + ts.tv_nsec / 1'000'000;
}

void add(std::atomic<std::uint64_t>& c) noexcept { c.fetch_add(1, std::memory_order_relaxed); }

}  // namespace

std::unique_ptr<SocketRegisterBus> SocketRegisterBus::connect(const std::string& path, int connect_timeout_ms,
                                                              int reply_timeout_ms, std::string& error) {
  const int fd = connect_seqpacket(path, connect_timeout_ms, error);
  if (fd < 0) return nullptr;
  return std::make_unique<SocketRegisterBus>(fd, reply_timeout_ms);
}

SocketRegisterBus::~SocketRegisterBus() {
  if (fd_ >= 0) ::close(fd_);
}

hal::HalStatus SocketRegisterBus::read_block(std::uint16_t first_word, std::span<std::uint32_t> out) noexcept {
  if (out.size() > regwire::kMaxWords) return hal::HalStatus::bad_address;
  const std::size_t n = regwire::encode_read_request(++seq_, first_word, static_cast<std::uint16_t>(out.size()), tx_);
  if (n == 0) return hal::HalStatus::bad_address;
  return transact(n, regwire::kOpRead, out);
}

hal::HalStatus SocketRegisterBus::write_block(std::uint16_t first_word, std::span<const std::uint32_t> in) noexcept {
  const std::size_t n = regwire::encode_write_request(++seq_, first_word, in, tx_);
  if (n == 0) return hal::HalStatus::bad_address;
  return transact(n, regwire::kOpWrite, {});
}

hal::HalStatus SocketRegisterBus::transact(std::size_t request_bytes, std::uint8_t op,
                                           std::span<std::uint32_t> read_out) noexcept {
  add(transfers_);
  if (fd_ < 0) return hal::HalStatus::not_present;
  ssize_t sent;
  do {
    sent = ::send(fd_, tx_.data(), request_bytes, MSG_NOSIGNAL);
  } while (sent < 0 && errno == EINTR);
  if (sent != static_cast<ssize_t>(request_bytes)) {
    add(link_errors_);
    return hal::HalStatus::not_present;
  }
  const std::int64_t deadline_ms = now_ms() + reply_timeout_ms_;
  for (;;) {
    const std::int64_t left_ms = deadline_ms - now_ms();
    if (left_ms <= 0) {
      add(timeouts_);
      return hal::HalStatus::timeout;
    }
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left_ms));
    if (ready < 0 && errno == EINTR) continue;
    if (ready < 0) {
      add(link_errors_);
      return hal::HalStatus::bus_error;
    }
    if (ready == 0) continue;  // the deadline check above reports the timeout
    const ssize_t got = ::recv(fd_, rx_.data(), rx_.size(), 0);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) {
      add(link_errors_);
      return hal::HalStatus::not_present;  // peer closed or the link failed
    }
    if (got >= 3 && rx_[0] == regwire::kReplyMagic && rx_[2] != seq_) {
      add(stale_replies_);  // the answer to a request that already timed out
      continue;
    }
    std::uint8_t seq = 0;
    hal::HalStatus status = hal::HalStatus::ok;
    const regwire::DecodeError e =
        regwire::decode_reply({rx_.data(), static_cast<std::size_t>(got)}, op, seq, status, read_out);
    if (e != regwire::DecodeError::none) {
      add(frame_errors_);
      return hal::HalStatus::bus_error;
    }
    return status;
  }
}

RegisterLinkCounters SocketRegisterBus::counters() const noexcept {
  auto get = [](const std::atomic<std::uint64_t>& c) { return c.load(std::memory_order_relaxed); };
  return {get(transfers_), get(timeouts_), get(frame_errors_), get(stale_replies_), get(link_errors_)};
}

}  // namespace tnv::drivers
