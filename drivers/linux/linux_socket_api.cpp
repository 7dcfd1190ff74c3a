// The SocketApi on the Linux kernel: one system call per method.
#include <fcntl.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>

#include "drivers/linux/socket_api.hpp"

namespace tnv::drivers {

namespace {

class LinuxSocketApi final : public SocketApi {
 public:
  SysResult open_can_raw() override { return result_of(::socket(PF_CAN, SOCK_RAW, CAN_RAW)); }

  SysResult interface_index(const std::string& name) override {
    const unsigned index = ::if_nametoindex(name.c_str());
    if (index == 0) return {-1, errno};
    return {static_cast<long>(index), 0};
  }

  SysResult set_filters(int fd, std::span<const can_filter> filters) override {
    return result_of(::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, filters.data(),
                                  static_cast<socklen_t>(filters.size_bytes())));
  }

  SysResult set_error_mask(int fd, can_err_mask_t mask) override {
    return result_of(::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_ERR_FILTER, &mask, sizeof mask));
  }

  SysResult set_send_buffer(int fd, int bytes) override {
    return result_of(::setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &bytes, sizeof bytes));
  }

  SysResult set_nonblocking(int fd) override {
    const int flags = ::fcntl(fd, F_GETFL, 0);
    if (flags < 0) return {-1, errno};
    return result_of(::fcntl(fd, F_SETFL, flags | O_NONBLOCK));
  }

  SysResult bind_can(int fd, int ifindex) override {
    sockaddr_can addr{};
    addr.can_family = AF_CAN;
    addr.can_ifindex = ifindex;
    return result_of(::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr));
  }

  SysResult poll_one(int fd, short events, int timeout_ms) override {
    pollfd p{fd, events, 0};
    const int n = ::poll(&p, 1, timeout_ms);
    if (n < 0) return {-1, errno};
    return {n == 0 ? 0 : static_cast<long>(p.revents), 0};
  }

  SysResult read_some(int fd, void* buffer, std::size_t size) override { return result_of(::read(fd, buffer, size)); }

  SysResult write_some(int fd, const void* buffer, std::size_t size) override {
    return result_of(::write(fd, buffer, size));
  }

  void close_fd(int fd) override { ::close(fd); }

  Micros monotonic_now() override {
    return std::chrono::duration_cast<Micros>(std::chrono::steady_clock::now().time_since_epoch());
  }
};

}  // namespace

SocketApi& linux_socket_api() {
  static LinuxSocketApi api;
  return api;
}

}  // namespace tnv::drivers
