#include "drivers/linux/register_server.hpp"

#include <poll.h>
#include <sys/socket.h>

#include <array>
#include <cerrno>

namespace tnv::drivers {

std::size_t answer_register_request(std::span<const std::uint8_t> request, hal::RegisterBus& target,
                                    regwire::FrameBuffer& reply) noexcept {
  regwire::Request r;
  if (regwire::decode_request(request, r) != regwire::DecodeError::none) {
    const std::uint8_t seq = request.size() >= 3 ? request[2] : 0;
    return regwire::encode_reply(seq, hal::HalStatus::bus_error, {}, reply);
  }
  if (r.op == regwire::kOpRead) {
    std::array<std::uint32_t, regwire::kMaxWords> words{};
    const std::span<std::uint32_t> out(words.data(), r.count);
    const hal::HalStatus status = target.read_block(r.first_word, out);
    return regwire::encode_reply(r.seq, status, status == hal::HalStatus::ok ? std::span<const std::uint32_t>(out)
                                                                              : std::span<const std::uint32_t>{},
                                 reply);
  }
  const hal::HalStatus status = target.write_block(r.first_word, {r.data.data(), r.count});
  return regwire::encode_reply(r.seq, status, {}, reply);
}

ServeEnd serve_register_connection(int fd, hal::RegisterBus& target, int stop_fd, ServeStats& stats) noexcept {
  regwire::FrameBuffer in{};
  regwire::FrameBuffer out{};
  for (;;) {
    std::array<pollfd, 2> p{pollfd{fd, POLLIN, 0}, pollfd{stop_fd, POLLIN, 0}};
    const int ready = ::poll(p.data(), stop_fd >= 0 ? 2 : 1, -1);
    if (ready < 0) {
      if (errno == EINTR) continue;
      return ServeEnd::link_error;
    }
    if (stop_fd >= 0 && (p[1].revents & POLLIN) != 0) return ServeEnd::stopped;
    if ((p[0].revents & (POLLIN | POLLHUP | POLLERR)) == 0) continue;
    const ssize_t got = ::recv(fd, in.data(), in.size(), 0);
    if (got < 0 && errno == EINTR) continue;
    if (got == 0) return ServeEnd::peer_closed;
    if (got < 0) return errno == ECONNRESET ? ServeEnd::peer_closed : ServeEnd::link_error;
    ++stats.requests;
    regwire::Request probe;
    if (regwire::decode_request({in.data(), static_cast<std::size_t>(got)}, probe) != regwire::DecodeError::none) {
      ++stats.bad_requests;
    }
    const std::size_t n = answer_register_request({in.data(), static_cast<std::size_t>(got)}, target, out);
    if (::send(fd, out.data(), n, MSG_NOSIGNAL) != static_cast<ssize_t>(n)) {
      return errno == EPIPE || errno == ECONNRESET ? ServeEnd::peer_closed : ServeEnd::link_error;
    }
  }
}

}  // namespace tnv::drivers
